// lavapipe silently stops a shader invocation after 65,535 loop iterations (PLATFORM.md): every
// kernel is driven here at its worst case on a backend that counts loop iterations
// (test::loop_counter, Vulkan with loop counting), and the largest count any invocation reached
// must stay below the device's Capabilities::max_loop_iterations. The other backends skip this
// suite (test_main.cpp says so); the coverage test below runs everywhere.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "engine/atom/orbital_tables.h"
#include "engine/core/error.h"
#include "engine/volume/preintegration.h"
#if MASAV_HAVE_VULKAN
#include "compute/sph_walk_choice.h"
#endif
#include "engine/grid/hash_grid.h"
#include "engine/kernels/atom_checks.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_particles.h"
#include "tests/backend_fixture.h"
#include "tests/loop_limit.h"
#include "tests/sph_fixture.h"

using namespace masav;

namespace {

std::vector<Vec4f> cluster(uint32_t n, float extent, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, extent);
  std::vector<Vec4f> p(n);
  for (auto& v : p) v = {u(rng), u(rng), u(rng), 0.0f};
  return p;
}

// One crowded cell of 3,000 particles: every particle is every particle's candidate, and the
// walls' images reach every particle (the box is one support radius wide).
struct CrowdedCell {
  uint32_t n = 3000;
  float h = 0.05f;
  SphStepParams p;
  Buffer<Real4> pos, vel;
  std::vector<Vec4f> pts;
  HashGrid g;
};
CrowdedCell crowded_cell(Backend& b, SphPressureModel model, uint64_t seed) {
  CrowdedCell c;
  const uint32_t n = c.n;
  const float h = c.h;
  SphStepParams& p = c.p;
  p.grid = make_grid_params({0, 0, 0}, h, {1, 1, 1}, n);
  p.n = n;
  p.model = model;
  p.h = h;
  p.mass = lattice_mass(1000.0, 0.025, h, model == SphPressureModel::dfsph);
  p.max_candidates = n;
  p.walls = true;
  p.box_min = {0, 0, 0};
  p.box_max = {h, h, h};
  c.pos = b.create<Real4>(n, "pos");
  c.vel = b.create<Real4>(n, "vel");
  c.pts = cluster(n, h, seed);
  for (auto& q : c.pts) q.w = 1.0f;
  b.upload(c.pos, c.pts);
  b.upload(c.vel, std::vector<Vec4f>(n));
  c.g = make_hash_grid(b, p.grid, n);
  build_hash_grid(b, c.g, c.pos, {GridBuild::counting, n});
  return c;
}

}  // namespace

TEST_CASE("every kernel of kernels.inc has a loop-limit case") {
  for (KernelId k : kAllKernels) {
    CAPTURE(kernel_name(k));
    CHECK(test::loop_limit_covered().count(k) == 1);
  }
}

LOOP_LIMIT_CASE("philox kernels loop a fixed, small number of times", KernelId::philox_u32,
                KernelId::philox_uniform) {
  Backend& b = test::loop_counter();
  auto out = b.create<uint32_t>(1 << 16, "words");
  b.philox_u32({1, 2, 3}, out);
  const uint32_t ticks = test::ticks_of(b);
  CHECK(ticks == 10 + 4);  // ten rounds, four output words
}

LOOP_LIMIT_CASE("radix sort and its scans stay far below the loop limit at 2^20 keys",
                KernelId::radix_sort) {
  Backend& b = test::loop_counter();
  const uint32_t n = 1 << 20;
  std::vector<uint32_t> keys(n);
  std::mt19937 rng(5);
  for (auto& k : keys) k = rng();
  auto kb = b.create<uint32_t>(n, "keys");
  auto vb = b.create<uint32_t>(n, "values");
  b.upload(kb, keys);
  b.radix_sort({n, 32}, kb, &vb);
  const uint32_t ticks = test::ticks_of(b);
  MESSAGE("radix_sort worst invocation: " << ticks << " loop iterations");
  CHECK(ticks > 0);
  // Independent of n. Tiled scatter: a few loops over the tile and the subgroups (~300).
  // Subgroup scatter: the digit table (256 / subgroup) plus 256 rounds of 1 + 8 ballot steps.
  CHECK(ticks <= 256 / 4 + 256 * 9);
}

