// SPH kernels on CUDA, host side: the layouts computed once (device_params), then the launches
// in sph_kernels.cu.
#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/sph_launch.h"

namespace masav::cuda {
namespace {

using V4 = hd::V4<float>;

}  // namespace

void CudaBackend::run_own(const KernelArgs<KernelId::sph_density>& a) {
  auto& [p, items_, positions, cells, cell_start, cell_end, density, pressure, stats, velocities,
         neighbor_state, reach_rows, neighbor_rows] = a;
  const char* k = "sph_density";
  uint32_t* rows = neighbor_rows ? device_ptr<uint32_t>(*neighbor_rows, k) : nullptr;
  uint32_t* reach = reach_rows ? device_ptr<uint32_t>(*reach_rows, k) : nullptr;
  V4* state = neighbor_state ? device_ptr<V4>(*neighbor_state, k) : nullptr;
  const V4* vel = state ? device_ptr<V4>(*velocities, k) : nullptr;
  launched(launch::sph_density(stream_, grid_for_items(sph_range_count(p), k),
                               device_params<float>(p, neighbor_rows), device_ptr<V4>(positions, k),
                               device_ptr<uint32_t>(cells, k), device_ptr<uint32_t>(cell_start, k),
                               device_ptr<uint32_t>(cell_end, k), device_ptr<float>(density, k),
                               device_ptr<float>(pressure, k), device_ptr<uint32_t>(stats, k), vel,
                               state, reach, rows),
           k);
}

void CudaBackend::run_own(const KernelArgs<KernelId::sph_forces>& a) {
  auto& [p, items_, positions, velocities, density, pressure, cells, cell_start, cell_end, accel,
         stats, neighbor_state, neighbor_rows] = a;
  const char* k = "sph_forces";
  const uint32_t* rows = neighbor_rows ? device_ptr<uint32_t>(*neighbor_rows, k) : nullptr;
  const V4* state = neighbor_state ? device_ptr<V4>(*neighbor_state, k) : nullptr;
  launched(launch::sph_forces(stream_, grid_for_items(sph_range_count(p), k),
                              device_params<float>(p, neighbor_rows), device_ptr<V4>(positions, k),
                              device_ptr<V4>(velocities, k), device_ptr<float>(density, k),
                              device_ptr<float>(pressure, k), state, device_ptr<uint32_t>(cells, k),
                              device_ptr<uint32_t>(cell_start, k),
                              device_ptr<uint32_t>(cell_end, k), device_ptr<V4>(accel, k),
                              device_ptr<uint32_t>(stats, k), rows, sph_images_after_),
           k);
}

void CudaBackend::run_own(const KernelArgs<KernelId::sph_integrate>& a) {
  auto& [p, items_, x0, v0, vk, accel, x_out, v_out, sum_x, sum_v, stats] = a;
  const char* k = "sph_integrate";
  auto opt = [&](const Buffer<Real4>* b) { return b ? device_ptr<V4>(*b, k) : nullptr; };
  launched(launch::sph_integrate(stream_, grid_for_items(sph_range_count(p), k),
                                 device_params<float>(p), opt(x0), device_ptr<V4>(v0, k), opt(vk),
                                 device_ptr<V4>(accel, k), opt(x_out), device_ptr<V4>(v_out, k),
                                 opt(sum_x), opt(sum_v), device_ptr<uint32_t>(stats, k)),
           k);
}

}  // namespace masav::cuda
