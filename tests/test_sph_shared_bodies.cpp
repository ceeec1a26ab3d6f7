// The per-particle bodies the CUDA SPH kernels call (sph::density_at, sph::force_at in
// engine/kernels/sph_kernels.h), run on the host in double and in float, against the CPU
// reference's kernels, which sum the same terms over neighbour lists (cpu_sph.cpp). CUDA cannot
// run here; this is how its kernel bodies are exercised without it.
#include <doctest/doctest.h>

#include <cstring>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/kernels/sph_kernels.h"
#include "engine/sph/sph_coefficients.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/util/error_metrics.h"
#include "tests/sph_fixture.h"

using namespace masav;

namespace {

template <class T>
sph::V3<T> v3(const Vec4d& a) {
  return {T(a.x), T(a.y), T(a.z)};
}

// density_at and force_at over every sorted particle of the case, in precision T, the wall
// images after the walk or (ImagesAfter false, cuda.sph_images_after=off) inside it.
template <class T, bool ImagesAfter = true>
void host_bodies(const test::SphCase& c, const std::vector<Vec4d>& pos,
                 const std::vector<Vec4d>& vel, const std::vector<double>& rho,
                 const std::vector<double>& pr, const std::vector<uint32_t>& cells,
                 const std::vector<uint32_t>& start, const std::vector<uint32_t>& end,
                 const SphStepLayout<T>& k, std::vector<double>& rho_out,
                 std::vector<Vec4d>& acc_out) {
  const SphStepParams& p = c.params;
  const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
  auto pos_at = [&](uint32_t j) { return v3<T>(pos[j]); };
  auto fetch = [&](uint32_t j) {
    return sph::make_neighbor<T>(v3<T>(pos[j]), v3<T>(vel[j]), T(rho[j]), T(pr[j]));
  };
  rho_out.resize(p.n);
  acc_out.resize(p.n);
  for (uint32_t i = 0; i < p.n; ++i) {
    const auto d = sph::density_at<T>(uint32_t(i), pos_at(i), cells[i], dims, start.data(),
                                      end.data(), p.max_candidates, k, pos_at);
    rho_out[i] = double(d.density);
    const auto f = sph::force_at<T, ImagesAfter>(i, fetch(i), cells[i], dims, start.data(),
                                                 end.data(), p.max_candidates, k, pos_at, fetch);
    const sph::V3<T> a = sph::total_accel(f.accel, T(pos[i].w), k);
    acc_out[i] = {double(a.x), double(a.y), double(a.z), double(f.neighbors)};
  }
}

// density_at recording row masks, then force_at walking every candidate and over the masks, in
// precision T, with the wall images after the walk or inside it; true if the two force walks
// give the same bits (accelerations and neighbours).
template <class T, bool ImagesAfter>
bool masked_forces_same(const test::SphCase& c, const std::vector<Vec4d>& pos,
                        const std::vector<Vec4d>& vel, const std::vector<double>& rho,
                        const std::vector<double>& pr, const std::vector<uint32_t>& cells,
                        const std::vector<uint32_t>& start, const std::vector<uint32_t>& end,
                        std::vector<uint32_t>& rows) {
  const SphStepParams& p = c.params;
  const auto k = device_params<T>(p);
  const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
  auto pos_at = [&](uint32_t j) { return v3<T>(pos[j]); };
  auto fetch = [&](uint32_t j) {
    return sph::make_neighbor<T>(v3<T>(pos[j]), v3<T>(vel[j]), T(rho[j]), T(pr[j]));
  };
  rows.assign(size_t(kSphRowMaskWords) * p.n, 0xdeadbeefu);  // every word must be written
  for (uint32_t i = 0; i < p.n; ++i)
    sph::density_at<T>(uint32_t(i), pos_at(i), cells[i], dims, start.data(), end.data(),
                       p.max_candidates, k, pos_at, sph::row_masks(rows.data(), i, p.n));
  for (uint32_t i = 0; i < p.n; ++i) {
    const auto full = sph::force_at<T, ImagesAfter>(i, fetch(i), cells[i], dims, start.data(),
                                                    end.data(), p.max_candidates, k, pos_at, fetch);
    const auto masked = sph::force_at<T, ImagesAfter>(
        i, fetch(i), cells[i], dims, start.data(), end.data(), p.max_candidates, k, pos_at, fetch,
        sph::row_masks<const uint32_t>(rows.data(), i, p.n));
    if (std::memcmp(&full.accel, &masked.accel, sizeof(full.accel)) != 0 ||
        full.neighbors != masked.neighbors || full.candidates != masked.candidates ||
        full.overflow != masked.overflow)
      return false;
  }
  return true;
}

}  // namespace