LOOP_LIMIT_CASE("neighbour count: loop ticks = 27 cells + candidates, capped below the limit",
                KernelId::grid_count_neighbors) {
  Backend& b = test::loop_counter();
  const uint32_t n = 4000;
  const GridParams gp = make_grid_params({0, 0, 0}, 1.0f, {1, 1, 1}, n);  // one crowded cell
  auto pos = b.create<Real4>(n, "pos");
  b.upload(pos, cluster(n, 1.0f, 9));
  HashGrid g = make_hash_grid(b, gp, n);
  build_hash_grid(b, g, pos);
  (void)test::ticks_of(b);
  auto counts = b.create<uint32_t>(n, "counts");
  NeighborParams np = make_neighbor_params(gp, 1.0f);
  np.max_candidates = n;
  b.grid_count_neighbors(np, pos, g.cell_start, g.cell_end, counts);
  CHECK(test::ticks_of(b) == 27 + n);  // the counter measures what we think it does
  // The validated maximum of max_candidates keeps the worst invocation under the limit.
  NeighborParams worst = np;
  worst.max_candidates = 65000;
  CHECK(27 + worst.max_candidates + 1 < test::loop_counter().caps().max_loop_iterations);
  worst.max_candidates = 65001;
  CHECK_THROWS_AS(b.grid_count_neighbors(worst, pos, g.cell_start, g.cell_end, counts), Error);
}

LOOP_LIMIT_CASE("grid assignment, ranges and gather do not loop", KernelId::grid_assign_cells,
                KernelId::grid_cell_ranges, KernelId::gather) {
  Backend& b = test::loop_counter();
  const uint32_t n = 100000;
  const GridParams gp = make_grid_params({0, 0, 0}, 0.05f, {20, 20, 20}, n);
  auto pos = b.create<Real4>(n, "pos");
  b.upload(pos, cluster(n, 1.0f, 4));
  HashGrid g = make_hash_grid(b, gp, n);
  b.grid_assign_cells(gp, pos, g.sorted_cells, g.sorted_index);
  CHECK(test::ticks_of(b) == 0);
  b.radix_sort({n, grid_key_bits(gp)}, g.sorted_cells, &g.sorted_index);
  (void)test::ticks_of(b);
  b.grid_cell_ranges(gp, g.sorted_cells, g.cell_start, g.cell_end);
  auto sorted = b.create<Real4>(n, "sorted");
  reorder(b, g, pos.impl(), sorted.impl());
  CHECK(test::ticks_of(b) == 0);
}

LOOP_LIMIT_CASE("orbital_sample: three bounded binary searches (exact) or one (shells)",
                KernelId::orbital_sample) {
  Backend& b = test::loop_counter();
  for (OrbitalPlacement pl : {OrbitalPlacement::exact, OrbitalPlacement::shells}) {
    const auto t = atom::make_orbital_tables({5, 3, -2, true}, pl, 20000, 1);
    auto tables = b.create<uint32_t>(t.cdf.size(), "tables");
    b.upload(tables, t.cdf);
    auto pos = b.create<Real4>(t.params.count, "positions");
    (void)test::ticks_of(b);
    b.orbital_sample(t.params, tables, pos);
    const uint32_t ticks = test::ticks_of(b);
    MESSAGE("orbital_sample (placement " << int(pl) << "): " << ticks << " loop iterations");
    CHECK(ticks > 10);
    CHECK(ticks <= 10 + 3 * 25);  // Philox's ten rounds + at most 25 halvings per table (2^24 bins)
  }
}

LOOP_LIMIT_CASE("cloud_density does not loop", KernelId::cloud_density) {
  Backend& b = test::loop_counter();
  const GridParams g = make_grid_params({0, 0, 0}, 0.1f, {16, 16, 16}, 1000);
  auto start = b.create<uint32_t>(16 * 16 * 16, "cell start");
  auto end = b.create<uint32_t>(16 * 16 * 16, "cell end");
  auto density = b.create<Real>(16 * 16 * 16, "density");
  b.fill(start, 0u);
  b.fill(end, 0u);
  (void)test::ticks_of(b);
  b.cloud_density({g, 1000}, start, end, density);
  CHECK(test::ticks_of(b) == 0);
}

