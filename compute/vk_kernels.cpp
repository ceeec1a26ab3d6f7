// Every kernel of engine/kernels/kernels.inc on Vulkan: one dispatch of shaders/<name>.comp with
// the kernel's layout as its push constants, its buffers bound as kernels.inc says
// (compute/vk_bindings.h) and its variant's specialisation constants (compute/vk_variants.h), or
// the backend's own run_own for the kernels listed in runs_own (vk_backend.h).
#include <type_traits>
#include <vector>

#include "compute/push_padding.h"
#include "compute/vk_backend.h"
#include "compute/vk_bindings.h"
#include "engine/kernels/kernel_body.h"
#include "engine/kernels/volume_math.h"
#include "shaders/spec_ids.h"

namespace masav::vk {
namespace {

// Every kernel run as one dispatch has a format for each of its texel bindings: no any_in
// buffer, whose format only its call knows.
static_assert([] {
  for (KernelId k : kAllKernels)
    for (const BufferBinding& b : kernel_bindings(k))
      if (!runs_own(k) && b.kind == BindingKind::texel &&
          b.texels.format == ::vk::Format::eUndefined)
        return false;
  return true;
}());

void add(SpecConstants& c, uint32_t id, const std::optional<uint32_t>& v) {
  if (v) c.push_back({id, *v});
}
void add(SpecConstants& c, uint32_t id, const std::optional<bool>& v) {
  if (v) c.push_back({id, *v ? 1u : 0u});
}

}  // namespace

SpecConstants RaymarchVariant::constants() const {
  return {{kSpecRayModes, modes},
          {kSpecRayBrick, brick},
          {kSpecRayPow, pow_form},
          {kSpecVolumeQuads, quads ? 1u : 0u}};
}

SpecConstants SphVariant::constants() const {
  SpecConstants c;
  add(c, kSpecSphModel, model);
  add(c, kSpecSphCoopWalk, coop_walk);
  add(c, kSpecSphWallSplit, wall_split);
  add(c, kSpecSphReach, reach);
  add(c, kSpecSphImagesAfter, images_after);
  add(c, kSpecSphState, state);
  return c;
}

template <KernelId K, class Params, class... Buffers>
void VulkanBackend::run_kernel(const Params& p, uint64_t items, Buffers&... buffers) {
  if constexpr (runs_own(K)) {
    run_own(KernelArgs<K>{p, items, buffers...});
  } else {
    const auto& layout = device_params<float>(p, buffers...);
    using Layout = std::decay_t<decltype(layout)>;
    static_assert(sizeof(layout) <= 128, "push constants beyond the 128 bytes every device has");
    static_assert(sizeof...(Buffers) == kernel_bindings(K).size());
    const BufferImpl* const impls[] = {impl_of(buffers)...};
    // The kernel writes the buffers it takes by non-const reference or pointer (kernels.inc's
    // out, inout and opt_out), so a barrier goes only where a later command depends on it.
    const bool writes[] = {!std::is_const_v<std::remove_pointer_t<Buffers>>...};
    uint32_t written = 0;
    for (size_t i = 0; i < sizeof...(Buffers); ++i) written |= writes[i] ? 1u << i : 0u;
    if (const uint32_t limit = diag_limit(layout)) pending_diag_limit_ = limit;
    // The variant this call runs, filled here and only here.
    SpecConstants constants;
    std::shared_ptr<Allocation> extra;  // kernel_extra(K) (compute/vk_bindings.h)
    if constexpr (std::is_same_v<Layout, RaymarchLayout>) {
      extra = raymarch_quads(layout, *impls[0]);
      constants =
          RaymarchVariant{layout.bits & kRayModeFlags, (layout.bits >> kRayBrickShift) & 31u,
                          volume::pow_step_form(layout.step / layout.reference_step),
                          extra != nullptr}
              .constants();
      if (!extra) extra = alloc(*impls[1], "raymarch");  // unread: the quads' binding needs one
    }
    // sph_density and sph_forces: the pressure model, the cooperative walk, the split at the
    // walls, whether the call passes the neighbour state (its (x, rho | v, p / rho^2) records,
    // read by name from the call's arguments), and for each one switch of its own: a pipeline
    // each, none paying for the others. The DFSPH solves have the split alone.
    if constexpr (std::is_same_v<Layout, SphStepLayout<float>>) {
      SphVariant v;
      v.model = uint32_t(layout.model);
      v.coop_walk = sph_coop_walk_;
      v.wall_split = K == KernelId::sph_density ? sph_wall_split_.density : sph_wall_split_.others;
      v.state = KernelArgs<K>{p, items, buffers...}.neighbor_state != nullptr;
      if constexpr (K == KernelId::sph_density) v.reach = uint32_t(layout.reach);
      if constexpr (K == KernelId::sph_forces) v.images_after = sph_images_after_;
      constants = v.constants();
    }
    if constexpr (std::is_same_v<Layout, DfsphLayout<float>>)
      constants = SphVariant{.wall_split = sph_wall_split_.others}.constants();
    // The push constants as pushed: a copy with its padding zeroed (compute/push_padding.h).
    auto push = without_padding(layout);
    if constexpr (K == KernelId::sph_integrate) {
      // Captured, dt goes through the replay table, so that blocks differing only in dt
      // replay one recording (compute/vk_stream.h).
      static_assert(Stream::kNoSlot == kSphDtInline);
      push.dt_slot = stream_.capture_value(layout.dt);
      if (push.dt_slot != kSphDtInline) push.dt = 0;
      extra = stream_.value_table();
    }
    dispatch_kernel(K, impls, &push, sizeof(push), items, written, std::move(constants),
                    std::move(extra));
  }
}

#define MASAV_KERNEL(name, Params, items, ...) \
  MASAV_KERNEL_FORWARD(VulkanBackend, name, Params, __VA_ARGS__)
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

}  // namespace masav::vk
