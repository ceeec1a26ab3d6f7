// Pre-integrated transfer function: the GLSL twin of volume::tf_pos and volume::segment_mean
// (engine/kernels/volume_math.h, which describes the table). The including kernel declares
// `tf_integral[]`.
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

// The mean (emission, depth) over the values between a and b, in either order.
vec4 segment_mean(TfPos a, TfPos b) {
  TfPos f = a, e = b;
  if (b.k < a.k || (b.k == a.k && b.w < a.w)) {
    f = b;
    e = a;
  }
  const vec4 sf = tf_integral[3u * f.k];
  if (f.k == e.k) return sf;
  const vec4 se = tf_integral[3u * e.k];
  if (e.k == f.k + 1u) {
    const float wf = 1.0 - f.w;
    return (sf * wf + se * e.w) * (1.0 / (wf + e.w));
  }
  const vec4 sums = (tf_integral[3u * e.k + 1u] - tf_integral[3u * f.k + 1u]) +
                    (tf_integral[3u * e.k + 2u] - tf_integral[3u * f.k + 2u]);
  return (sums + se * e.w - sf * f.w) * (1.0 / (float(e.k - f.k) + e.w - f.w));
}
