// Every kernel of engine/kernels/kernels.inc on Vulkan: one dispatch of shaders/<name>.comp with
// the kernel's layout as its push constants, or the backend's own run_own for the kernels listed in
// runs_own (vk_backend.h).
#include <type_traits>
#include <vector>

#include "compute/push_padding.h"
#include "compute/vk_backend.h"
#include "engine/kernels/kernel_body.h"
#include "engine/kernels/volume_math.h"

namespace masav::vk {
template <KernelId K, class Params, class... Buffers>
void VulkanBackend::run_kernel(const Params& p, uint64_t items, Buffers&... buffers) {
  if constexpr (runs_own(K)) {
    run_own(KernelArgs<K>{p, items, buffers...});
  } else {
    const auto& layout = device_params<float>(p, buffers...);
    static_assert(sizeof(layout) <= 128, "push constants beyond the 128 bytes every device has");
    const BufferImpl* const impls[] = {impl_of(buffers)...};
    // The kernel writes the buffers it takes by non-const reference or pointer (kernels.inc's
    // out, inout and opt_out), so a barrier goes only where a later command depends on it.
    const bool writes[] = {!std::is_const_v<std::remove_pointer_t<Buffers>>...};
    uint32_t written = 0;
    for (size_t i = 0; i < sizeof...(Buffers); ++i) written |= writes[i] ? 1u << i : 0u;
    if (const uint32_t limit = diag_limit(layout)) pending_diag_limit_ = limit;
    std::vector<uint32_t> constants;
    // raymarch is specialised on the flags that choose its code paths, on the brick size, on
    // the form of its opacity correction's power and on reading the volume as quads
    // (shaders/raymarch.comp): lavapipe runs a branch that no lane takes, loads and all, unless
    // the branch is compiled out, and divides by a brick size it does not know lane by lane. It
    // reads what it only reads as texel buffers: lavapipe fetches a texel with a gather, an element
    // of a storage buffer with a loop over the lanes.
    std::vector<Texels> texels;
    std::shared_ptr<Allocation> extra;  // bound after the kernel's buffers
    const Texels rgba32 = kTexelsRgba32f, r32f = kTexelsR32f, r32u = kTexelsR32u,
                 none = kStorageBuffer;
    if constexpr (std::is_same_v<std::decay_t<decltype(layout)>, RaymarchLayout>) {
      constants.push_back(layout.bits & kRayModeFlags);
      constants.push_back((layout.bits >> kRayBrickShift) & 31u);
      constants.push_back(volume::pow_step_form(layout.step / layout.reference_step));
      extra = raymarch_quads(layout, *impls[0]);
      constants.push_back(extra ? 1u : 0u);
      if (!extra) extra = alloc(*impls[1], "raymarch");  // unread: the quads' binding needs one
      // volume, tf, bricks, image, tf_integral; the quads
      texels = {r32f, rgba32, rgba32, none, rgba32, rgba32};
    }
    // sph_density and sph_forces are specialised on the pressure model (shaders/common/sph.glsl),
    // on whether rows are walked cooperatively (shaders/common/sph_coop.glsl) and on whether the
    // walks are split at the walls (shaders/common/sph_walk.glsl), and read their inputs as texel
    // buffers too. The DFSPH solves take the last alone (constants 3 and 4 are not theirs).
    if constexpr (std::is_same_v<std::decay_t<decltype(layout)>, SphStepLayout<float>>) {
      constants.push_back(uint32_t(layout.model));
      constants.push_back(sph_coop_walk_ ? 1u : 0u);
      const bool split =
          K == KernelId::sph_density ? sph_wall_split_.density : sph_wall_split_.others;
      constants.push_back(split ? 1u : 0u);
      // Whether the call passes the neighbour state (constant 7), its (x, rho | v, p / rho^2)
      // records, read by name from the call's arguments.
      const bool state = KernelArgs<K>{p, items, buffers...}.neighbor_state != nullptr;
      if constexpr (K == KernelId::sph_density) {  // positions, cells, cell_start, cell_end
        texels = {rgba32, r32u, r32u, r32u, none, none, none, rgba32, none, none, none};
        // How it uses the reach masks (constant 6): a pipeline each, none paying for the others.
        constants.push_back(uint32_t(layout.reach));
        constants.push_back(state ? 1u : 0u);
      }
      if constexpr (K == KernelId::sph_forces) {
        // ... velocities, density, pressure; the neighbour state, neighbor_rows
        texels = {rgba32, rgba32, r32f, r32f, r32u, r32u, r32u, none, none, rgba32, r32u};
        constants.push_back(sph_images_after_ ? 1u : 0u);  // the masked walk's wall images
        constants.push_back(state ? 1u : 0u);
      }
    }
    // The nebula kernels' paths through the density grid, the DFSPH solves' neighbour walks, the
    // grid build's passes and the SPH integrator read their inputs as texel buffers too.
    if constexpr (K == KernelId::grid_count_neighbors)  // positions, ranges; counts
      texels = {rgba32, r32u, r32u, none};
    if constexpr (K == KernelId::grid_assign_count)  // positions; cells, counts
      texels = {rgba32, none, none};
    if constexpr (K == KernelId::grid_scatter_cells)  // cells, cell_end; counts, unsorted
      texels = {r32u, r32u, none, none};
    if constexpr (K == KernelId::grid_rank_in_cell)  // cells, unsorted, ranges; sorted cells, index
      texels = {r32u, r32u, r32u, r32u, none, none};
    if constexpr (K == KernelId::grid_rank_and_move)  // as above; a, b and ids, each + sorted
      texels = {r32u, r32u, r32u, r32u, none, none, rgba32, none, rgba32, none, r32u, none};
    // The push constants as pushed: a copy with its padding zeroed (compute/push_padding.h).
    auto push = without_padding(layout);
    if constexpr (K == KernelId::sph_integrate) {  // x0, v0, vk, accel; outputs, sums, stats;
      texels = {rgba32, rgba32, rgba32, rgba32, none, none, none, none, none, none};  // dt table
      // Captured, dt goes through the replay table, so that blocks differing only in dt
      // replay one recording (compute/vk_stream.h).
      static_assert(Stream::kNoSlot == kSphDtInline);
      push.dt_slot = stream_.capture_value(layout.dt);
      if (push.dt_slot != kSphDtInline) push.dt = 0;
      extra = stream_.value_table();
    }
    if constexpr (K == KernelId::nebula_illuminate)  // positions, density; illumination
      texels = {rgba32, r32f, none};
    if constexpr (K == KernelId::nebula_view)  // positions, density, table, illumination; light
      texels = {rgba32, r32f, r32f, r32f, none};
    if constexpr (std::is_same_v<std::decay_t<decltype(layout)>, DfsphLayout<float>>)
      constants = {0u, 0u, sph_wall_split_.others ? 1u : 0u};
    if constexpr (K == KernelId::dfsph_factor)  // positions, cells, ranges; factor, stats; rows
      texels = {rgba32, r32u, r32u, r32u, none, none, r32u};
    if constexpr (K == KernelId::dfsph_rate)  // + velocities, density, factor; kappa, sums
      texels = {rgba32, rgba32, r32f, r32f, r32u, r32u, r32u, none, none, none, r32u};
    if constexpr (K == KernelId::dfsph_correct)  // positions, kappa, cells, ranges; v, stats;
      texels = {rgba32, r32f, r32u, r32u, r32u, none, none, r32u, r32u};  // residual, rows
    dispatch_kernel(K, impls, &push, sizeof(push), items, written, constants, texels, extra);
  }
}

#define MASAV_KERNEL(name, Params, items, ...) \
  MASAV_KERNEL_FORWARD(VulkanBackend, name, Params, __VA_ARGS__)
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

}  // namespace masav::vk
