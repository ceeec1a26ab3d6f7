// Pre-integrated transfer function: the GLSL twin of volume::tf_pos and volume::segment_mean
// (engine/kernels/volume_transfer.h, which describes the table). The including kernel defines
// `vec4 tf_integral_at(uint index)`.
struct TfPos {
  uint k;   // the piece, <= size - 2
  float w;  // where in it, [0, 1]
};

TfPos tf_pos(float v, uint size) {
  const float x = clamp(v, 0.0, 1.0) * float(size - 1u);
  uint k = uint(x);
  if (k > size - 2u) k = size - 2u;
  return TfPos(k, x - float(k));
}

// The mean (emission, depth) over the values between a and b, in either order: one piece (or
// close), neighbouring pieces, farther apart, as volume::segment_mean.
vec4 segment_mean(TfPos a, TfPos b) {
  TfPos f = a, e = b;
  if (b.k < a.k || (b.k == a.k && b.w < a.w)) {
    f = b;
    e = a;
  }
  const float len = float(e.k - f.k) + (e.w - f.w);
  if (e.k == f.k || len < 0.0625) {
    uint k = f.k;
    float w = f.w + 0.5 * len;
    if (w > 1.0) {  // the midpoint is in e's piece (only then can w pass 1)
      k = e.k;
      w -= 1.0;
    }
    return mix(tf_integral_at(3u * k), tf_integral_at(3u * k + 3u), w);
  }
  const vec4 p0 = tf_integral_at(3u * f.k), p1 = tf_integral_at(3u * f.k + 3u);
  const float inv = 1.0 / len;
  if (e.k == f.k + 1u) {
    const vec4 p2 = tf_integral_at(3u * e.k + 3u);
    return (mix(p0, p1, 0.5 * (1.0 + f.w)) * (1.0 - f.w) + mix(p1, p2, 0.5 * e.w) * e.w) * inv;
  }
  // The integral from entry k to k + w: w times the value at k + w/2.
  const vec4 pf = mix(p0, p1, 0.5 * f.w);
  const vec4 pe = mix(tf_integral_at(3u * e.k), tf_integral_at(3u * e.k + 3u), 0.5 * e.w);
  const vec4 sums = (tf_integral_at(3u * e.k + 1u) - tf_integral_at(3u * f.k + 1u)) +
                    (tf_integral_at(3u * e.k + 2u) - tf_integral_at(3u * f.k + 2u));
  return (sums + pe * e.w - pf * f.w) * inv;
}
