// Kay-Kajiya slab ray-box test (thesis Alg. 3.1): the GLSL twin of volume::slab in
// engine/kernels/volume_sample.h. Unrolled, with no loop: lavapipe runs a loop nested in a
// conditional at least once per pass of the enclosing loop even when every lane skips it, and
// counts that pass against its 65,535-iteration limit (raymarch was cut at 32,768 samples).
const float VOLUME_FAR = 1e30;

bool slab_axis(float o, float d, float lo, float hi, inout float t_near, inout float t_far) {
  if (d == 0.0) return !(o < lo || o > hi);
  float t1 = (lo - o) / d, t2 = (hi - o) / d;
  if (t1 > t2) {
    const float s = t1;
    t1 = t2;
    t2 = s;
  }
  if (t1 > t_near) t_near = t1;
  if (t2 < t_far) t_far = t2;
  return !(t_near > t_far);
}

bool slab(vec3 o, vec3 d, vec3 lo, vec3 hi, inout float t_near, inout float t_far) {
  return slab_axis(o.x, d.x, lo.x, hi.x, t_near, t_far) &&
         slab_axis(o.y, d.y, lo.y, hi.y, t_near, t_far) &&
         slab_axis(o.z, d.z, lo.z, hi.z, t_near, t_far);
}
