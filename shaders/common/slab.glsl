// Kay-Kajiya slab ray-box test (thesis Alg. 3.1): the GLSL twin of volume::slab in
// engine/atom/volume_math.h.
const float VOLUME_FAR = 1e30;

bool slab(vec3 o, vec3 d, vec3 lo, vec3 hi, inout float t_near, inout float t_far) {
  for (int a = 0; a < 3; ++a) {
    LOOP_TICK();
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    float t1 = (lo[a] - o[a]) / d[a], t2 = (hi[a] - o[a]) / d[a];
    if (t1 > t2) {
      const float s = t1;
      t1 = t2;
      t2 = s;
    }
    if (t1 > t_near) t_near = t1;
    if (t2 < t_far) t_far = t2;
    if (t_near > t_far) return false;
  }
  return true;
}
