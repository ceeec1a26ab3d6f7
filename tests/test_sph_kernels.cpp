// SPH kernels (sph_density, sph_forces, sph_integrate), one test body each, on every backend:
// against the CPU reference (fp64) on identical sorted inputs, and against brute-force sums.
// Tolerances: fp32 backends hold positions to ~6e-8 relative. Measured on lavapipe: densities
// agree to 1e-7 (rel L2), accelerations -- sums of ~30 terms that largely cancel -- to 2e-7 of
// their RMS (max 1.3e-6); the bounds below leave about 10x.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <vector>

#include "engine/core/error.h"
#include "engine/kernels/grid_cell.h"
#include "engine/kernels/sph_integrate_body.h"
#include "engine/sph/dfsph_case_buffers.h"
#include "engine/sph/sph_coefficients.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/util/error_metrics.h"
#include "tests/backend_fixture.h"
#include "tests/same_bits.h"
#include "tests/sph_fixture.h"

using namespace masav;

// sph_forces on the backend and on the CPU reference, each over its own buffers (which hold the
// same inputs): accelerations within rel L2 2e-6 and max 2e-5 of the RMS, neighbour counts exact.
void forces_match_reference(Backend& b, Backend& r, const test::SphCase& c, test::SphBuffers& sb,
                            test::SphBuffers& sr) {
  sph_forces(
      b, c.params,
      {&sb.sorted_pos, &sb.sorted_vel, &sb.density, &sb.pressure, sb.view(), &sb.accel, &sb.stats});
  sph_forces(
      r, c.params,
      {&sr.sorted_pos, &sr.sorted_vel, &sr.density, &sr.pressure, sr.view(), &sr.accel, &sr.stats});
  const auto got = b.download(sb.accel), want = r.download(sr.accel);
  const auto g3 = xyz_components(got), w3 = xyz_components(want);
  const ErrorStats e = compare(g3, w3, rms(w3));
  INFO("accel: " << describe(e) << ", rms " << rms(w3));
  CHECK(e.rel_l2 < 2e-6);
  CHECK(e.max_rel < 2e-5);
  for (size_t i = 0; i < got.size(); ++i) REQUIRE(got[i].w == want[i].w);  // neighbour counts
}