LOOP_LIMIT_CASE("scatter_table: the event cap bounds a photon that never escapes",
                KernelId::scatter_table) {
  Backend& b = test::loop_counter();
  ScatterTableParams p;
  p.rows = 1;
  p.first_row = 1;
  p.tau_step = 1e4f;  // optically so thick that no photon leaves
  p.albedo = 1.0f;
  p.weight_threshold = 0.0f;
  p.max_scatterings = 5000;  // the validated maximum
  p.photons_per_row = 32;
  p.start = ScatterStart::centre;
  const uint32_t entries = p.bins + kScatterExtras;
  auto table = b.create<Real>(entries, "table");
  auto hits = b.create<uint32_t>(entries, "hits");
  (void)test::ticks_of(b);
  b.scatter_table(p, table, hits);
  const uint32_t ticks = test::ticks_of(b);
  MESSAGE("scatter_table at 5000 events: " << ticks << " loop iterations");
  CHECK(ticks >= 5001 * 11);  // each event: one iteration plus Philox's ten rounds
  CHECK(ticks < test::loop_counter().caps().max_loop_iterations);
  CHECK(b.download(hits)[p.bins + kScatterCapped] == p.photons_per_row);
}

LOOP_LIMIT_CASE("nebula paths: voxel traversal and the smallest midpoint step stay below the limit",
                KernelId::nebula_illuminate, KernelId::nebula_view) {
  Backend& b = test::loop_counter();
  NebulaLightParams p;
  p.grid = make_grid_params({-8, -8, -8}, 0.25f, {64, 64, 64}, 2);
  p.viewer = {9, 9, 9};
  auto pos = b.create<Real4>(2, "positions");
  b.upload(pos, std::vector<Vec4f>{{-7.99f, -7.99f, -7.99f, 0}, {7.9f, -7.9f, 7.9f, 0}});
  auto density = b.create<Real>(64 * 64 * 64, "density");
  b.upload(density, std::vector<double>(64 * 64 * 64, 0.01));
  auto table = b.create<Real>(size_t(p.table_rows) * p.table_bins, "table");
  b.upload(table, std::vector<double>(size_t(p.table_rows) * p.table_bins, 0.01));
  auto ill = b.create<Real>(2, "illumination"), light = b.create<Real>(2, "light");
  for (OpticalPath path : {OpticalPath::exact, OpticalPath::midpoint}) {
    p.path = path;
    p.step_a0 =
        path == OpticalPath::midpoint ? float(16 * std::sqrt(3.0) / kMaxPathSteps) * 1.0001f : 0.1f;
    (void)test::ticks_of(b);
    b.nebula_illuminate(p, pos, density, ill);
    b.nebula_view(p, pos, density, table, ill, light);
    const uint32_t ticks = test::ticks_of(b);
    MESSAGE("nebula path " << int(path) << ": " << ticks << " loop iterations");
    CHECK(ticks < test::loop_counter().caps().max_loop_iterations);
    if (path == OpticalPath::exact)
      CHECK(ticks <= 3 * 64 + 3 + 6);
    else
      CHECK(ticks > 50000);  // the diagonal at the smallest step
  }
  p.step_a0 *= 0.5f;  // below the validated step: refused before dispatch
  CHECK_THROWS_AS(b.nebula_view(p, pos, density, table, ill, light), Error);
}

