#pragma once
// The CPU reference backend: the oracle the GPU backends are tested against. Float work runs in
// double precision (Real/Real4 buffers hold doubles); integer kernels define the exact answer.
// Multithreaded with a fixed pool; work runs eagerly, so finish() has nothing to wait for.
#include <chrono>
#include <memory>
#include <vector>

#include "engine/cpu/cpu_dfsph_terms.h"
#include "engine/cpu/cpu_sph_lists.h"
#include "engine/cpu/cpu_sph_simd.h"
#include "engine/cpu/thread_pool.h"
#include "engine/kernels/backend.h"
#include "engine/kernels/hd_vec.h"

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

// The precision the CPU backend renders the raymarch in: fp64, the reference every backend is
// checked against, or fp32, as a GPU renders it, for speed (its Real buffers stay fp64 either way).
enum class CpuRenderPrecision { fp64, fp32 };

class CpuBackend final : public Backend {
 public:
  explicit CpuBackend(unsigned threads = default_cpu_threads(),
                      CpuRenderPrecision render = CpuRenderPrecision::fp64,
                      const Tuning& tuning = {});

  const Capabilities& caps() const override { return caps_; }
  std::unique_ptr<BufferImpl> create_buffer(ElemKind kind, size_t count,
                                            std::string_view label) override;
  void fill_u32(BufferImpl& dst, uint32_t value) override;
  void finish() override {}
  TimestampId timestamp() override;
  double timestamp_ns(TimestampId id) override;
  void reset_timestamps() override { stamps_.clear(); }

  ThreadPool& pool() { return pool_; }
  // Whether the DFSPH solves read each pair's gradient back from DfsphTerms (the default, faster)
  // or recompute it on every call through the shared bodies CUDA runs: the tests' oracle that the
  // kept terms give the same bits.
  void set_dfsph_terms(bool on) { dfsph_terms_on_ = on; }

 protected:
#include "engine/kernels/backend_overrides.inc"

  void write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) override;
  void read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) override;
  void copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) override;

 private:
  CpuBuffer& own(BufferImpl& b, std::string_view kernel);
  const CpuBuffer& own(const BufferImpl& b, std::string_view kernel) const;
  // The SPH neighbour lists sph_density builds and sph_forces reuses (cpu_sph.cpp).
  SphListInputs sph_list_inputs(const SphStepParams& p, const Buffer<uint32_t>& cells,
                                const Buffer<uint32_t>& cell_start,
                                const Buffer<uint32_t>& cell_end, double h2,
                                const char* kernel) const;
  // In T: double, or float for the fp32 path (CpuTuning::sph_precision).
  template <class T, class Found>
  void build_sph_lists(const SphListInputs& in, size_t chunks, Found&& found,
                       const SphListReach& reach = {});
  // Whether the SPH kernels run in fp32 (CpuTuning::sph_precision): sph_density and
  // sph_forces in the SIMD pair loops (sph_simd_), their neighbour lists found in fp32, which
  // the DFSPH solves share; the solves then sum fp32 terms (DfsphTerms32) over fp32 velocities
  // and kappas.
  bool sph_in_fp32() const { return sph_simd_ != nullptr; }
  // What sph_forces reads and writes on either path; the neighbour lists made sure of first
  // (sph_density's where they match these positions and this grid, else new ones).
  struct SphForceBuffers {
    const double *pos, *vel, *rho, *pr;
    double* accel;
    uint32_t* stats;
    const hd::V4<double>* state;  // sph_density's neighbour state, or null
  };
  SphForceBuffers sph_force_buffers(const KernelArgs<KernelId::sph_forces>& a);
  void sph_forces_fp32(const KernelArgs<KernelId::sph_forces>& a);  // cpu_sph_fp32.cpp
  // The lists for `in` in sph_chunks(in.n) chunks: sph_density's where they match, else new.
  void ensure_sph_lists(const SphListInputs& in);
  size_t sph_chunks(uint32_t n) const;
  // The DFSPH pair terms of the current lists at `pos` in `terms` (cpu_dfsph.cpp): kept where
  // they match. True if built anew, then with each particle's factor in `factor` where given.
  bool ensure_dfsph_terms(DfsphTerms& terms, const double* pos, const DfsphLayout<double>& c,
                          double* factor = nullptr);
  // The same in fp32 into dfsph_terms32_ (the fp32 path).
  bool ensure_dfsph_terms32(const double* pos, const DfsphParams& p, double* factor = nullptr);
  // The terms the solves read (dfsph_rate, dfsph_correct), in the path's precision; none where
  // the fp64 path recomputes them (set_dfsph_terms(false)).
  void ensure_solve_terms(const double* pos, const DfsphParams& p);
  // fp32 copies of n rows of 4 (velocities) or of n values (kappas) for the fp32 solves.
  const float* fp32_rows(std::vector<float>& out, const double* in, uint32_t n, size_t width);
  // raymarch in fp32 from fp32 copies of its inputs, a row of 8x8 tiles per task (cpu_volume.cpp).
  void raymarch_fp32(const RaymarchParams& p, const Buffer<Real>& volume, const Buffer<Real4>& tf,
                     const Buffer<Real4>& bricks, Buffer<Real4>& image,
                     const Buffer<Real4>* tf_integral);

  Capabilities caps_;
  ThreadPool pool_;
  CpuRenderPrecision render_;
  SphNeighborLists sph_lists_;
  DfsphTerms dfsph_terms_;
  DfsphTerms32 dfsph_terms32_;
  std::vector<float> dfsph_xyz32_, dfsph_vel32_, dfsph_kappa32_;
  bool dfsph_terms_on_ = true;
  std::vector<double> sph_p_rho2_;  // sph_forces' p / rho^2 per particle, kept between calls
  const SphSimdKernels* sph_simd_ = nullptr;  // the fp32 pair loops; null: fp64
  std::vector<float> sph_fields_;  // sph_forces_fp32's neighbour fields, 8 per particle
  std::vector<std::chrono::steady_clock::time_point> stamps_;
  std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
};

// Stable LSD radix sort on the host, parallel over contiguous chunks (shared by the CPU backend
// and the benchmark's reference row).
void radix_sort_host(ThreadPool& pool, uint32_t n, uint32_t key_bits, uint32_t* keys,
                     uint32_t* values);

}  // namespace masav::cpu