TEST_CASE("sph_density equals the CPU reference and a brute-force kernel sum") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  test::for_each_model_and_walls(14, 7, [&](test::SphCase& c) {
    test::SphBuffers sb = test::upload_sph_case(b, c), sr = test::upload_sph_case(r, c);
    REQUIRE(b.download(sb.grid.sorted_index) == r.download(sr.grid.sorted_index));
    sph_density(b, c.params, {&sb.sorted_pos, sb.view(), &sb.density, &sb.pressure, &sb.stats});
    sph_density(r, c.params, {&sr.sorted_pos, sr.view(), &sr.density, &sr.pressure, &sr.stats});
    const auto rho = b.download(sb.density), rho_ref = r.download(sr.density);
    const auto pr = b.download(sb.pressure), pr_ref = r.download(sr.pressure);
    const ErrorStats e_rho = compare(rho, rho_ref, 1.0);
    INFO("density: " << describe(e_rho));
    CHECK(e_rho.rel_l2 < 1e-6);
    CHECK(e_rho.max_rel < 5e-6);
    // Pressure amplifies density errors (Tait: 7 B rho^6 / rho0^7): bound it by the EOS slope.
    const ErrorStats e_p = compare(pr, pr_ref, 1e-3 * rms(pr_ref) + 1.0);
    INFO("pressure: " << describe(e_p));
    CHECK(e_p.rel_l2 < 1e-4);

    // Brute force over all pairs in double, at the fp32 positions both backends hold, with the
    // walls as images: every particle reflected across each combination of the walls within h
    // of particle i (the nearer wall of each axis), i's own images like any other. The kernel:
    // spiky, or poly6 for the thesis model.
    const auto sp = r.download_f32(sr.sorted_pos);
    const double h = c.params.h, h2 = h * h;
    const auto coef = device_params<double>(c.params);
    const Vec3d lo = c.params.box_min, hi = c.params.box_max;
    double worst = 0;
    for (size_t i = 0; i < sp.size(); i += 7) {
      const double xi[3] = {sp[i].x, sp[i].y, sp[i].z};
      const double lo3[3] = {lo.x, lo.y, lo.z}, hi3[3] = {hi.x, hi.y, hi.z};
      double plane[3];
      bool near[3];
      for (int a = 0; a < 3; ++a) {
        const bool low = xi[a] - lo3[a] <= hi3[a] - xi[a];
        plane[a] = low ? lo3[a] : hi3[a];
        near[a] = coef.walls && std::abs(xi[a] - plane[a]) < h;
      }
      const bool spiky = c.params.model != SphPressureModel::thesis;
      double sum = 0;  // kernel terms (1 - q)^3 or (1 - q^2)^3
      for (size_t j = 0; j < sp.size(); ++j) {
        const double xj[3] = {sp[j].x, sp[j].y, sp[j].z};
        for (int mirror = 0; mirror < 8; ++mirror) {
          double r2 = 0;
          bool usable = true;
          for (int a = 0; a < 3; ++a) {
            const bool flip = mirror >> a & 1;
            usable = usable && (!flip || near[a]);
            const double d = xi[a] - (flip ? 2.0 * plane[a] - xj[a] : xj[a]);
            r2 += d * d;
          }
          if (!usable || !(r2 < h2)) continue;
          sum += std::pow(spiky ? 1.0 - std::sqrt(r2) / h : 1.0 - r2 / h2, 3);
        }
      }
      worst = std::max(worst, std::abs(coef.density * sum - rho_ref[i]) / rho_ref[i]);
    }
    CHECK(worst < 1e-12);
    // A particle deep inside the jittered lattice sits near rest density.
    const auto words = b.download(sb.stats);
    CHECK(words[kSphStatMaxNeighbors] > 20);
    CHECK(words[kSphStatMaxNeighbors] < 80);
    CHECK(words[kSphStatOverflow] == 0);
    CHECK(words[kSphStatNonFinite] == 0);
    CHECK(words[kSphStatMaxCandidates] == r.download(sr.stats)[kSphStatMaxCandidates]);
  });
}

TEST_CASE("sph_forces equals the CPU reference for both pressure models") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  test::for_each_model_and_walls(14, 11, [&](test::SphCase& c) {
    test::SphBuffers sb = test::upload_sph_case(b, c), sr = test::upload_sph_case(r, c);
    sph_density(r, c.params, {&sr.sorted_pos, sr.view(), &sr.density, &sr.pressure, &sr.stats});
    // The backend gets the reference's density and pressure: this tests the force kernel alone.
    b.upload(sb.density, r.download(sr.density));
    b.upload(sb.pressure, r.download(sr.pressure));
    forces_match_reference(b, r, c, sb, sr);

    // Pinned particles do not accelerate; the others feel gravity on top of the pair forces.
    const auto got = b.download(sb.accel);
    const auto pos = r.download(sr.sorted_pos);
    size_t pinned = 0;
    for (size_t i = 0; i < pos.size(); ++i)
      if (pos[i].w == 0) {
        ++pinned;
        CHECK(got[i].x == 0.0);
        CHECK(got[i].y == 0.0);
      }
    CHECK(pinned > 0);

    // wcsph pair forces are antisymmetric: with unit inverse masses and no gravity, the total
    // force is zero to rounding.
    if (c.params.model == SphPressureModel::wcsph && !c.params.walls) {
      test::SphCase sym = c;
      for (auto& p : sym.positions) p.w = 1.0f;
      sym.params.gravity = {0, 0, 0};
      test::SphBuffers s2 = test::upload_sph_case(r, sym);
      sph_density(r, sym.params, {&s2.sorted_pos, s2.view(), &s2.density, &s2.pressure, &s2.stats});
      sph_forces(r, sym.params,
                 {&s2.sorted_pos, &s2.sorted_vel, &s2.density, &s2.pressure, s2.view(), &s2.accel,
                  &s2.stats});
      double fx = 0, fy = 0, fz = 0, scale = 0;
      for (const auto& a : r.download(s2.accel)) {
        fx += a.x, fy += a.y, fz += a.z;
        scale += std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
      }
      CHECK(std::sqrt(fx * fx + fy * fy + fz * fz) < 1e-12 * scale);
    }
  });
}