TEST_CASE("sph::force_at over row masks gives the full walk's bits, in double and float") {
  cpu::CpuBackend r;
  // The fixture's lattice, and the same with 60 particles crowding one cell (its rows are too
  // long for a mask and walked whole) under a candidate cap that overflows.
  std::vector<test::SphCase> cases;
  test::for_each_model_and_walls(10, 33, [&](test::SphCase& c) { cases.push_back(c); });
  test::SphCase crowded = cases.front();
  for (int k = 0; k < 60; ++k) {
    const float o = 0.0004f * float(k % 7) - 0.0012f, q = 0.0003f * float(k / 7) - 0.0012f;
    crowded.positions.push_back({0.105f + o, 0.105f + q, 0.105f + o * q * 100.0f, 1.0f});
    crowded.velocities.push_back({0.1f * o, 0.0f, 0.1f * q, 0.0f});
  }
  crowded.params.n = crowded.params.grid.n = uint32_t(crowded.positions.size());
  cases.push_back(crowded);
  crowded.params.max_candidates = 100;
  cases.push_back(crowded);
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    CAPTURE(ci);
    const test::SphCase& c = cases[ci];
    test::SphBuffers s = test::upload_sph_case(r, c);
    sph_density(r, c.params,
                {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &s.neighbor_rows});
    const auto pos = r.download(s.sorted_pos), vel = r.download(s.sorted_vel);
    const auto rho = r.download(s.density), pr = r.download(s.pressure);
    const auto cells = r.download(s.grid.sorted_cells);
    const auto start = r.download(s.grid.cell_start), end = r.download(s.grid.cell_end);
    std::vector<uint32_t> rows;
    CHECK(masked_forces_same<double, true>(c, pos, vel, rho, pr, cells, start, end, rows));
    // The CPU reference derives its masks from its neighbour lists: the same bits.
    CHECK(rows == r.download(s.neighbor_rows));
    CHECK(masked_forces_same<float, true>(c, pos, vel, rho, pr, cells, start, end, rows));
    CHECK(masked_forces_same<double, false>(c, pos, vel, rho, pr, cells, start, end, rows));
    CHECK(masked_forces_same<float, false>(c, pos, vel, rho, pr, cells, start, end, rows));
  }
}