LOOP_LIMIT_CASE("voxelize does not loop; volume_bricks at the largest brick stays below the limit",
                KernelId::voxelize, KernelId::volume_bricks) {
  Backend& b = test::loop_counter();
  VoxelizeParams vp;
  vp.grid = make_grid_params({0, 0, 0}, 0.1f, {10, 10, 10}, 1000);
  auto pos = b.create<Real4>(1000, "pos");
  b.upload(pos, cluster(1000, 1.0f, 2));
  auto light = b.create<Real>(1000, "light");
  b.upload(light, std::vector<double>(1000, 0.5));
  auto p = b.create<Real>(1000, "p"), g = b.create<Real>(1000, "g"), s = b.create<Real>(1000, "s");
  (void)test::ticks_of(b);
  b.voxelize(vp, pos, light, p, g, s);
  CHECK(test::ticks_of(b) == 0);
  const VolumeDesc vol = make_volume_desc({64, 64, 64}, {0, 0, 0}, {1, 1, 1});
  auto v = b.create<Real>(64 * 64 * 64, "volume");
  b.upload(v, std::vector<double>(64 * 64 * 64, 0.5));
  auto tf = b.create<Real4>(4096, "tf");
  std::vector<Vec4d> tfv(4096, Vec4d{1, 1, 1, 0.1});
  b.upload(tf, tfv);
  auto bricks = b.create<Real4>(64, "bricks");
  b.volume_bricks({vol, 16, 4096}, v, tf, bricks);
  const uint32_t ticks = test::ticks_of(b);
  MESSAGE("volume_bricks, brick 16: " << ticks << " loop iterations");
  // The voxels of the first brick with its apron, and 2 TF entries.
  CHECK(ticks == 17 * 17 * 17 + 2);
  CHECK(ticks < test::loop_counter().caps().max_loop_iterations);
}

LOOP_LIMIT_CASE("volume_brick_skip walks 2 radius + 1 bricks at most",
                KernelId::volume_brick_skip) {
  Backend& b = test::loop_counter();
  BrickSkipParams p;
  p.bricks = {600, 2, 2};
  p.radius = kBrickSkipMaxRadius;
  auto bricks = b.create<Real4>(2400, "bricks");
  b.upload(bricks, std::vector<Vec4d>(2400, Vec4d{0, 0, 0, 1}));
  auto distances = b.create<uint32_t>(4800, "distances");
  uint32_t worst = 0;
  for (p.axis = 0; p.axis < 3; ++p.axis) {
    (void)test::ticks_of(b);
    b.volume_brick_skip(p, bricks, distances);
    worst = std::max(worst, test::ticks_of(b));
  }
  MESSAGE("volume_brick_skip at radius " << p.radius << ": " << worst << " loop iterations");
  CHECK(worst == 2 * kBrickSkipMaxRadius + 1);
}