// The dfsph model's density (spiky kernel) and forces (viscosity and gravity only): each pressure
// model has its own specialisation of both kernels on Vulkan (shaders/common/sph.glsl), so this
// one is checked like the two above, in the same backend after them.
TEST_CASE("sph_density and sph_forces with the dfsph model equal the CPU reference") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  for (const bool walls : {false, true}) {
    CAPTURE(walls);
    test::SphCase c = test::make_sph_case(12, SphPressureModel::dfsph, 31);
    c.params.mass = lattice_mass(1000.0, c.dx, c.params.h, true);
    test::with_walls(c, walls);
    test::SphBuffers sb = test::upload_sph_case(b, c), sr = test::upload_sph_case(r, c);
    sph_density(b, c.params, {&sb.sorted_pos, sb.view(), &sb.density, &sb.pressure, &sb.stats});
    sph_density(r, c.params, {&sr.sorted_pos, sr.view(), &sr.density, &sr.pressure, &sr.stats});
    const auto rho = b.download(sb.density), rho_ref = r.download(sr.density);
    const ErrorStats e_rho = compare(rho, rho_ref, 1.0);
    INFO("density: " << describe(e_rho));
    CHECK(e_rho.rel_l2 < 1e-6);
    CHECK(e_rho.max_rel < 5e-6);
    for (const double pr : b.download(sb.pressure)) REQUIRE(pr == 0.0);  // dfsph solves for it

    b.upload(sb.density, rho_ref);
    forces_match_reference(b, r, c, sb, sr);
  }
}

