#pragma once
// A rank's own particles read from its device, and every rank's gathered on every rank: the
// reads a snapshot, a checkpoint (SphResumeState holds the one-process arrays) and download()
// make on several ranks (sph_ranks.h).
#include <cstdint>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/sph/sph_ranks.h"
#include "engine/sph/sph_state.h"

namespace masav {

// The own particles' values of `b` in the committed layout, read from the device alone (not
// the whole buffer).
std::vector<Vec4d> own_values(Backend& backend, const SphRanks& ranks, const Buffer<Real4>& b);
std::vector<double> own_values(Backend& backend, const SphRanks& ranks, const Buffer<Real>& b);
std::vector<uint32_t> own_values(Backend& backend, const SphRanks& ranks,
                                 const Buffer<uint32_t>& b);
// The own particles' values of `b` (the committed layout) of every rank, in rank order (the
// one-process order), on every rank.
std::vector<Vec4d> gather_own(Backend& backend, SphRanks& ranks, const Buffer<Real4>& b);
std::vector<double> gather_own(Backend& backend, SphRanks& ranks, const Buffer<Real>& b);
std::vector<uint32_t> gather_own(Backend& backend, SphRanks& ranks, const Buffer<uint32_t>& b);

// The whole state of `n` particles by id, on every rank, from each rank's own particles `own`
// (by `ids`, in its order). Throws masav::Error where the ranks' particles are not each of the
// n exactly once (ranks of different builds or arguments).
SphState gather_state(Backend& backend, SphRanks& ranks, const SphState& own,
                      const std::vector<uint32_t>& ids, uint32_t n);

}  // namespace masav