LOOP_LIMIT_CASE(
    "raymarch: the smallest validated step stays below the limit; skipping and ERT cut it",
    KernelId::raymarch) {
  Backend& b = test::loop_counter();
  const VolumeDesc vol = make_volume_desc({64, 64, 64}, {0, 0, 0}, {1, 1, 1});
  auto v = b.create<Real>(64 * 64 * 64, "volume");
  auto tf = b.create<Real4>(2, "tf");
  auto bricks = b.create<Real4>(512, "bricks");
  auto img = b.create<Real4>(64, "image");
  auto table = b.create<Real4>(kPreintegratedPerEntry * 2, "pre-integrated table");
  RaymarchParams rp;
  rp.volume = vol;
  rp.width = rp.height = 8;
  rp.eye = {-0.5f, -0.5f, -0.5f};
  rp.target = {1, 1, 1};
  rp.up = {0, 0, 1};
  rp.fov_y_deg = 2;
  rp.tf_size = 2;
  rp.termination_alpha = 1.0f;
  rp.skip_empty = false;
  rp.brick = 8;  // 8^3 bricks of 8 voxels
  rp.step = 1.0f;
  const uint64_t fixed = max_ray_segments(rp) - 2 + 3 * 24 + 16;  // what check_raymarch adds
  rp.step = float(std::sqrt(3.0) / double(kMaxRaySteps - fixed)) * 1.001f;
  auto run = [&](double value, double alpha) {
    b.upload(v, std::vector<double>(64 * 64 * 64, value));
    b.upload(tf, std::vector<Vec4d>{{1, 1, 1, alpha}, {1, 1, 1, alpha}});
    b.volume_bricks({vol, rp.brick, 2}, v, tf, bricks);
    b.upload(table, volume::preintegrate_transfer({{1, 1, 1, alpha}, {1, 1, 1, alpha}}));
    (void)test::ticks_of(b);
    b.raymarch(rp, v, tf, bricks, img, &table);
    return test::ticks_of(b);
  };
  const uint32_t worst = run(0.5, 1e-6);
  MESSAGE("raymarch at the smallest step: " << worst << " loop iterations");
  CHECK(worst > 55000);  // all the segments ran (a nested loop once made lavapipe stop at 32,768)
  CHECK(worst < test::loop_counter().caps().max_loop_iterations);
  rp.preintegrate = true;
  const uint32_t worst_pre = run(0.5, 1e-6);
  MESSAGE("pre-integrated at the smallest step: " << worst_pre << " loop iterations");
  CHECK(worst_pre > 55000);
  CHECK(worst_pre < test::loop_counter().caps().max_loop_iterations);
  rp.preintegrate = false;
  rp.skip_empty = true;
  const uint32_t empty = run(0.5, 0.0);  // every brick empty, stride 1: one step per brick
  MESSAGE("raymarch through empty bricks: " << empty << " loop iterations");
  CHECK(empty < 200);
  // With the strides the whole grid of 8^3 bricks is one empty cube: one lookup per ray.
  BrickSkipParams s;
  s.bricks = {8, 8, 8};
  auto distances = b.create<uint32_t>(1024, "distances");
  for (s.axis = 0; s.axis < 3; ++s.axis) b.volume_brick_skip(s, bricks, distances);
  (void)test::ticks_of(b);
  b.raymarch(rp, v, tf, bricks, img, &table);
  const uint32_t strided = test::ticks_of(b);
  MESSAGE("raymarch through empty bricks with strides: " << strided << " loop iterations");
  CHECK(strided <= 2);
  CHECK(strided < empty);
  rp.termination_alpha = 0.99f;
  rp.reference_step = rp.step;
  const uint32_t dense = run(0.5, 0.5);  // opaque after seven samples
  CHECK(dense < 100);
  rp.step *= 0.9f;
  CHECK_THROWS_AS(b.raymarch(rp, v, tf, bricks, img, &table), Error);
}

LOOP_LIMIT_CASE("drift_points loops three times (one per axis), independent of n",
                KernelId::drift_points) {
  Backend& b = test::loop_counter();
  const uint32_t n = 100000;
  auto start = b.create<float>(4 * n, "start");
  auto dir = b.create<float>(4 * n, "direction");
  auto pos = b.create<Real4>(n, "positions");
  b.philox_uniform({1, 0, 0}, start);
  b.philox_uniform({1, 1, 0}, dir);
  (void)test::ticks_of(b);
  DriftParams p;
  p.n = n;
  p.time_s = 100.0f;
  b.drift_points(p, start, dir, pos);
  CHECK(test::ticks_of(b) == 3);
}

