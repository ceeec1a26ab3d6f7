#pragma once
// The tuning options of each backend and of the SPH simulation: the code-path choices whose best
// setting depends on the device, and the limits the tests lower. Every option defaults to
// `automatic`, which each backend resolves per device class (a CPU device -- the CPU reference
// or lavapipe -- or a GPU) as docs/backends.md states with the measurements behind it. A caller
// passes them in (BackendRequest::tuning); nothing in the engine reads them from the process
// environment. The command line fills them from `--tune key=value` (set_tuning), one syntax for
// every option: on | off | auto for a switch, a name for a choice, a whole number for a count.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace masav {

enum class Choice : uint8_t { automatic, on, off };

// `automatic_value` where the choice is automatic.
constexpr bool resolve(Choice c, bool automatic_value) {
  return c == Choice::automatic ? automatic_value : c == Choice::on;
}

// Which radix-sort scatter the Vulkan backend runs: the tiled one (any device) or the one over
// subgroup ballots (a fixed subgroup size and ballots needed). auto: subgroup on a CPU device.
enum class SortScatter : uint8_t { automatic, tiled, subgroup };
// How the Vulkan SPH kernels walk a particle's neighbour rows: cooperatively over the subgroup
// or each lane its own. auto: cooperative on a CPU device, per lane on a GPU.
enum class SphWalk : uint8_t { automatic, cooperative, lanes };

// The precision of the CPU backend's SPH kernels (sph_density, sph_forces and the DFSPH solves'
// sums, every pressure model): fp64, the reference every backend is checked against, or fp32 in
// SIMD loops (engine/cpu/cpu_sph_simd.h), cross-checked against it like a GPU. Buffers and the
// integrator stay fp64 either way. auto: fp64.
enum class CpuSphPrecision : uint8_t { automatic, fp64, fp32 };
// The instruction set of those fp32 loops: the same bits with each. auto: the widest present.
enum class CpuSphSimd : uint8_t { automatic, generic, avx2, avx512 };

struct CpuTuning {
  uint32_t threads = 0;  // worker threads; 0: automatic (the hardware's threads)
  CpuSphPrecision sph_precision = CpuSphPrecision::automatic;
  CpuSphSimd sph_simd = CpuSphSimd::automatic;
};

struct VulkanTuning {
  SortScatter sort_scatter = SortScatter::automatic;
  SphWalk sph_walk = SphWalk::automatic;
  // SPH walks split at the walls (a second copy without the wall images for subgroups with no
  // lane near a wall). auto: sph_density always, the others on a CPU device.
  Choice sph_wall_split = Choice::automatic;
  // sph_forces adds the wall images after its masked walk, not per neighbour inside it. auto: on
  // a GPU (decided by tools/gpu-report).
  Choice sph_images_after = Choice::automatic;
  // raymarch reads its volume four voxels to a texel. auto: on a CPU device.
  Choice raymarch_quads = Choice::automatic;
  // A recorded block of SPH steps is replayed where equal to an earlier recording. auto: on
  // (decided by tools/gpu-report).
  Choice replay = Choice::automatic;
  // Device limits lowered, never raised (0: the device's own), so that the refusal of a size too
  // large is tested the same on every device.
  uint64_t max_buffer_mib = 0;  // the largest buffer a kernel may bind
  uint64_t max_texels = 0;      // the most texels a uniform texel buffer may span
};

struct CudaTuning {
  // A block of SPH steps captured and launched as one CUDA graph. auto: off (decided by
  // tools/gpu-report).
  Choice graphs = Choice::automatic;
  // sph_forces adds the wall images in a walk of their own after the direct terms. auto: on
  // (decided by tools/gpu-report).
  Choice sph_images_after = Choice::automatic;
  // Wait for every kernel, so that a fault names its kernel (debugging only, never timings).
  bool sync_each_launch = false;
};

struct SphTuning {
  // sph_forces reads sph_density's packed neighbour state instead of four arrays (the same
  // bits). auto: on where it fits the memory budget (decided on GPUs by tools/gpu-report).
  Choice neighbor_state = Choice::automatic;
};

struct Tuning {
  CpuTuning cpu;
  VulkanTuning vulkan;
  CudaTuning cuda;
  SphTuning sph;
};

// One option as `--tune` and docs/backends.md name it.
struct TuningKey {
  std::string_view key;           // "vulkan.replay"
  std::string_view values;        // "auto, on or off"
  std::string_view automatic;     // what auto means, per device class
  std::string_view description;   // what it chooses
};
std::span<const TuningKey> tuning_keys();

// Applies one `key=value` assignment. Throws masav::Error naming the key, the value and the
// allowed values (or the list of keys) on anything else.
void set_tuning(Tuning& t, std::string_view assignment);
// The options that are not automatic (or zero), as `key=value` separated by spaces; "" if none.
std::string describe(const Tuning& t);

}  // namespace masav
