// A rank's buffers: sized for its share of the particles and its halos rather than for all of
// them, so that memory per rank falls as ranks are added, and grown when a rank takes more.
#include <algorithm>

#include "engine/sph/sph_simulation.h"

namespace masav {
namespace {

// `b` with room for `count` elements, its contents kept.
template <class T>
void grow(Backend& backend, Buffer<T>& b, size_t count) {
  if (!b.valid() || b.size() >= count) return;
  Buffer<T> bigger = backend.create<T>(count, b.impl().label());
  backend.copy_bytes(b.impl(), bigger.impl(), b.impl().bytes());
  b = std::move(bigger);
}

}  // namespace

void SphSimulation::reserve(uint32_t local) {
  if (local <= capacity_) return;
  // A quarter more than asked, so that a rank whose share creeps up grows a few times only.
  capacity_ = uint32_t(std::min<uint64_t>(n_, uint64_t(local) + local / 4 + 1024));
  ++capacity_growths_;
  const size_t c = capacity_;
  for (Buffer<Real4>* b : {&pos_, &vel_, &xs_, &vs_, &sum_x_, &sum_v_, &ta_, &tb_, &tc_, &accel_,
                           &checkpoint_.pos, &checkpoint_.vel, &checkpoint_.accel})
    grow(backend_, *b, c);
  for (Buffer<Real>* b : {&density_, &pressure_}) grow(backend_, *b, c);
  for (Buffer<uint32_t>* b :
       {&ids_, &ids_t_, &checkpoint_.ids, &grid_.sorted_cells, &grid_.sorted_index})
    grow(backend_, *b, c);
  grow(backend_, neighbor_rows_, size_t(kSphRowMaskWords) * c);
}

}  // namespace masav