LOOP_LIMIT_CASE("sph kernels: loop ticks = rows + cells + candidates, capped below the limit",
                KernelId::sph_density, KernelId::sph_forces, KernelId::sph_integrate) {
  Backend& b = test::loop_counter();
  CrowdedCell cc = crowded_cell(b, SphPressureModel::wcsph, 12);
  const uint32_t n = cc.n;
  const float h = cc.h;
  SphStepParams& p = cc.p;
  auto &pos = cc.pos, &vel = cc.vel;
  const std::vector<Vec4f>& pts = cc.pts;
  HashGrid& g = cc.g;
  auto rho = b.create<Real>(n, "rho"), pr = b.create<Real>(n, "p");
  auto acc = b.create<Real4>(n, "acc");
  auto stats = b.create<uint32_t>(kSphStatWords, "stats");
  b.fill(stats, 0u);
  (void)test::ticks_of(b);
  const SphGridView view = sph_grid_view(g);
  sph_density(b, p, {&pos, view, &rho, &pr, &stats});
  // x loop 3 + y loop 9 + the crowded row (a row's range is two loads and the cooperative walk's
  // row unions written-out butterflies, no loops): walked together in chunks of C (1 + C ticks
  // each, C the smallest subgroup) when that costs at most the extra budget (260,
  // shaders/common/sph_coop.glsl) over the n candidates of the per-lane walk (C = 32 on NVIDIA:
  // 102 extra), else per lane (C = 8 on lavapipe: 375 extra). sph_forces spells the wall
  // images out per neighbour, not looped over: they add no tick to its walk.
#if MASAV_HAVE_VULKAN
  const bool coop = vk::sph_coop_walk(b.tuning().vulkan, b.caps().device_type);
#else
  const bool coop = false;  // only Vulkan counts loop ticks
#endif
  const uint32_t c = std::min(b.caps().min_subgroup_size, 32u);  // clusters of at most 32
  const uint32_t together = (n + c - 1) / c * (c + 1);
  const uint32_t row = coop && together - n <= 260 ? together : n;
  MESSAGE("subgroup ", c, ": the crowded row costs ", row, " ticks (", n, " candidates)");
  // Within h of the walls, sph_density then walks each particle's neighbours within h again
  // (itself included) for their wall images: the most any particle has.
  const uint32_t images = b.download(stats)[kSphStatMaxNeighbors];
  CHECK(images > 1);
  CHECK(test::ticks_of(b) == 3 + 9 + row + images);
  sph_forces(b, p, {&pos, &vel, &rho, &pr, view, &acc, &stats});
  CHECK(test::ticks_of(b) == 3 + 9 + row);
  // The worst any SPH kernel can do: 3 + 9 row loops, the cooperative walk's extra budget (260,
  // shaders/common/sph_coop.glsl) and two walks over the validated maximum of candidates (32,500:
  // sph_density's candidates and its neighbours' images) stay under lavapipe's limit; one more
  // candidate is refused.
  const uint32_t cap = max_sph_candidates(test::loop_counter().caps().max_loop_iterations);
  CHECK(cap == 32500);
  CHECK(3 + 9 + 260 + kSphWalks * cap < test::loop_counter().caps().max_loop_iterations);

  // Over neighbour row masks: recording them adds no loop to sph_density; sph_forces walks per
  // lane a row too long for its mask whole, so the crowded row costs what it did, and a row that
  // fits one pass per neighbour (at most its candidates). Where it adds the wall images after
  // its walk (compute/sph_walk_choice.h), a lane near a wall walks its rows a second time. Its
  // worst case, 3 + 9 + 2 x 32,500, is then sph_density's bound above.
#if MASAV_HAVE_VULKAN
  const uint32_t walks = vk::sph_images_after(b.tuning().vulkan, b.caps().device_type) ? 2 : 1;
#else
  const uint32_t walks = 1;
#endif
  MESSAGE("sph_forces walks its masked rows ", walks, " time(s) near the walls");
  auto rows = b.create<uint32_t>(size_t(kSphRowMaskWords) * n, "rows");
  sph_density(b, p, {&pos, view, &rho, &pr, &stats, &rows});
  CHECK(test::ticks_of(b) == 3 + 9 + row + images);
  sph_forces(b, p, {&pos, &vel, &rho, &pr, view, &acc, &stats, &rows});
  CHECK(test::ticks_of(b) == 3 + 9 + walks * n);
  const uint32_t few = 50;  // one row that fits a mask
  SphStepParams q = p;
  q.grid.n = q.n = q.max_candidates = few;
  auto pos_q = b.create<Real4>(few, "pos few");
  b.upload(pos_q, std::vector<Vec4f>(pts.begin(), pts.begin() + few));
  HashGrid gq = make_hash_grid(b, q.grid, few);
  build_hash_grid(b, gq, pos_q, {GridBuild::counting, few});
  const SphGridView vq = sph_grid_view(gq);
  sph_density(b, q, {&pos_q, vq, &rho, &pr, &stats, &rows});
  (void)test::ticks_of(b);
  sph_forces(b, q, {&pos_q, &vel, &rho, &pr, vq, &acc, &stats, &rows});
  const std::vector<uint32_t> words = b.download(rows);
  uint32_t most = 0;  // the most neighbours any particle has, itself included
  for (uint32_t i = 0; i < few; ++i) most = std::max(most, test::row_mask_bits(words, i, few));
  CHECK(most > 1);
  CHECK(most <= few);
  CHECK(test::ticks_of(b) == 3 + 9 + walks * most);

  p.max_candidates = cap;
  CHECK_NOTHROW(sph_density(b, p, {&pos, view, &rho, &pr, &stats}));
  (void)test::ticks_of(b);
  p.max_candidates = cap + 1;
  CHECK_THROWS_AS(sph_density(b, p, {&pos, view, &rho, &pr, &stats}), Error);

  // The integrator's only loops are the walls' (at most 3 + 3).
  SphIntegrateParams ip;
  ip.n = n;
  ip.op = SphStageOp::euler;
  ip.tangential_damping = 0.1;
  ip.box_max = {0.5 * h, 0.5 * h, 0.5 * h};
  auto xo = b.create<Real4>(n, "xo"), vo = b.create<Real4>(n, "vo");
  sph_integrate(b, ip, {&pos, &vel, nullptr, &acc, &xo, &vo, nullptr, nullptr, &stats});
  CHECK(test::ticks_of(b) <= 6);
}

