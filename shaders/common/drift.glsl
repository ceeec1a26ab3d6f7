// GLSL twin of engine/kernels/drift_body.h: the periodic drift of drift_points, in fp32 with one
// rounding per operation (`precise`).

float drift_axis_fraction(float u, float w, float speed_t) {
  precise float dir = 2.0 * w - 1.0;
  precise float f = u + dir * speed_t;
  precise float r = f - floor(f);
  return r < 1.0 ? r : 0.0;
}

float drift_axis_velocity(float w, float speed, float extent) {
  precise float v = ((2.0 * w - 1.0) * speed) * extent;
  return v;
}
