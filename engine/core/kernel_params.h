#pragma once
// Parameter structs of the kernels declared in backend.h. Plain data: every backend reads the same
// fields, and the shared validators (kernel_checks.h) reject bad values before any dispatch.
#include <cstdint>

#include "engine/core/buffer.h"
#include "engine/core/types.h"

namespace masav {

class DeviceApi;

// Philox4x32-10 stream: word i of the output is word (i % 4) of the block with counter
// (first_block + i / 4, stream) under key `seed`. Streams with different ids never overlap.
struct PhiloxParams {
  uint64_t seed = 0;
  uint64_t stream = 0;
  uint64_t first_block = 0;
};

enum class SortImpl : uint8_t {
  portable,  // our reduce-then-scan LSD sort (every backend)
  vendor,    // the vendor library where one exists (CUB on CUDA); else the portable sort
};

// Stable LSD sort of keys[0..n) (and values[0..n) alongside) by the low `key_bits` bits of each
// key; bits above key_bits are ignored and kept.
struct RadixSortParams {
  uint32_t n = 0;
  uint32_t key_bits = 32;
  SortImpl impl = SortImpl::portable;
};

// Uniform grid over a box (thesis Eq. 4.1-4.2). A point's cell is floor((p - origin) * inv_cell)
// per axis in fp32, clamped to [0, dims-1]; cell id = (cx * dims.y + cy) * dims.z + cz.
struct GridParams {
  Vec3f origin;
  float cell_size = 1.0f;
  float inv_cell = 1.0f;  // fp32 1/cell_size computed once on the host, so every backend agrees
  UVec3 dims{1, 1, 1};
  uint32_t n = 0;  // points
};
GridParams make_grid_params(Vec3f origin, float cell_size, UVec3 dims, uint32_t n);
uint64_t grid_cell_count(const GridParams& g);
uint32_t grid_key_bits(const GridParams& g);  // bits needed for the largest cell id

// Neighbours of each sorted point within `radius` over the 27 cells around it (itself included).
struct NeighborParams {
  GridParams grid;
  float radius = 1.0f;
  float radius2 = 1.0f;  // fp32 radius*radius computed on the host
  // Candidates examined per point at most; beyond it the kernel reports an overflow, because
  // lavapipe silently stops an invocation after 65,535 loop iterations.
  uint32_t max_candidates = 60000;
};
NeighborParams make_neighbor_params(const GridParams& grid, float radius);

// dst[i] = src[order[i]] for i < n.
struct GatherParams {
  uint32_t n = 0;
};

// The checks Backend runs before any backend sees a call (engine/core/kernel_checks.cpp); each
// throws masav::Error naming the kernel, the field, its value and the allowed range.
void validate(const DeviceApi& dev, const PhiloxParams& p, const Buffer<uint32_t>& out);
void validate(const DeviceApi& dev, const PhiloxParams& p, const Buffer<float>& out);
void validate(const DeviceApi& dev, const RadixSortParams& p, const Buffer<uint32_t>& keys,
              const Buffer<uint32_t>* values);
void validate(const DeviceApi& dev, const GridParams& g, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& indices);
void validate(const DeviceApi& dev, const GridParams& g, const Buffer<uint32_t>& sorted_cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end);
void validate(const DeviceApi& dev, const GatherParams& p, const Buffer<uint32_t>& order,
              const BufferImpl& src, const BufferImpl& dst);
void validate(const DeviceApi& dev, const NeighborParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<uint32_t>& counts);

}  // namespace masav