// The CPU reference keeps sph_density's neighbour lists for sph_forces (engine/cpu/
// cpu_sph_lists.h). Whatever a backend keeps, sph_forces must depend on its inputs only: the
// same bits whether sph_density just ran on these positions, on other positions in the same
// buffers, or on another particle set.
TEST_CASE("sph_forces depends only on its inputs, whatever sph_density saw before") {
  Backend& b = test::backend();
  test::SphCase c = test::make_sph_case(9, SphPressureModel::wcsph, 21);
  test::with_walls(c, true);
  test::SphCase other = test::make_sph_case(9, SphPressureModel::wcsph, 22);
  test::SphBuffers s = test::upload_sph_case(b, c), o = test::upload_sph_case(b, other);
  auto density = [&](test::SphBuffers& x) {
    sph_density(b, c.params, {&x.sorted_pos, x.view(), &x.density, &x.pressure, &x.stats});
  };
  auto forces = [&](test::SphBuffers& x) {
    sph_forces(
        b, c.params,
        {&x.sorted_pos, &x.sorted_vel, &x.density, &x.pressure, x.view(), &x.accel, &x.stats});
    return b.download(x.accel);
  };
  density(s);
  const auto fresh = forces(s);
  density(o);  // another particle set ran last
  CHECK(test::same_bits(forces(s), fresh));
  density(s);
  (void)forces(o);  // forces on other inputs in between
  CHECK(test::same_bits(forces(s), fresh));

  // Move one particle inside its cell, in the same buffer, after the density, so far that its
  // set of neighbours within h changes (a stale list would keep the old set).
  density(s);
  auto moved = b.download(s.sorted_pos);
  const auto cells = b.download(s.grid.sorted_cells);
  const GridParams& g = c.params.grid;
  const float origin[3] = {g.origin.x, g.origin.y, g.origin.z};
  const uint32_t dims[3] = {g.dims.x, g.dims.y, g.dims.z};
  auto cell_of = [&](const Vec4d& q) {
    const grid::CellCoord cc =
        grid::point_cell(float(q.x), float(q.y), float(q.z), origin, g.inv_cell, dims);
    return grid::cell_id(cc.x, cc.y, cc.z, dims[1], dims[2]);
  };
  auto within_h = [&](uint32_t k, const Vec4d& q) {
    uint32_t count = 0;
    for (uint32_t j = 0; j < moved.size(); ++j) {
      const double dx = q.x - moved[j].x, dy = q.y - moved[j].y, dz = q.z - moved[j].z;
      count += j != k && dx * dx + dy * dy + dz * dz < c.params.h * c.params.h ? 1 : 0;
    }
    return count;
  };
  uint32_t k = 0;
  bool found = false;
  for (; k < moved.size() && !found; ++k)
    for (double shift : {0.3 * c.params.h, -0.3 * c.params.h}) {
      Vec4d q = moved[k];
      q.x += shift;
      if (cell_of(q) != cells[k] || within_h(k, q) == within_h(k, moved[k])) continue;
      moved[k] = q;
      found = true;
      break;
    }
  REQUIRE(found);
  --k;
  b.upload(s.sorted_pos, moved);
  const auto after_move = forces(s);  // density and pressure still those of the old positions
  CHECK(after_move[k].w == double(within_h(k, moved[k])));  // the neighbour count
  test::SphBuffers t = test::upload_sph_case(b, c);
  b.upload(t.sorted_pos, moved);
  density(t);  // the moved positions' own neighbour walk, then the old density and pressure
  b.upload(t.density, b.download(s.density));
  b.upload(t.pressure, b.download(s.pressure));
  CHECK(test::same_bits(forces(t), after_move));
  CHECK(!test::same_bits(after_move, fresh));
}

