// DFSPH kernels on CUDA, host side: the layout computed once (device_params), then the launches
// in dfsph_kernels.cu.
#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/dfsph_launch.h"

namespace masav::cuda {
namespace {

using V4 = hd::V4<float>;

}  // namespace

void CudaBackend::run_own(const KernelArgs<KernelId::dfsph_factor>& a) {
  auto& [p, items_, positions, cells, cell_start, cell_end, factor, stats, neighbor_rows] = a;
  const char* k = "dfsph_factor";
  const uint32_t* rows = neighbor_rows ? device_ptr<uint32_t>(*neighbor_rows, k) : nullptr;
  launched(
      launch::dfsph_factor(stream_, grid_for_items(sph_range_count(p.step), k),
                           device_params<float>(p, neighbor_rows), device_ptr<V4>(positions, k),
                           device_ptr<uint32_t>(cells, k), device_ptr<uint32_t>(cell_start, k),
                           device_ptr<uint32_t>(cell_end, k), device_ptr<float>(factor, k),
                           device_ptr<uint32_t>(stats, k), rows),
      k);
}

void CudaBackend::run_own(const KernelArgs<KernelId::dfsph_rate>& a) {
  auto& [p, items_, positions, velocities, density, factor, cells, cell_start, cell_end, kappa,
         kappa_sum, residual, neighbor_rows] = a;
  const char* k = "dfsph_rate";
  const uint32_t* rows = neighbor_rows ? device_ptr<uint32_t>(*neighbor_rows, k) : nullptr;
  launched(
      launch::dfsph_rate(stream_, grid_for_items(sph_range_count(p.step), k),
                         device_params<float>(p, neighbor_rows), device_ptr<V4>(positions, k),
                         device_ptr<V4>(velocities, k), device_ptr<float>(density, k),
                         device_ptr<float>(factor, k), device_ptr<uint32_t>(cells, k),
                         device_ptr<uint32_t>(cell_start, k), device_ptr<uint32_t>(cell_end, k),
                         device_ptr<float>(kappa, k), device_ptr<float>(kappa_sum, k),
                         device_ptr<uint32_t>(residual, k), rows),
      k);
}

void CudaBackend::run_own(const KernelArgs<KernelId::dfsph_correct>& a) {
  auto& [p, items_, positions, kappa, cells, cell_start, cell_end, velocities, stats, residual,
         neighbor_rows] = a;
  const char* k = "dfsph_correct";
  const uint32_t* rows = neighbor_rows ? device_ptr<uint32_t>(*neighbor_rows, k) : nullptr;
  const uint32_t* words = residual ? device_ptr<uint32_t>(*residual, k) : nullptr;
  launched(launch::dfsph_correct(
               stream_, grid_for_items(sph_range_count(p.step), k),
               device_params<float>(p, neighbor_rows), device_ptr<V4>(positions, k),
               device_ptr<float>(kappa, k), device_ptr<uint32_t>(cells, k),
               device_ptr<uint32_t>(cell_start, k), device_ptr<uint32_t>(cell_end, k),
               device_ptr<V4>(velocities, k), device_ptr<uint32_t>(stats, k), words, rows),
           k);
}

}  // namespace masav::cuda
