// `masav bench raymarch`: volume ray casting (thesis chapter 3) of the 60^3 electron-cloud volume
// at 512^2 and 1024^2 (and a 256^3 volume at 1920x1080 with --large) on each backend, beside the
// thesis's 32-37 ms per frame; and run time against error: the step against the analytic line
// integral of a linear volume.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "app/bench_atom_common.h"
#include "app/progress.h"
#include "engine/atom/atom_scene.h"
#include "engine/core/error.h"
#include "engine/kernels/atom_checks.h"
#include "engine/volume/ray_integral.h"
#include "engine/volume/transfer_function.h"

namespace masav::app {

struct RaymarchBenchOptions : BenchOptions {
  int reps = 5;
  bool large = false;
  uint32_t brick = RaymarchParams{}.brick;
  std::string state = "state1";
};

namespace {

struct Timed {
  double ms;
  std::vector<Vec4d> image;
};

Timed time_raymarch(Backend& b, const RaymarchParams& rp, const Buffer<Real>& vol,
                    const std::vector<Vec4d>& tf, int reps) {
  atom::RaymarchBuffers r = atom::prepare_raymarch(b, vol, tf, rp);
  const TimingStats s = time_work(b, reps, [&] { atom::raymarch_frame(b, rp, vol, r); });
  return {s.median_ms, b.download(r.image)};
}

// The --large volume: a smooth blob on n^3 voxels with fine detail along x y.
std::vector<float> large_volume(uint32_t n) {
  std::vector<float> v(size_t(n) * n * n);
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t jj = 0; jj < n; ++jj)
      for (uint32_t i = 0; i < n; ++i) {
        const double x = i / 128.0 - 1, y = jj / 128.0 - 1, z = k / 128.0 - 1;
        v[(size_t(k) * n + jj) * n + i] =
            float(std::exp(-3 * (x * x + y * y + z * z)) * (0.6 + 0.4 * std::cos(12 * x * y)));
      }
  return v;
}

int run_raymarch_bench(const RaymarchBenchOptions& o, JsonWriter& j) {
  const ThesisRow* state = nullptr;
  for (const ThesisRow& r : kThesisTable23)
    if (o.state == r.state) state = &r;
  if (!state)
    throw_invalid("masav bench raymarch", "--state", o.state, "a preset state1 .. state10");
  fmt::print(
      "bench raymarch: the {} cloud voxelized on 60^3 (front view, step 1/2 voxel, "
      "empty-space skipping, ERT 0.99), median of {} runs\n",
      o.state, o.reps);
  j.field("thesis_ms_min", kThesisRaymarchMs[0]).field("thesis_ms_max", kThesisRaymarchMs[1]);
  j.key("rows").begin_array();
  auto backends = open_backends(o.choice, "--reps 1");
  // Per backend: 6 rows at 60^3 (+1 at 256^3), then 2 transfer functions x 5 steps x 2.
  Progress progress("raymarch rows", backends.size() * ((o.large ? 7 : 6) + 20));
  const auto tf = volume::resample_transfer(volume::default_transfer_points());
  fmt::print("  {:<8} {:>10} {:>12} {:>10} {:>8} {:>12}\n", "backend", "volume", "image",
             "ms/frame", "fps", "Mrays/s");
  int rc = for_each_backend(backends, [&](Backend& b) {
    auto row = [&](const char* volume, const RaymarchParams& rp, double step_voxels, double ms) {
      const uint32_t w = rp.width, h = rp.height;
      const double rays = double(w) * h / (ms * 1e-3);
      std::string note;
      if (!rp.skip_empty) note += "  (no skipping)";
      if (step_voxels != 0.5) note += fmt::format("  (step {} voxel)", step_voxels);
      if (rp.preintegrate) note += "  (pre-integrated)";
      if (rp.shading.enabled) note += "  (shaded)";
      fmt::print("  {:<8} {:>10} {:>7}x{:<4} {:>10.2f} {:>8.1f} {:>12.1f}{}\n", b.name(), volume, w,
                 h, ms, 1e3 / ms, rays * 1e-6, note);
      begin_row(j, b);
      j.field("volume", volume).field("width", w).field("height", h);
      j.field("skip_empty", rp.skip_empty).field("preintegrate", rp.preintegrate);
      j.field("shade", rp.shading.enabled);
      j.field("step_voxels", step_voxels);
      j.field("median_ms", ms).field("rays_per_s", rays).end_object();
      progress.advance(fmt::format("{} {} {}x{}", b.name(), volume, w, h));
    };
    // The thesis's count for the state.
    atom::AtomScene scene(b, bench_scene_options(state->state, state->particles, 256));
    scene.run_all();
    struct Case {
      uint32_t w, h;
    };
    struct Variant {
      bool skip, preintegrate;
      double step_voxels;
      bool shade = false;
    };
    for (Case c : {Case{512, 512}, Case{1024, 1024}}) {
      // The effects of skipping, of pre-integration (the same step, then twice it) and of
      // gradient shading show at 512^2; the rows alternate so that a machine's load changes both
      // sides alike.
      for (Variant v :
           {Variant{true, false, 0.5}, Variant{false, false, 0.5}, Variant{true, true, 0.5},
            Variant{true, true, 1.0}, Variant{true, false, 0.5, true}}) {
        if (c.w > 512 && (!v.skip || v.preintegrate || v.shade)) continue;
        RaymarchParams rp =
            atom::default_raymarch(scene.volume(), atom::ViewPreset::front, c.w, c.h);
        rp.skip_empty = v.skip;
        rp.preintegrate = v.preintegrate;
        rp.step = float(rp.step * 2 * v.step_voxels);
        rp.brick = o.brick;
        rp.shading.enabled = v.shade;
        row("60^3", rp, v.step_voxels, time_raymarch(b, rp, scene.sample, tf, o.reps).ms);
      }
    }
    if (o.large) {
      const uint32_t n = 256;
      const std::vector<float> v = large_volume(n);
      auto vol = b.create<Real>(v.size(), "volume 256");
      b.upload(vol, std::span<const float>(v));
      const VolumeDesc d = make_volume_desc({n, n, n}, {-1, -1, -1}, {1, 1, 1});
      RaymarchParams rp = atom::default_raymarch(d, atom::ViewPreset::front, 1920, 1080);
      rp.brick = o.brick;
      row("256^3", rp, 0.5, time_raymarch(b, rp, vol, tf, o.reps).ms);
    }
  });
  j.end_array();
  // Step against error: a linear volume on 60^3 whose opacity has a closed form, seen through a
  // transfer function of extinction linear in the value, and through one with a narrow peak
  // (what pre-integration is for).
  const uint32_t n = 60;
  std::vector<double> ramp;
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t jj = 0; jj < n; ++jj)
      for (uint32_t i = 0; i < n; ++i) ramp.push_back((i + jj + k) / (3.0 * (n - 1)));
  const double ref = 0.01;
  // The peak a fifth of a voxel wide along the steepest rays (the value changes by up to 0.0098
  // per voxel): a step of a voxel or two steps over it.
  volume::PeakedExtinction peaked;
  peaked.width = 0.002;
  peaked.height = 50;
  volume::PeakedExtinction linear;
  linear.height = 0;
  const VolumeDesc d = make_volume_desc({n, n, n}, {-1, -1, -1}, {1, 1, 1});
  RaymarchParams rp = atom::default_raymarch(d, atom::ViewPreset::front, 128, 128);
  rp.eye = {2.2f, -2.9f, 1.7f};
  rp.reference_step = float(ref);
  rp.termination_alpha = 1.0f;
  rp.skip_empty = false;
  rp.tf_size = 4096;
  const double spacing = 2.0 / n;
  const RaymarchLayout cam = raymarch_layout(rp);
  // The analytic opacity of each pixel through extinction e.
  auto analytic = [&](const volume::PeakedExtinction& e) {
    std::vector<double> want(size_t(rp.width) * rp.height, 0.0);
    for (uint32_t y = 0; y < rp.height; ++y)
      for (uint32_t x = 0; x < rp.width; ++x) {
        const hd::V3<double> eye = volume::v3<double>(cam.eye);
        const hd::V3<double> dir = volume::pixel_direction<double>(cam, x, y);
        double t0 = 0, t1 = 1e30;
        if (!volume::slab(eye, dir, hd::V3<double>{-1, -1, -1}, hd::V3<double>{1, 1, 1}, t0, t1))
          continue;
        double o[3], du[3];
        for (int a = 0; a < 3; ++a) {
          o[a] = (hd::comp(eye, a) + 1) / spacing - 0.5;
          du[a] = hd::comp(dir, a) / spacing;
        }
        want[size_t(y) * rp.width + x] = 1 - std::exp(-volume::clamped_ramp_depth(
                                                 o, du, 0, n - 1, 1 / (3.0 * (n - 1)), t0, t1, e));
      }
    return want;
  };
  auto transfer = [&](const volume::PeakedExtinction& e) {
    std::vector<Vec4d> tf(4096);
    for (uint32_t k = 0; k < 4096; ++k) tf[k] = {1, 1, 1, 1 - std::exp(-e(k / 4095.0) * ref)};
    return tf;
  };
  struct Tf {
    const char* name;
    std::vector<Vec4d> tf;
    std::vector<double> want;
  };
  const Tf tfs[] = {{"linear", transfer(linear), analytic(linear)},
                    {"peaked", transfer(peaked), analytic(peaked)}};
  fmt::print(
      "  step vs error against the analytic line integral (linear 60^3 volume, 128^2; extinction "
      "linear in the value, or with a peak {} wide):\n",
      peaked.width);
  fmt::print("  {:<8} {:>7} {:>12} {:>14} {:>10} {:>14} {:>14}\n", "backend", "tf", "step (voxels)",
             "pre-integrated", "ms", "max |alpha err|", "rms alpha err");
  j.key("sweep").begin_array();
  rc |= for_each_backend(backends, [&](Backend& b) {
    auto vol = b.create<Real>(ramp.size(), "ramp");
    b.upload(vol, ramp);
    for (const Tf& tf : tfs)
      for (double sv : {2.0, 1.0, 0.5, 0.25, 0.125})
        for (bool pre : {false, true}) {
          rp.step = float(sv * spacing);
          rp.preintegrate = pre;
          const Timed t = time_raymarch(b, rp, vol, tf.tf, o.reps);
          double err = 0, sq = 0;
          for (size_t i = 0; i < tf.want.size(); ++i) {
            const double e = std::abs(t.image[i].w - tf.want[i]);
            err = std::max(err, e);
            sq += e * e;
          }
          const double rms = std::sqrt(sq / double(tf.want.size()));
          fmt::print("  {:<8} {:>7} {:>12.3f} {:>14} {:>10.3f} {:>14.3e} {:>14.3e}\n", b.name(),
                     tf.name, sv, pre ? "yes" : "no", t.ms, err, rms);
          j.begin_object().field("backend", b.name()).field("transfer", tf.name);
          j.field("step_voxels", sv).field("preintegrate", pre).field("ms", t.ms);
          j.field("max_abs_error", err).field("rms_error", rms).end_object();
          progress.advance(fmt::format("{} {} step {} voxels", b.name(), tf.name, sv));
        }
  });
  progress.finish();
  j.end_array();
  return rc;
}

}  // namespace

void add_raymarch_bench(CLI::App& bench) {
  static RaymarchBenchOptions o;
  auto* cmd = add_bench(bench, "raymarch", "volume ray casting of 60^3; step vs error", o,
                        run_raymarch_bench);
  add_reps_option(*cmd, o.reps);
  cmd->add_flag("--large", o.large, "also a 256^3 volume at 1920x1080");
  add_ranged_option(*cmd, "--brick", o.brick, "voxels per brick of empty-space skipping", 2u, 16u);
  cmd->add_option("--state", o.state, "the thesis's preset state voxelized (its Table 2.3 count)")
      ->capture_default_str();
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
