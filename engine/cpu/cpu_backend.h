#pragma once
// The CPU reference backend: the oracle the GPU backends are tested against. Float work runs in
// double precision (Real/Real4 buffers hold doubles); integer kernels define the exact answer.
// Multithreaded with a fixed pool; work runs eagerly, so finish() has nothing to wait for.
#include <chrono>
#include <memory>
#include <vector>

#include "engine/core/backend.h"
#include "engine/cpu/cpu_sph_lists.h"
#include "engine/cpu/thread_pool.h"

namespace masav::cpu {

class CpuBuffer : public BufferImpl {
 public:
  CpuBuffer(const DeviceApi* owner, ElemKind kind, size_t count, size_t bytes, std::string label);
  std::byte* data() { return reinterpret_cast<std::byte*>(storage_.data()); }
  const std::byte* data() const { return reinterpret_cast<const std::byte*>(storage_.data()); }
  template <class T>
  T* as() {
    return reinterpret_cast<T*>(storage_.data());
  }
  template <class T>
  const T* as() const {
    return reinterpret_cast<const T*>(storage_.data());
  }

 private:
  std::vector<double> storage_;  // 8-byte aligned for doubles, fine for 32-bit words
};

class CpuBackend final : public Backend {
 public:
  explicit CpuBackend(unsigned threads = default_cpu_threads());

  const Capabilities& caps() const override { return caps_; }
  std::unique_ptr<BufferImpl> create_buffer(ElemKind kind, size_t count,
                                            std::string_view label) override;
  void fill_u32(BufferImpl& dst, uint32_t value) override;
  void finish() override {}
  TimestampId timestamp() override;
  double timestamp_ns(TimestampId id) override;
  void reset_timestamps() override { stamps_.clear(); }

  // ---- demo point cloud
  void drift_points(const DriftParams& p, const Buffer<float>& start,
                    const Buffer<float>& direction, Buffer<Real4>& positions) override;

  void philox_u32(const PhiloxParams& p, Buffer<uint32_t>& out) override;
  void philox_uniform(const PhiloxParams& p, Buffer<float>& out) override;
  void radix_sort(const RadixSortParams& p, Buffer<uint32_t>& keys,
                  Buffer<uint32_t>* values) override;
  void grid_assign_cells(const GridParams& g, const Buffer<Real4>& positions,
                         Buffer<uint32_t>& cells, Buffer<uint32_t>& indices) override;
  void grid_cell_ranges(const GridParams& g, const Buffer<uint32_t>& sorted_cells,
                        Buffer<uint32_t>& cell_start, Buffer<uint32_t>& cell_end) override;
  void gather(const Buffer<uint32_t>& order, const BufferImpl& src, BufferImpl& dst) override;
  void grid_count_neighbors(const NeighborParams& p, const Buffer<Real4>& sorted_positions,
                            const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
                            Buffer<uint32_t>& counts) override;

  // ---- SPH fluid
  void sph_density(const SphStepParams& p, const SphDensityIO& io) override;
  void sph_forces(const SphStepParams& p, const SphForcesIO& io) override;
  void sph_integrate(const SphIntegrateParams& p, const SphIntegrateIO& io) override;

  // ---- electron cloud, nebula lighting, volume
  void orbital_sample(const OrbitalSampleParams& p, const Buffer<uint32_t>& tables,
                      Buffer<Real4>& positions) override;
  void cloud_density(const CloudDensityParams& p, const Buffer<uint32_t>& cell_start,
                     const Buffer<uint32_t>& cell_end, Buffer<Real>& density) override;
  void scatter_table(const ScatterTableParams& p, Buffer<Real>& table,
                     Buffer<uint32_t>& hits) override;
  void nebula_illuminate(const NebulaLightParams& p, const Buffer<Real4>& positions,
                         const Buffer<Real>& density, Buffer<Real>& illumination) override;
  void nebula_view(const NebulaLightParams& p, const Buffer<Real4>& positions,
                   const Buffer<Real>& density, const Buffer<Real>& table,
                   const Buffer<Real>& illumination, Buffer<Real>& light) override;
  void voxelize(const VoxelizeParams& p, const Buffer<Real4>& positions, const Buffer<Real>& light,
                Buffer<Real>& probability, Buffer<Real>& mean_light,
                Buffer<Real>& sample) override;
  void volume_bricks(const VolumeBrickParams& p, const Buffer<Real>& volume,
                     const Buffer<Real4>& tf, Buffer<Real4>& bricks) override;
  void raymarch(const RaymarchParams& p, const Buffer<Real>& volume, const Buffer<Real4>& tf,
                const Buffer<Real4>& bricks, Buffer<Real4>& image) override;

  ThreadPool& pool() { return pool_; }

 protected:
  void write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) override;
  void read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) override;
  void copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) override;

 private:
  CpuBuffer& own(BufferImpl& b, std::string_view kernel);
  const CpuBuffer& own(const BufferImpl& b, std::string_view kernel) const;
  // The SPH neighbour lists sph_density builds and sph_forces reuses (cpu_sph.cpp).
  SphListInputs sph_list_inputs(const SphStepParams& p, const SphGridView& grid, double h2,
                                const char* kernel) const;
  template <class Found>
  void build_sph_lists(const SphListInputs& in, size_t chunks, Found&& found);

  Capabilities caps_;
  ThreadPool pool_;
  SphNeighborLists sph_lists_;
  std::vector<double> sph_p_rho2_;  // sph_forces' p / rho^2 per particle, kept between calls
  std::vector<std::chrono::steady_clock::time_point> stamps_;
  std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
};

// Stable LSD radix sort on the host, parallel over contiguous chunks (shared by the CPU backend
// and the benchmark's reference row).
void radix_sort_host(ThreadPool& pool, uint32_t n, uint32_t key_bits, uint32_t* keys,
                     uint32_t* values);

}  // namespace masav::cpu
