// Cross-checks of the atom kernels (SPEC §2) for the atom and atom-volume scenes, with the
// tolerances the kernel tests established (tests/test_{orbital,nebula,scatter,volume}.cpp).
// Inputs are built on the host from the scene's parameters (its state, scattering table and
// grids) and uploaded identically to both backends; float results are compared against the
// reference's double precision.
#include "engine/atom/atom_cross_checks.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "engine/atom/atom_schema.h"
#include "engine/atom/orbital.h"
#include "engine/atom/orbital_tables.h"
#include "engine/atom/scatter_cache.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/grid/hash_grid.h"
#include "engine/kernels/atom_checks.h"
#include "engine/volume/brick_skip.h"
#include "engine/volume/preintegration.h"
#include "engine/volume/transfer_function.h"

namespace masav::verify {
namespace {

using atom::state_of;

// The scene's parameters, or the atom defaults when a check runs without a scene.
const scene::ParamSet& params_of(const CheckInputs& in) {
  static const scene::ParamSet defaults = [] {
    scene::ParamSet p;
    for (const auto* t : {&atom::atom_table(), &atom::nebula_table(), &atom::scatter_table_schema(),
                          &atom::volume_table()})
      p.add_table(*t);
    return p;
  }();
  return in.params.has_table("atom") ? in.params : defaults;
}

float half_width(const scene::ParamSet& p) {
  return float(atom::box_half_width(state_of(p), p.get_real("nebula.box_probability")));
}

GridParams cube_grid(const scene::ParamSet& p, uint32_t dims, uint32_t n) {
  const float h = half_width(p);
  return make_grid_params({-h, -h, -h}, 2 * h / float(dims), {dims, dims, dims}, n);
}

// The checks' grids have at most this many cells per axis: the kernels are the same at any
// size, the lighting tolerances below were measured on 60^3 grids, and a 512^3 grid (legal in a
// scene) would make the check allocate gigabytes (the scene itself is refused on devices whose
// buffers cannot hold it, with the largest size that fits).
constexpr int64_t kMaxCheckDims = 64;

uint32_t check_dims(const scene::ParamSet& p, const char* key) {
  return uint32_t(std::min(p.get_int(key), kMaxCheckDims));
}

GridParams density_grid(const CheckInputs& in) {
  const scene::ParamSet& p = params_of(in);
  return cube_grid(p, check_dims(p, "nebula.density_dims"), in.points);
}

// Check points spread over the cloud's cube (uniform: every cell of the grid gets some).
Buffer<Real4> cloud_points(Backend& b, const CheckInputs& in, const GridParams& g) {
  CheckInputs at = in;
  at.grid = g;
  auto pos = b.create<Real4>(in.points, "check positions");
  b.upload(pos, check_points(at));
  return pos;
}

std::vector<double> flatten(const std::vector<Vec4d>& v, bool with_w = true) {
  std::vector<double> out;
  out.reserve(4 * v.size());
  for (const Vec4d& x : v) {
    out.insert(out.end(), {x.x, x.y, x.z});
    if (with_w) out.push_back(x.w);
  }
  return out;
}

// The lighting checks' tolerances were measured at the thesis's optical depth (tau_peak 0.5,
// albedo 0.6). Light is attenuated by exp(-tau) with tau proportional to tau_peak / albedo, and
// fp32's error in exp(-tau) grows with tau: deeper clouds are allowed more, three times as fast
// as the depth grows (the worst state, 5, measured 22x the error at 20x the depth and 68x at 60x;
// the others at most 17x at 60x).
double depth_factor(const CheckInputs& in) {
  const scene::ParamSet& p = params_of(in);
  const double depth = p.get_real("nebula.tau_peak") / p.get_real("scatter.albedo");
  return std::max(1.0, 3.0 * depth / (0.5 / 0.6) - 2.0);
}

// Below this, light has left fp32's range in all but a few bits (its smallest normal number is
// 1.2e-38): both sides are compared as zero there (a cloud that dark is black on every backend).
constexpr double kDarkLight = 1e-30;

void flush_dark(CheckOutputs& outs) {
  for (auto& o : outs)
    for (double& v : o.reals)
      if (std::abs(v) < kDarkLight) v = 0;
}

// A lighting check: relative errors taken against `floor` times the largest reference value
// (light spans many decades; tiny values carry fp32's absolute error), tolerances scaled by the
// optical depth, values below kDarkLight compared as zero.
KernelCheck lighting_check(KernelId kernel, Tolerance tol, double floor,
                           std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  KernelCheck k = tolerance_check(kernel, tol, std::move(run));
  k.compare = [tol, floor](const CheckOutputs& got, const CheckOutputs& want,
                           const CheckInputs& in) {
    CheckOutputs g = got, w = want;
    flush_dark(g);
    flush_dark(w);
    Tolerance t = tol;
    const double f = depth_factor(in);
    t.rel_l2 *= f;
    t.max_rel *= f;
    double top = 0;
    for (const auto& o : w)
      for (double v : o.reals) top = std::max(top, std::abs(v));
    t.rel_floor = std::max(floor * top, 1e-30);
    return compare_tolerance(g, w, t);
  };
  return k;
}

// The lighting checks' clouds have at least this many particles: their relative L2 error is an
// average, and over a handful of particles one that starts its path in the neighbouring cell
// in fp32 (see below) dominates it (16 to 64 particles failed where 4096 pass).
constexpr uint32_t kMinLightingPoints = 4096;

CheckInputs lighting_inputs(const CheckInputs& in) {
  CheckInputs at = in;
  at.points = std::max(in.points, kMinLightingPoints);
  return at;
}

// The scattering table the lighting checks read: a small, smooth one computed once on the CPU
// reference (identical input for both backends).
const std::vector<double>& check_phase_table(ScatterTableParams& sp) {
  static std::once_flag once;
  static std::vector<double> table;
  static ScatterTableParams params;
  std::call_once(once, [] {
    params.rows = 100;
    params.tau_step = 0.1f;
    params.photons_per_row = 4096;  // smooth rows: fp32 interpolation weights stay ~1e-6
    cpu::CpuBackend cpu;
    table = atom::make_phase_table(atom::compute_scatter_table(cpu, params));
  });
  sp = params;
  return table;
}

// The lighting kernels on the scene's density grid and optical depth, over a cloud of the
// scene's state sampled once on the CPU reference and rounded to fp32 (identical input for both
// backends; the regime of tests/test_nebula.cpp).
NebulaLightParams light_params(const CheckInputs& in, const ScatterTableParams& sp) {
  const scene::ParamSet& p = params_of(in);
  const atom::OrbitalState state = state_of(p);
  NebulaLightParams lp;
  lp.grid = density_grid(in);
  lp.kappa_a2 =
      float(p.get_real("nebula.tau_peak") / (atom::peak_density(state) * lp.grid.cell_size));
  lp.albedo = float(p.get_real("scatter.albedo"));
  lp.core_radius_a0 = 0.5f * lp.grid.cell_size;
  const float h = half_width(p);
  lp.viewer = {0.4f * h, -2.5f * h, 0.8f * h};
  lp.path = p.get_text("nebula.path") == "midpoint" ? OpticalPath::midpoint : OpticalPath::exact;
  lp.step_a0 = p.get_real("nebula.step_a0") > 0 ? float(p.get_real("nebula.step_a0"))
                                                : 0.5f * lp.grid.cell_size;
  lp.table_rows = sp.rows;
  lp.table_bins = sp.bins;
  lp.table_tau_step = sp.tau_step;
  return lp;
}

std::vector<Vec4f> sampled_cloud(const CheckInputs& in) {
  const scene::ParamSet& p = params_of(in);
  const auto t =
      atom::make_orbital_tables(state_of(p), OrbitalPlacement::exact, in.points, in.seed);
  cpu::CpuBackend cpu;
  auto tables = cpu.create<uint32_t>(t.cdf.size(), "check orbital tables");
  cpu.upload(tables, t.cdf);
  auto pos = cpu.create<Real4>(in.points, "check cloud");
  cpu.orbital_sample(t.params, tables, pos);
  return cpu.download_f32(pos);
}

struct LitCloud {
  Buffer<Real4> pos;
  Buffer<Real> density, illumination;
};

LitCloud lit_cloud(Backend& b, const CheckInputs& in, const NebulaLightParams& lp) {
  LitCloud c;
  c.pos = b.create<Real4>(in.points, "check cloud");
  b.upload(c.pos, sampled_cloud(in));
  HashGrid g = make_hash_grid(b, lp.grid, in.points);
  build_hash_grid(b, g, c.pos);
  c.density = b.create<Real>(grid_cell_count(lp.grid), "check density");
  b.cloud_density({lp.grid, in.points}, g.cell_start, g.cell_end, c.density);
  c.illumination = b.create<Real>(in.points, "check illumination");
  b.nebula_illuminate(lp, c.pos, c.density, c.illumination);
  return c;
}

// A small volume with structure at every scale, its transfer function, and a camera.
struct CheckVolume {
  VolumeDesc desc;
  std::vector<double> values;
  std::vector<Vec4d> tf;
};

CheckVolume check_volume(const CheckInputs& in) {
  const scene::ParamSet& p = params_of(in);
  CheckVolume v;
  const uint32_t d = uint32_t(std::min<int64_t>(p.get_int("volume.dims"), 32));
  const float h = half_width(p);
  v.desc = make_volume_desc({d, d, d}, {-h, -h, -h}, {h, h, h});
  for (uint32_t k = 0; k < d; ++k)
    for (uint32_t j = 0; j < d; ++j)
      for (uint32_t i = 0; i < d; ++i)
        v.values.push_back(0.5 + 0.4 * std::sin(0.4 * i) * std::cos(0.3 * j) + 0.1 * k / d);
  v.tf = volume::resample_transfer(volume::default_transfer_points());
  return v;
}

// The check volume and its transfer function on a backend, with its bricks (the raymarch's
// default size) computed there.
struct BrickedVolume {
  Buffer<Real> volume;
  Buffer<Real4> transfer, bricks, preintegrated;
};

BrickedVolume upload_bricked(Backend& b, const CheckVolume& v) {
  BrickedVolume bv{b.create<Real>(v.values.size(), "check volume"),
                   b.create<Real4>(v.tf.size(), "check transfer"),
                   {}};
  b.upload(bv.volume, v.values);
  b.upload(bv.transfer, v.tf);
  const uint32_t brick = RaymarchParams{}.brick;
  const UVec3 nb = brick_dims(v.desc, brick);
  bv.bricks = b.create<Real4>(size_t(nb.x) * nb.y * nb.z, "check bricks");
  volume::fill_bricks(b, {v.desc, brick, uint32_t(v.tf.size())}, bv.volume, bv.transfer, bv.bricks);
  bv.preintegrated = volume::upload_preintegrated(b, v.tf);
  return bv;
}

}  // namespace

std::vector<KernelCheck> atom_checks() {
  std::vector<KernelCheck> c;
  // orbital_sample: integer tables, Philox uniforms, then fp32 trigonometry: positions agree
  // to 2e-5 of the cloud's extent (tests/test_orbital.cpp).
  {
    KernelCheck k =
        tolerance_check(KernelId::orbital_sample, {}, [](Backend& b, const CheckInputs& in) {
          const scene::ParamSet& p = params_of(in);
          const OrbitalPlacement placement = p.get_text("atom.placement") == "shells"
                                                 ? OrbitalPlacement::shells
                                                 : OrbitalPlacement::exact;
          const auto t = atom::make_orbital_tables(state_of(p), placement, in.points, in.seed);
          auto tables = b.create<uint32_t>(t.cdf.size(), "check orbital tables");
          b.upload(tables, t.cdf);
          auto pos = b.create<Real4>(in.points, "check cloud");
          b.orbital_sample(t.params, tables, pos);
          return CheckOutputs{{"positions xyz", {}, flatten(b.download(pos), false)}};
        });
    k.compare = [](const CheckOutputs& g, const CheckOutputs& w, const CheckInputs& in) {
      const scene::ParamSet& p = params_of(in);
      const auto t = atom::make_orbital_tables(state_of(p), OrbitalPlacement::exact, 1, 1);
      Tolerance tol;
      tol.rel_l2 = 1e-5;
      tol.max_abs = 2e-5 * t.params.radial_max_a0;
      return compare_tolerance(g, w, tol);
    };
    c.push_back(std::move(k));
  }
  // cloud_density: integer counts over N * cell volume: fp32 rounding only.
  c.push_back(tolerance_check(KernelId::cloud_density, {1e-6, 0, 1e-6},
                              [](Backend& b, const CheckInputs& in) {
                                const GridParams g = density_grid(in);
                                Buffer<Real4> pos = cloud_points(b, in, g);
                                HashGrid grid = make_hash_grid(b, g, in.points);
                                build_hash_grid(b, grid, pos);
                                auto d = b.create<Real>(grid_cell_count(g), "check density");
                                b.cloud_density({g, in.points}, grid.cell_start, grid.cell_end, d);
                                return CheckOutputs{{"density", {}, b.download(d)}};
                              }));
  // scatter_table: Monte Carlo; the photon histograms must be the same distribution
  // (two-sample chi-square, as tests/test_scatter.cpp). A few rows of the scene's table.
  c.push_back(
      chi_square_check(KernelId::scatter_table, 1e-4, [](Backend& b, const CheckInputs& in) {
        ScatterTableParams sp = atom::scatter_params_of(params_of(in));
        sp.first_row = sp.rows > 106 ? 100 : sp.rows / 2;  // rows that do scatter (tau ~ 1)
        sp.rows = std::min<uint32_t>(sp.rows - sp.first_row, 6);
        sp.photons_per_row = std::min<uint32_t>(sp.photons_per_row, 2048);
        sp.seed = in.seed;
        const atom::ScatterTable t = atom::compute_scatter_table(b, sp);
        return CheckOutputs{{"photon hits", t.hits, {}}};
      }));
  // nebula_illuminate / nebula_view: fp32 path integrals and table interpolation against
  // double, relative to 1e-6 of the largest light. The tests' per-value bounds (1e-4, 2e-3)
  // hold on their 24^3 grid; on the scenes' 60^3 grid a few particles sit so close to a cell
  // face that fp32 and fp64 start their path in neighbouring cells (measured up to 8.2e-3 over
  // the ten states on lavapipe), so each value is allowed 2e-2. Those few particles also set
  // the rel L2, which depends on which particles the count draws: over the ten states and
  // 6000 to 50000 particles it measured up to 2.9e-5 (state 7, 15000 particles; under 6e-6 at
  // 65536), so it is allowed 1e-4.
  c.push_back(
      lighting_check(KernelId::nebula_illuminate, {1e-4, 0, 2e-2}, 1e-6,
                     [](Backend& b, const CheckInputs& scene_in) {
                       const CheckInputs in = lighting_inputs(scene_in);
                       ScatterTableParams sp;
                       check_phase_table(sp);
                       const NebulaLightParams lp = light_params(in, sp);
                       LitCloud lc = lit_cloud(b, in, lp);
                       return CheckOutputs{{"illumination", {}, b.download(lc.illumination)}};
                     }));
  c.push_back(lighting_check(KernelId::nebula_view, {1e-4, 0, 2e-2}, 1e-6,
                             [](Backend& b, const CheckInputs& scene_in) {
                               const CheckInputs in = lighting_inputs(scene_in);
                               ScatterTableParams sp;
                               const std::vector<double>& phase = check_phase_table(sp);
                               const NebulaLightParams lp = light_params(in, sp);
                               LitCloud lc = lit_cloud(b, in, lp);
                               auto tab = b.create<Real>(phase.size(), "check phase table");
                               b.upload(tab, phase);
                               auto light = b.create<Real>(in.points, "check light");
                               b.nebula_view(lp, lc.pos, lc.density, tab, lc.illumination, light);
                               return CheckOutputs{{"light", {}, b.download(light)}};
                             }));
  // voxelize: counts exact, means in fp32: 3e-6 absolute on values in [0, 1]
  // (tests/test_volume.cpp).
  c.push_back(
      tolerance_check(KernelId::voxelize, {1e-5, 3e-6, 0}, [](Backend& b, const CheckInputs& in) {
        const scene::ParamSet& p = params_of(in);
        const GridParams g = cube_grid(p, check_dims(p, "volume.dims"), in.points);
        Buffer<Real4> pos = cloud_points(b, in, g);
        std::vector<double> lit(in.points);
        for (uint32_t i = 0; i < in.points; ++i) lit[i] = 0.5 + 0.5 * std::sin(0.37 * i);
        auto light = b.create<Real>(in.points, "check light");
        b.upload(light, lit);
        const size_t cells = grid_cell_count(g);
        auto prob = b.create<Real>(cells, "check p"), mean = b.create<Real>(cells, "check g"),
             sample = b.create<Real>(cells, "check sample");
        VoxelizeParams vp;
        vp.grid = g;
        vp.s = float(p.get_real("volume.s"));
        vp.t = float(p.get_real("volume.t"));
        vp.light_to_unit = 1.5f;
        b.voxelize(vp, pos, light, prob, mean, sample);
        return CheckOutputs{{"p", {}, b.download(prob)},
                            {"g", {}, b.download(mean)},
                            {"sample", {}, b.download(sample)}};
      }));
  // volume_bricks: ranges and the largest alpha: fp32 of values in [0, 1].
  c.push_back(tolerance_check(KernelId::volume_bricks, {1e-6, 2e-6, 0},
                              [](Backend& b, const CheckInputs& in) {
                                const CheckVolume v = check_volume(in);
                                const BrickedVolume bv = upload_bricked(b, v);
                                return CheckOutputs{{"bricks", {}, flatten(b.download(bv.bricks))}};
                              }));
  // volume_brick_skip: integer distances over a pattern of occupied bricks made on the host (a
  // ball, scattered single bricks, strides reaching the radius): bit for bit.
  c.push_back(exact_check(KernelId::volume_brick_skip, [](Backend& b, const CheckInputs&) {
    BrickSkipParams s;
    s.bricks = {23, 17, 11};
    s.radius = 6;
    const size_t n = size_t(s.bricks.x) * s.bricks.y * s.bricks.z;
    std::vector<Vec4d> alpha(n);
    uint32_t h = 0x9e3779b9u;
    for (size_t i = 0; i < n; ++i) {
      h = h * 1664525u + 1013904223u;
      const double x = double(i % s.bricks.x) - 8, y = double(i / s.bricks.x % s.bricks.y) - 9,
                   z = double(i / (size_t(s.bricks.x) * s.bricks.y)) - 5;
      const bool occupied = x * x + y * y + z * z < 20 || (h >> 24) < 6;
      alpha[i] = {0.0, 1.0, occupied ? 0.5 : 0.0, 1.0};
    }
    auto bricks = b.create<Real4>(n, "check bricks");
    b.upload(bricks, alpha);
    auto distances = b.create<uint32_t>(2 * n, "check brick distances");
    for (s.axis = 0; s.axis < 3; ++s.axis) b.volume_brick_skip(s, bricks, distances);
    std::vector<uint32_t> strides;
    for (const Vec4d& v : b.download(bricks)) strides.push_back(uint32_t(v.w));
    return CheckOutputs{{"strides", strides, {}}};
  }));
  // raymarch: fp32 compositing along ~100 steps: rel L2 1e-4; per channel 2e-3 absolute (the
  // kernel test's 1e-4 is for a gentle transfer function; the default one's opacity ramp is
  // steeper: measured 8.8e-4).
  c.push_back(
      tolerance_check(KernelId::raymarch, {1e-4, 2e-3, 0}, [](Backend& b, const CheckInputs& in) {
        const CheckVolume v = check_volume(in);
        const BrickedVolume bv = upload_bricked(b, v);
        const float h = v.desc.box_max.x;
        RaymarchParams rp;
        rp.volume = v.desc;
        rp.width = 48;
        rp.height = 36;
        rp.eye = {1.2f * h, -2.6f * h, 1.5f * h};
        rp.up = {0, 0, 1};
        rp.step = 0.5f * 2 * h / float(v.desc.dims.x);
        rp.reference_step = 2 * rp.step;
        rp.tf_size = uint32_t(v.tf.size());
        auto img = b.create<Real4>(size_t(rp.width) * rp.height, "check image");
        b.raymarch(rp, bv.volume, bv.transfer, bv.bricks, img, nullptr);
        const std::vector<double> plain = flatten(b.download(img));
        // Pre-integrated, at the step of a voxel it is meant for.
        rp.preintegrate = true;
        rp.step = 2 * rp.step;
        b.raymarch(rp, bv.volume, bv.transfer, bv.bricks, img, &bv.preintegrated);
        const std::vector<double> preintegrated = flatten(b.download(img));
        // Clipped across x a little off the middle and shaded (the headlight).
        rp.preintegrate = false;
        rp.step = 0.5f * rp.step;
        rp.clip = {true, 0, 0.45f, true};
        rp.shading.enabled = true;
        b.raymarch(rp, bv.volume, bv.transfer, bv.bricks, img, nullptr);
        return CheckOutputs{{"image", {}, plain},
                            {"image preintegrated", {}, preintegrated},
                            {"image clipped and shaded", {}, flatten(b.download(img))}};
      }));
  return c;
}

}  // namespace masav::verify
