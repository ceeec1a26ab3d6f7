// The CPU reference's kept DFSPH pair terms (engine/cpu/cpu_dfsph_terms.h): the kernels that
// read the gradients back give the very bits of the shared bodies that recompute them, over both
// solves with wall images and pinned particles, and after the positions or the walls change
// under the kept terms (terms of the old ones would give other bits). Runs with --backend=cpu.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "engine/core/tuning.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/kernels/dfsph_params.h"
#include "engine/sph/dfsph_case_buffers.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_particles.h"
#include "tests/backend_fixture.h"
#include "tests/cpu_fp32_sets.h"
#include "tests/sph_fixture.h"

using namespace masav;

namespace {

// Every double the kernels wrote, in call order, and the residual words.
struct Record {
  std::vector<double> reals;
  std::vector<uint32_t> words;
  bool operator==(const Record& o) const {
    return reals.size() == o.reals.size() && words == o.words &&
           std::memcmp(reals.data(), o.reals.data(), reals.size() * sizeof(double)) == 0;
  }
};

// What changes before the last two iterations: nothing, the positions (moved without a new
// sph_density or dfsph_factor) or the walls (other images, the same neighbour lists).
enum class Change { none, move, box };

// The case's solves on a fresh CPU backend with the terms on or off.
Record run_solves(cpu::CpuBackend& b, const test::SphCase& c, Change change);
Record run_solves(bool terms, const test::SphCase& c, Change change) {
  cpu::CpuBackend b(2);
  b.set_dfsph_terms(terms);
  return run_solves(b, c, change);
}

Record run_solves(cpu::CpuBackend& b, const test::SphCase& c, Change change) {
  test::SphBuffers s = test::upload_sph_case(b, c);
  DfsphCaseBuffers d = make_dfsph_buffers(b, c.params.n, "test dfsph");
  DfsphIO io = dfsph_io(s, d);
  Record r;
  auto keep = [&](const Buffer<Real>& buf) {
    for (double v : b.download(buf)) r.reals.push_back(v);
  };
  auto keep4 = [&](const Buffer<Real4>& buf) {
    for (const Vec4d& v : b.download(buf)) r.reals.insert(r.reals.end(), {v.x, v.y, v.z, v.w});
  };
  auto iterate = [&](DfsphParams p, uint32_t iterations) {
    for (uint32_t k = 0; k < iterations; ++k) {
      p.slot = k;
      p.first = k == 0;
      dfsph_rate(b, p, io);
      p.first = false;
      dfsph_correct(b, p, io);
      keep(d.kappa);
      keep(d.kappa_sum);
      keep4(s.sorted_vel);
    }
  };

  sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
  dfsph_factor(b, DfsphParams{c.params}, io);
  keep(d.factor);
  DfsphParams p{c.params, DfsphSolve::density, 2e-3};
  iterate(p, 4);
  // The divergence solve's warm start, then its iterations; some particles have too few
  // neighbours to count.
  p.solve = DfsphSolve::divergence;
  p.min_neighbors = 20;
  p.first = true;
  io.kappa = &d.kappa_sum;
  dfsph_correct(b, p, io);
  io.kappa = &d.kappa;
  keep4(s.sorted_vel);
  iterate(p, 3);
  if (change == Change::move) {  // a third of the particles 0.1 dx along x
    std::vector<Vec4d> x = b.download(s.sorted_pos);
    for (size_t i = 0; i < x.size(); i += 3) x[i].x += 0.1 * c.dx;
    b.upload(s.sorted_pos, x);
  }
  if (change == Change::box) p.step.box_min.x -= 0.5 * c.dx;  // the walls further out on x
  iterate(p, 2);
  r.words = b.download(d.residual);
  return r;
}

test::SphCase solve_case(bool walls) {
  test::SphCase c = test::make_sph_case(9, SphPressureModel::dfsph, 11);
  c.params.mass = lattice_mass(1000.0, c.dx, c.params.h, true);
  test::with_walls(c, walls);
  return c;
}

}  // namespace

TEST_CASE("cpu dfsph: the kept pair terms give the shared bodies' bits, and follow changes") {
  if (test::backend().caps().backend != "cpu") return;  // a CPU backend's own structure
  for (const bool walls : {false, true}) {
    CAPTURE(walls);
    const test::SphCase c = solve_case(walls);
    Record still;
    for (const Change change : {Change::none, Change::move, Change::box}) {
      CAPTURE(int(change));
      const Record with = run_solves(true, c, change);
      const Record without = run_solves(false, c, change);
      REQUIRE(with.reals.size() == without.reals.size());
      CHECK(with == without);
      // Each change does change the last iterations (with walls), so terms kept across it
      // would have given the unchanged run's bits.
      if (change == Change::none)
        still = without;
      else if (walls || change == Change::move)
        CHECK_FALSE(without == still);
    }
  }
}

TEST_CASE("cpu dfsph fp32: the same bits for any instruction set and thread count, within fp32 "
          "rounding of fp64") {
  // The fp32 solves (DfsphTerms32) sum each particle's terms in a fixed lane order, so neither
  // the instruction set nor the thread count changes a bit; they are not the fp64 bits (the
  // option does change the arithmetic), and the solves' outputs stay within fp32 rounding of
  // them (whole-record relative L2 below 1e-5; the kernel tests, kernels.cpu.fp32, check each
  // kernel against brute-force sums). An instruction set this CPU lacks is skipped, saying so.
  if (test::backend().caps().backend != "cpu") return;  // a CPU backend's own structure
  test::announce_missing_sets();
  for (const bool walls : {false, true}) {
    CAPTURE(walls);
    const test::SphCase c = solve_case(walls);
    cpu::CpuBackend one(1, cpu::CpuRenderPrecision::fp64, test::fp32_tuning(CpuSphSimd::generic));
    const Record want = run_solves(one, c, Change::move);
    test::for_each_fp32_backend(
        [&](cpu::CpuBackend& b) { CHECK(run_solves(b, c, Change::move) == want); });
    const Record ref = run_solves(true, c, Change::move);
    REQUIRE(ref.reals.size() == want.reals.size());
    CHECK_FALSE(ref == want);
    double diff2 = 0, norm2 = 0;
    for (size_t k = 0; k < ref.reals.size(); ++k) {
      diff2 += (want.reals[k] - ref.reals[k]) * (want.reals[k] - ref.reals[k]);
      norm2 += ref.reals[k] * ref.reals[k];
    }
    INFO("relative L2 difference " << std::sqrt(diff2 / norm2));
    CHECK(std::sqrt(diff2 / norm2) < 1e-5);
  }
}
