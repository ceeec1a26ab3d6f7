// Workgroup-wide exclusive prefix sums built on subgroup scans, correct for any subgroup size
// and any mapping of invocations to subgroups: the order of the scan is (subgroup id, subgroup
// invocation id), and wg_rank() gives each invocation its dense position in that order, which
// kernels use to pick the elements they own. Needs kernel_base.glsl. Ends with a barrier, so
// shared memory read before a call may be overwritten after it.
#extension GL_KHR_shader_subgroup_arithmetic : require

const uint MAX_SUBGROUPS = WG_SIZE / SUBGROUP_MIN;
shared uvec2 s_scan_partials[MAX_SUBGROUPS];
shared uvec2 s_scan_total;

uvec2 wg_exclusive_scan2(uvec2 v, out uvec2 total) {
  const uvec2 inclusive = subgroupInclusiveAdd(v);
  const uvec2 subgroup_total = subgroupAdd(v);
  if (subgroupElect()) s_scan_partials[gl_SubgroupID] = subgroup_total;
  barrier();
  if (gl_LocalInvocationID.x == 0u) {
    uvec2 acc = uvec2(0u);
    for (uint s = 0u; s < gl_NumSubgroups; ++s) {
      LOOP_TICK();
      const uvec2 t = s_scan_partials[s];
      s_scan_partials[s] = acc;
      acc += t;
    }
    s_scan_total = acc;
  }
  barrier();
  const uvec2 result = s_scan_partials[gl_SubgroupID] + inclusive - v;
  total = s_scan_total;
  barrier();
  return result;
}

uint wg_exclusive_scan(uint v, out uint total) {
  uvec2 t;
  const uvec2 r = wg_exclusive_scan2(uvec2(v, 0u), t);
  total = t.x;
  return r.x;
}

// This invocation's position in the scan order, in [0, WG_SIZE).
uint wg_rank() {
  uint total;
  return wg_exclusive_scan(1u, total);
}