TEST_CASE("sph_integrate: every stage and the walls equal the CPU reference") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  const test::SphCase c = test::make_sph_case(10, SphPressureModel::wcsph, 3, 0.45);
  const uint32_t n = c.params.n;
  std::vector<Vec4f> acc(n), vk(n), sums(n);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-30.0f, 30.0f);
  for (uint32_t i = 0; i < n; ++i) {
    acc[i] = {u(rng), u(rng), u(rng), 0};
    vk[i] = {u(rng) / 10, u(rng) / 10, u(rng) / 10, 0};
    sums[i] = {u(rng), u(rng), u(rng), 0};
  }
  struct Side {
    Buffer<Real4> x0, v0, vk, a, xo, vo, sx, sv;
    Buffer<uint32_t> stats;
  };
  auto make = [&](Backend& be) {
    Side s{be.create<Real4>(n, "x0"),
           be.create<Real4>(n, "v0"),
           be.create<Real4>(n, "vk"),
           be.create<Real4>(n, "a"),
           be.create<Real4>(n, "xo"),
           be.create<Real4>(n, "vo"),
           be.create<Real4>(n, "sx"),
           be.create<Real4>(n, "sv"),
           be.create<uint32_t>(kSphStatWords, "stats")};
    be.upload(s.x0, c.positions);
    be.upload(s.v0, c.velocities);
    be.upload(s.vk, vk);
    be.upload(s.a, acc);
    be.upload(s.sx, sums);
    be.upload(s.sv, sums);
    be.fill(s.stats, 0u);
    return s;
  };
  for (uint32_t op = 0; op <= uint32_t(SphStageOp::kick); ++op) {
    CAPTURE(op);
    Side sb = make(b), sr = make(r);
    SphIntegrateParams p;
    p.n = n;
    p.op = SphStageOp(op);
    p.dt = 2e-3;
    // A box that cuts through the particles: walls act on the stages that end a step.
    p.box_min = {0.06, 0.055, 0.04};
    p.box_max = {0.13, 0.14, 0.12};
    p.restitution = 0.4;
    p.tangential_damping = 0.1;
    const bool uses_vk =
        op >= uint32_t(SphStageOp::rk4_stage2) && op <= uint32_t(SphStageOp::rk4_final);
    auto io = [&](Side& s) {
      return SphIntegrateIO{&s.x0, &s.v0,   uses_vk ? &s.vk : nullptr, &s.a, &s.xo, &s.vo, &s.sx,
                            &s.sv, &s.stats};
    };
    sph_integrate(b, p, io(sb));
    sph_integrate(r, p, io(sr));
    const auto v_got = xyz_components(b.download(sb.vo));
    const auto v_want = xyz_components(r.download(sr.vo));
    const ErrorStats ev = compare(v_got, v_want, 1.0);
    INFO("velocity: " << describe(ev));
    CHECK(ev.max_abs < 5e-5);
    if (p.op != SphStageOp::kick) {
      const auto x_got = b.download(sb.xo), x_want = r.download(sr.xo);
      const ErrorStats ex = compare(xyz_components(x_got), xyz_components(x_want), 1.0);
      INFO("position: " << describe(ex));
      CHECK(ex.max_abs < 1e-6);
      for (size_t i = 0; i < n; ++i) REQUIRE(x_got[i].w == x_want[i].w);  // inverse mass kept
      const bool ends = sph::op_ends_step(p.op);
      size_t outside = 0;
      for (const auto& x : x_want)
        outside += x.x < p.box_min.x || x.x > p.box_max.x || x.y < p.box_min.y ||
                   x.y > p.box_max.y || x.z < p.box_min.z || x.z > p.box_max.z;
      if (ends) CHECK(outside == 0);
      const auto w = b.download(sb.stats);
      CHECK(w[kSphStatOutside] == r.download(sr.stats)[kSphStatOutside]);
      if (!ends) CHECK(w[kSphStatOutside] == 0);
      if (!ends) CHECK(outside > 0);  // the box does cut the particles
    }
    if (op >= uint32_t(SphStageOp::rk4_stage1) && op <= uint32_t(SphStageOp::rk4_stage3)) {
      const ErrorStats es =
          compare(xyz_components(b.download(sb.sv)), xyz_components(r.download(sr.sv)), 1.0);
      INFO("sum_v: " << describe(es));
      CHECK(es.max_abs < 1e-4);
    }
    const auto w = b.download(sb.stats), wr = r.download(sr.stats);
    CHECK(std::abs(std::bit_cast<float>(w[kSphStatMaxSpeed2]) -
                   std::bit_cast<float>(wr[kSphStatMaxSpeed2])) <
          1e-5f * std::bit_cast<float>(wr[kSphStatMaxSpeed2]));
    CHECK(w[kSphStatNonFinite] == 0);
  }
}

TEST_CASE("sph kernels report candidate overflow and non-finite values, never hide them") {
  Backend& b = test::backend();
  test::SphCase c = test::make_sph_case(10, SphPressureModel::wcsph, 5);
  c.params.max_candidates = 40;  // far below the ~200 candidates of a lattice particle
  c.velocities[17].y = std::nanf("");
  test::SphBuffers s = test::upload_sph_case(b, c);
  sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
  auto w = b.download(s.stats);
  CHECK(w[kSphStatOverflow] != 0);
  CHECK(~w[kSphStatOverflow] < c.params.n);  // the smallest overflowing sorted index
  CHECK(w[kSphStatMaxCandidates] <= 40);

  c.params.max_candidates = 8192;
  b.fill(s.stats, 0u);
  sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
  sph_forces(b, c.params,
             {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(), &s.accel, &s.stats});
  w = b.download(s.stats);
  CHECK(w[kSphStatOverflow] == 0);
  REQUIRE(w[kSphStatNonFinite] != 0);  // the NaN velocity reaches its neighbours' viscosity
  const auto index = b.download(s.grid.sorted_index);
  const auto acc = b.download(s.accel);
  const uint32_t first = ~w[kSphStatNonFinite];
  CHECK(!std::isfinite(acc[first].x + acc[first].y + acc[first].z));
  for (uint32_t i = 0; i < first; ++i) CHECK(std::isfinite(acc[i].x + acc[i].y + acc[i].z));
  (void)index;
}

