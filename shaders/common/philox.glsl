// Philox4x32-10, the GLSL twin of engine/kernels/philox.h (bit-identical by construction and by
// test against the Random123 known answers).
const uint PHILOX_M0 = 0xD2511F53u, PHILOX_M1 = 0xCD9E8D57u;
const uint PHILOX_W0 = 0x9E3779B9u, PHILOX_W1 = 0xBB67AE85u;

uvec4 philox4x32_10(uvec4 ctr, uvec2 key) {
  for (int round = 0; round < 10; ++round) {
    LOOP_TICK();
    if (round > 0) key += uvec2(PHILOX_W0, PHILOX_W1);
    uint hi0, lo0, hi1, lo1;
    umulExtended(PHILOX_M0, ctr.x, hi0, lo0);
    umulExtended(PHILOX_M1, ctr.z, hi1, lo1);
    ctr = uvec4(hi1 ^ ctr.y ^ key.x, lo1, hi0 ^ ctr.w ^ key.y, lo0);
  }
  return ctr;
}

// Block (first_block + offset) of `stream` under `seed`; 64-bit values as (lo, hi) pairs.
uvec4 philox_stream_block(uvec2 seed, uvec2 stream, uvec2 first_block, uint offset) {
  uint carry;
  const uint lo = uaddCarry(first_block.x, offset, carry);
  return philox4x32_10(uvec4(lo, first_block.y + carry, stream.x, stream.y), seed);
}

// Uniform in [0, 1) from the top 24 bits, exact on every backend.
float philox_u01(uint word) { return float(word >> 8) * (1.0 / 16777216.0); }