TEST_CASE("sph::density_at and sph::force_at (the CUDA bodies) equal the CPU reference") {
  cpu::CpuBackend r;
  test::for_each_model_and_walls(10, 31, [&](test::SphCase& c) {
    test::SphBuffers s = test::upload_sph_case(r, c);
    sph_density(r, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
    sph_forces(
        r, c.params,
        {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(), &s.accel, &s.stats});
    const auto pos = r.download(s.sorted_pos), vel = r.download(s.sorted_vel);
    const auto rho = r.download(s.density), pr = r.download(s.pressure);
    const auto acc = r.download(s.accel);
    const auto cells = r.download(s.grid.sorted_cells);
    const auto start = r.download(s.grid.cell_start), end = r.download(s.grid.cell_end);
    const auto k = device_params<double>(c.params);

    std::vector<double> rho_d, rho_f;
    std::vector<Vec4d> acc_d, acc_f;
    host_bodies<double>(c, pos, vel, rho, pr, cells, start, end, k, rho_d, acc_d);
    host_bodies<float>(c, pos, vel, rho, pr, cells, start, end, device_params<float>(c.params),
                       rho_f, acc_f);
    const double acc_scale = rms(xyz_components(acc));
    // double: the densities sum the same terms in another order (lists vs the walk), rounding
    // only; the forces sum them in the lists' order, the wall images after the direct terms, so
    // force_at gives the reference's bits.
    CHECK(compare(rho_d, rho, 1.0).max_rel < 1e-12);
    CHECK(compare(xyz_components(acc_d), xyz_components(acc), acc_scale).max_abs == 0.0);
    // float: the tolerances of the fp32 backends' kernel tests (test_sph_kernels.cpp).
    CHECK(compare(rho_f, rho, 1.0).rel_l2 < 1e-6);
    const ErrorStats ef = compare(xyz_components(acc_f), xyz_components(acc), acc_scale);
    INFO("float accel: " << describe(ef));
    CHECK(ef.rel_l2 < 2e-6);
    CHECK(ef.max_rel < 2e-5);
    for (uint32_t i = 0; i < c.params.n; ++i) REQUIRE(acc_d[i].w == acc[i].w);  // neighbours
    // The images inside the walk (cuda.sph_images_after=off): the same terms in another
    // order where a wall is near.
    std::vector<double> rho_in;
    std::vector<Vec4d> acc_in_d, acc_in_f;
    host_bodies<double, false>(c, pos, vel, rho, pr, cells, start, end, k, rho_in, acc_in_d);
    host_bodies<float, false>(c, pos, vel, rho, pr, cells, start, end,
                              device_params<float>(c.params), rho_in, acc_in_f);
    CHECK(compare(xyz_components(acc_in_d), xyz_components(acc), acc_scale).max_rel < 1e-10);
    const ErrorStats ei = compare(xyz_components(acc_in_f), xyz_components(acc), acc_scale);
    INFO("float accel, images inside: " << describe(ei));
    CHECK(ei.rel_l2 < 2e-6);
    CHECK(ei.max_rel < 2e-5);
    for (uint32_t i = 0; i < c.params.n; ++i) REQUIRE(acc_in_d[i].w == acc[i].w);
  });
}

// CUDA's density kernel walks without the wall images in warps with no lane near a wall
// (sph::density_walk<T, false, true>); for a particle far from the walls that copy must give
// density_at's bits, and near a wall it must differ (it leaves the images out).
TEST_CASE("sph::density_walk without wall images equals density_at far from the walls") {
  cpu::CpuBackend r;
  uint32_t far = 0, near = 0, lower = 0;
  test::for_each_model_and_walls(10, 37, [&](test::SphCase& c) {
    test::SphBuffers s = test::upload_sph_case(r, c);
    sph_density(r, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
    const auto pos = r.download(s.sorted_pos);
    const auto cells = r.download(s.grid.sorted_cells);
    const auto start = r.download(s.grid.cell_start), end = r.download(s.grid.cell_end);
    const SphStepParams& p = c.params;
    const auto k = device_params<float>(p);
    const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
    auto pos_at = [&](uint32_t j) { return v3<float>(pos[j]); };
    std::vector<uint32_t> rows_at(size_t(kSphRowMaskWords) * p.n),
        rows_walk(size_t(kSphRowMaskWords) * p.n);
    for (uint32_t i = 0; i < p.n; ++i) {
      CAPTURE(i);
      const auto m = k.walls ? sph::wall_mirrors(pos_at(i), k) : sph::WallMirrors<float>{};
      const auto at = sph::density_at<float>(i, pos_at(i), cells[i], dims, start.data(), end.data(),
                                             p.max_candidates, k, pos_at,
                                             sph::row_masks(rows_at.data(), i, p.n));
      const auto walk = sph::density_walk<float, false, true>(
          i, pos_at(i), m, cells[i], dims, start.data(), end.data(), p.max_candidates, k, pos_at,
          sph::row_masks(rows_walk.data(), i, p.n));
      REQUIRE(walk.neighbors == at.neighbors);
      REQUIRE(walk.candidates == at.candidates);
      if (m.axes == 0u) {
        ++far;
        REQUIRE(std::memcmp(&walk.density, &at.density, sizeof(float)) == 0);
      } else {
        ++near;
        REQUIRE(walk.density <= at.density);
        lower += walk.density < at.density ? 1u : 0u;
      }
    }
    CHECK(rows_walk == rows_at);
  });
  CHECK(far > 0u);
  CHECK(near > 0u);
  CHECK(lower > near / 2);
}