TEST_CASE("sph kernel parameters out of range are rejected, naming the field") {
  Backend& b = test::backend();
  const test::SphCase c = test::make_sph_case(4, SphPressureModel::wcsph, 1);
  test::SphBuffers s = test::upload_sph_case(b, c);
  auto density = [&](SphStepParams p) {
    sph_density(b, p, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
  };
  SphStepParams p = c.params;
  p.h = -1;
  CHECK_THROWS_WITH_AS(density(p), doctest::Contains("invalid h = -1"), Error);
  p = c.params;
  p.h = 1.0;  // larger than the cells
  CHECK_THROWS_WITH_AS(density(p), doctest::Contains("cell_size"), Error);
  p = c.params;
  p.viscosity = std::nan("");
  CHECK_THROWS_WITH_AS(density(p), doctest::Contains("viscosity"), Error);
  p = c.params;
  p.max_candidates = 70000;
  CHECK_THROWS_WITH_AS(density(p), doctest::Contains("max_candidates"), Error);
  p = c.params;
  p.n = c.params.n + 1;
  CHECK_THROWS_WITH_AS(density(p), doctest::Contains("n ="), Error);
  SphIntegrateParams ip;
  ip.n = c.params.n;
  ip.dt = 0;
  CHECK_THROWS_WITH_AS(sph_integrate(b, ip,
                                     {&s.sorted_pos, &s.sorted_vel, nullptr, &s.accel, &s.pos,
                                      &s.vel, nullptr, nullptr, &s.stats}),
                       doctest::Contains("dt"), Error);
  ip.dt = 1e-3;
  ip.op = SphStageOp::rk4_stage2;
  CHECK_THROWS_WITH_AS(sph_integrate(b, ip,
                                     {&s.sorted_pos, &s.sorted_vel, nullptr, &s.accel, &s.pos,
                                      &s.vel, nullptr, nullptr, &s.stats}),
                       doctest::Contains("vk"), Error);
}

TEST_CASE("sph and dfsph kernels refuse a grid whose tables are not prefix ranges") {
  Backend& b = test::backend();
  const test::SphCase c = test::make_sph_case(4, SphPressureModel::dfsph, 2);
  test::SphBuffers s = test::upload_sph_case(b, c);
  // The same points, grid and order by the radix build, whose empty cells read [0, 0): a row
  // read from its first cell's start to its last one's end would be wrong there.
  build_hash_grid(b, s.grid, s.pos);
  REQUIRE(!s.grid.prefix_ranges);
  const auto refused = doctest::Contains("not prefix ranges");
  CHECK_THROWS_WITH_AS(
      sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats}),
      refused, Error);
  CHECK_THROWS_WITH_AS(sph_forces(b, c.params,
                                  {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(),
                                   &s.accel, &s.stats}),
                       refused, Error);
  DfsphCaseBuffers d = make_dfsph_buffers(b, c.params.n, "test dfsph");
  const DfsphIO io = dfsph_io(s, d);
  CHECK_THROWS_WITH_AS(dfsph_factor(b, DfsphParams{c.params}, io), refused, Error);
  CHECK_THROWS_WITH_AS(dfsph_rate(b, DfsphParams{c.params}, io), refused, Error);
  CHECK_THROWS_WITH_AS(dfsph_correct(b, DfsphParams{c.params}, io), refused, Error);
  // The counting build again: accepted.
  build_hash_grid(b, s.grid, s.pos, {GridBuild::counting, c.params.n});
  CHECK_NOTHROW(
      sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats}));
}
