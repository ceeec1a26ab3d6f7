#pragma once
// The DFSPH kernels' own buffers beside a case's SphCaseBuffers, and the kernels' inputs and
// outputs over both: the cross-check (engine/sph/dfsph_cross_checks.cpp) and the kernel tests
// run dfsph_factor, dfsph_rate and dfsph_correct on these.
#include <string_view>

#include "engine/kernels/dfsph_params.h"
#include "engine/sph/sph_case_buffers.h"

namespace masav {

struct DfsphCaseBuffers {
  Buffer<Real> factor, kappa, kappa_sum;  // kappa_sum zeroed
  Buffer<uint32_t> residual;              // kDfsphResidualWords, zeroed
};

// n particles' buffers; labels start with `label`.
DfsphCaseBuffers make_dfsph_buffers(Backend& b, uint32_t n, std::string_view label);

// The kernels' arguments over s and d, with s's neighbour row masks where `masked`.
DfsphIO dfsph_io(SphCaseBuffers& s, DfsphCaseBuffers& d, bool masked = false);

}  // namespace masav
