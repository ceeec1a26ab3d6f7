// Included first by every compute kernel: workgroup size and subgroup size as specialization
// constants, the diagnostics buffer (binding 0) and loop-iteration counting.
//
// lavapipe silently stops a shader invocation after 65,535 loop iterations in total. With
// COUNT_LOOP_TICKS set, every loop body calls LOOP_TICK() and the largest count any invocation
// reached lands in diag.max_loop_ticks, so a test can prove each kernel's worst case stays below.
#extension GL_KHR_shader_subgroup_basic : require
#include "shaders/spec_ids.h"  // the constants' ids, shared with the Vulkan backend

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(constant_id = kSpecWorkgroupSize) const uint WG_SIZE = 256u;
layout(constant_id = kSpecSubgroupMin) const uint SUBGROUP_MIN = 4u;  // smallest subgroup the device may use
layout(constant_id = kSpecCountLoopTicks) const bool COUNT_LOOP_TICKS = false;

layout(std430, set = 0, binding = 0) buffer Diagnostics {
  uint max_loop_ticks;
  uint flags;   // kDiag* bits (engine/kernels/grid_params.h)
  uint detail;  // smallest offending index
  uint reserved;
} diag;

uint g_loop_ticks = 0u;
#define LOOP_TICK()                \
  if (COUNT_LOOP_TICKS) {          \
    g_loop_ticks += 1u;            \
  }

void report_loop_ticks() {
  if (COUNT_LOOP_TICKS) atomicMax(diag.max_loop_ticks, g_loop_ticks);
}

void report_diagnostic(uint flag, uint detail) {
  atomicOr(diag.flags, flag);
  atomicMin(diag.detail, detail);
}

// Dispatches wider than maxComputeWorkGroupCount[0] spill into y.
uint flat_group_id() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }
uint flat_invocation_id() { return flat_group_id() * WG_SIZE + gl_LocalInvocationID.x; }