LOOP_LIMIT_CASE("dfsph kernels: loop ticks = rows + cells + candidates, as sph_forces' masked walk",
                KernelId::dfsph_factor, KernelId::dfsph_rate, KernelId::dfsph_correct) {
  Backend& b = test::loop_counter();
  CrowdedCell cc = crowded_cell(b, SphPressureModel::dfsph, 13);
  const uint32_t n = cc.n;
  SphStepParams& p = cc.p;
  auto &pos = cc.pos, &vel = cc.vel;
  HashGrid& g = cc.g;
  auto rho = b.create<Real>(n, "rho"), pr = b.create<Real>(n, "p");
  auto factor = b.create<Real>(n, "factor"), kappa = b.create<Real>(n, "kappa"),
       kappa_sum = b.create<Real>(n, "kappa sum");
  auto residual = b.create<uint32_t>(kDfsphResidualWords, "residual");
  auto stats = b.create<uint32_t>(kSphStatWords, "stats");
  auto rows = b.create<uint32_t>(size_t(kSphRowMaskWords) * n, "rows");
  b.fill(stats, 0u);
  b.fill(kappa_sum, 0u);
  const SphGridView view = sph_grid_view(g);
  // Each kernel, walking every candidate and over the masks (the crowded row is too long for
  // its mask, so it is walked whole either way): x loop 3 + y loop 9 + n
  // candidates, one pass each; the wall images are spelled out, not looped over.
  for (const bool masked : {false, true}) {
    CAPTURE(masked);
    sph_density(b, p, {&pos, view, &rho, &pr, &stats, masked ? &rows : nullptr});
    (void)test::ticks_of(b);
    DfsphIO io;
    io.positions = &pos;
    io.velocities = &vel;
    io.density = &rho;
    io.factor = &factor;
    io.grid = view;
    io.kappa = &kappa;
    io.kappa_sum = &kappa_sum;
    io.residual = &residual;
    io.stats = &stats;
    io.neighbor_rows = masked ? &rows : nullptr;
    const DfsphParams dp{p, DfsphSolve::density, 1e-3};
    dfsph_factor(b, dp, io);
    CHECK(test::ticks_of(b) == 3 + 9 + n);
    dfsph_rate(b, dp, io);
    CHECK(test::ticks_of(b) == 3 + 9 + n);
    dfsph_correct(b, dp, io);
    CHECK(test::ticks_of(b) == 3 + 9 + n);
  }
  // The worst case, 3 + 9 + the validated maximum of candidates, is below sph_density's
  // (the case above); one more candidate is refused.
  p.max_candidates = max_sph_candidates(b.caps().max_loop_iterations) + 1;
  CHECK_THROWS_AS(
      dfsph_factor(b, DfsphParams{p},
                   DfsphIO{&pos, &vel, &rho, &factor, view, &kappa, &kappa_sum, &residual, &stats}),
      Error);
}
