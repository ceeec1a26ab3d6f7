// `masav atom`: the electron cloud of one hydrogen state, lit as a reflection nebula, voxelized
// and raymarched; writes the cloud (.vtp), the volume (.vti), the scattering table (.csv) and
// images (.png). `masav volume`: raymarches a scalar volume from a raw, NRRD or VTI file.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <type_traits>

#include "app/bench_common.h"
#include "app/commands.h"
#include "app/host_environment.h"
#include "app/progress.h"
#include "app/scene_options.h"
#include "app/vocabulary.h"
#include "engine/atom/atom_export.h"
#include "engine/atom/atom_schema.h"
#include "engine/core/error.h"
#include "engine/io/output_lock.h"
#include "engine/io/png_writer.h"
#include "engine/io/staged_files.h"
#include "engine/volume/transfer_function.h"
#include "engine/volume/volume_file.h"
#include "registry/backends.h"
#include "registry/scene_catalog.h"

namespace masav::app {
namespace {

struct AtomCliOptions {
  BackendChoice choice;
  std::string preset;
  int n = 0, l = 0, m = 0;
  bool real = false;
  std::string placement = "exact";
  uint32_t particles = 500000;
  uint64_t seed = 1;
  std::string out = "out/atom";
  float power = 250000.0f;
  std::string view = "front";
  uint32_t width = 512, height = 512;
  uint32_t dims = 60, density_dims = 60;
  uint32_t photons = 2048;
  float tau_peak = 0.5f;
  float s = 0.6f, t = 0.4f;
  std::string tf;
  std::string clip;  // AXIS:POSITION[:above|below]
  bool shade = false;
  float shade_specular = 0.3f;
  bool no_cache = false;
};

struct VolumeCliOptions {
  BackendChoice choice;
  volume::VolumeFileOptions source;
  std::string out = "out/volume", tf, view = "front", mode = "front_to_back";
  std::string preintegrate = "off";
  std::string clip;  // AXIS:POSITION[:above|below]
  bool shade = false;
  float shade_specular = 0.3f;
  int reps = 0;
  uint32_t width = 512, height = 512;
  float step_voxels = 0.5f;
};

std::vector<Vec4d> transfer(const std::string& file) {
  return volume::resample_transfer(file.empty() ? volume::default_transfer_points()
                                                : volume::load_transfer_points(file));
}

// The nebula as the thesis shows it: particles projected along the view, coloured by their light
// (green, saturating) -- a quick look without the renderer.
std::vector<Vec4d> splat_cloud(atom::AtomScene& scene, atom::ViewPreset view, uint32_t size) {
  Backend& b = scene.backend();
  const auto pos = b.download_f32(scene.positions);
  const auto light = b.download(scene.light);
  std::vector<Vec4d> img(size_t(size) * size, Vec4d{0, 0, 0, 0});
  const double h = scene.box_half_width();
  const double k = scene.exposure();
  for (size_t i = 0; i < pos.size(); ++i) {
    double u = 0, v = 0;
    switch (view) {
      case atom::ViewPreset::top:
        u = pos[i].x, v = pos[i].y;
        break;
      case atom::ViewPreset::left:
        u = -pos[i].y, v = pos[i].z;
        break;
      case atom::ViewPreset::front:
        u = pos[i].x, v = pos[i].z;
        break;
    }
    const int px = int((u / h * 0.5 + 0.5) * size), py = int((0.5 - v / h * 0.5) * size);
    if (px < 0 || py < 0 || px >= int(size) || py >= int(size)) continue;
    Vec4d& c = img[size_t(py) * size + px];
    const double g = std::min(1.0, light[i] * k);
    c.x += 0.02 * g * g;  // hot particles tint towards white
    c.y += 0.05 * g;
    c.z += 0.015;  // every particle leaves a faint trace, so the whole cloud shows
    c.w = 1;
  }
  return img;
}

// --clip AXIS:POSITION[:above|below], spelled as the scene keys volume.clip, clip_position and
// clip_keep spell their values.
RaymarchParams::Clip parse_clip(const std::string& text, const std::string& command) {
  RaymarchParams::Clip c;
  if (text.empty()) return c;
  const std::string want =
      "AXIS:POSITION[:SIDE] with AXIS x, y or z, POSITION in [0, 1] (a fraction of the box) and "
      "SIDE above (the default) or below, e.g. z:0.5:below";
  std::vector<std::string> parts;
  for (size_t b = 0;;) {
    const size_t e = text.find(':', b);
    parts.push_back(text.substr(b, e == std::string::npos ? e : e - b));
    if (e == std::string::npos) break;
    b = e + 1;
  }
  if (parts.size() < 2 || parts.size() > 3) throw_invalid(command, "--clip", text, want);
  if (parts[0] != "x" && parts[0] != "y" && parts[0] != "z")
    throw_invalid(command, "--clip axis", parts[0], "x, y or z (" + want + ")");
  c.axis = uint32_t(parts[0][0] - 'x');
  size_t used = 0;
  double pos = -1;
  try {
    pos = std::stod(parts[1], &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != parts[1].size() || !(pos >= 0 && pos <= 1))
    throw_invalid(command, "--clip position", parts[1], "a number in [0, 1] (" + want + ")");
  c.position = float(pos);
  if (parts.size() == 3 && parts[2] != "above" && parts[2] != "below")
    throw_invalid(command, "--clip side", parts[2], "above or below (" + want + ")");
  c.keep_above = parts.size() < 3 || parts[2] == "above";
  c.enabled = true;
  return c;
}

int run_atom(const AtomCliOptions& o) {
  atom::AtomSceneOptions so;
  so.cache_dir = host_environment().cache_dir().string();
  if (!o.preset.empty()) {
    so.state = atom::preset_state(o.preset);
    so.state.real = o.real;
  } else {
    if (o.n == 0)
      throw_invalid("masav atom", "--state or --n", "none",
                    "a preset (--state state1..state10) "
                    "or a state (--n N --l L --m M)");
    so.state = {o.n, o.l, o.m, o.real};
  }
  atom::validate_state(so.state, "masav atom");
  if (o.placement != "exact" && o.placement != "shells")
    throw_invalid("masav atom", "--placement", o.placement, "exact or shells");
  so.placement = o.placement == "shells" ? OrbitalPlacement::shells : OrbitalPlacement::exact;
  so.particles = o.particles;
  so.seed = o.seed;
  so.source_power_lm = o.power;
  so.density_dims = o.density_dims;
  so.volume_dims = o.dims;
  so.scatter.photons_per_row = o.photons;
  atom::check_scatter_cost(so.scatter, "--photons");
  so.tau_peak = o.tau_peak;
  so.s = o.s;
  so.t = o.t;
  so.use_cache = !o.no_cache;
  const atom::ViewPreset view = atom::parse_view(o.view);
  const std::vector<Vec4d> tf = transfer(o.tf);
  const RaymarchParams::Clip clip = parse_clip(o.clip, "masav atom");
  // The output directory is proved writable and held before any work, so a bad --out fails in
  // a moment and a second run cannot mix its files into this one's.
  ensure_writable_dir(o.out, "--out");
  const OutputLock lock(o.out, "--out");
  auto backend = open_backend(o.choice);
  // The viewer of the nebula lighting sits where the raymarch camera does.
  const float half = float(atom::box_half_width(so.state, so.box_probability));
  const Vec3f eye = atom::view_eye(view, 1.9f * half * std::sqrt(3.0f));
  so.viewer = eye;
  fmt::print("atom: {} ({} particles, {} placement) on {} ({})\n", describe(so.state), so.particles,
             o.placement, backend->name(), backend->caps().device_name);
  atom::AtomScene scene(*backend, so);
  // The same steps as AtomScene::run_all, counted: half a million particles take minutes on a
  // CPU device.
  Progress progress("atom steps", 7);
  progress.update(0, "cloud");
  scene.build_cloud();
  progress.advance("density");
  scene.build_density();
  progress.advance("scattering table");
  scene.build_table();
  progress.advance("illumination");
  scene.illuminate();
  progress.advance("view");
  scene.view();
  progress.advance("voxelize");
  scene.voxelize();
  progress.advance("raymarch and files");
  const auto& t = scene.times();
  fmt::print(
      "  cloud {:.1f} ms, density {:.1f} ms, scattering table {:.1f} ms{}, illumination "
      "{:.1f} ms, view {:.1f} ms, voxelize {:.1f} ms\n",
      t.cloud_ms, t.density_ms, t.table_ms, t.table_from_cache ? " (from the cache)" : "",
      t.illuminate_ms, t.view_ms, t.voxelize_ms);
  // The five files appear together or not at all (an old set stays whole if this one fails).
  StagedFiles files(o.out);
  atom::write_cloud_vtp(scene, files.stage("cloud.vtp"));
  atom::write_volume_vti(scene, files.stage("volume.vti"));
  atom::write_scatter_csv(scene.table(), files.stage("scatter_table.csv"));
  RaymarchParams rp = atom::default_raymarch(scene.volume(), view, o.width, o.height);
  rp.clip = clip;
  rp.shading.enabled = o.shade;
  rp.shading.specular = o.shade_specular;
  const auto img = atom::render_volume(*backend, scene.volume(), scene.sample, tf, rp);
  atom::write_image_png(img, o.width, o.height, files.stage("raymarch.png"));
  const auto splat = splat_cloud(scene, view, std::min(o.width, o.height));
  write_png(files.stage("cloud.png"), std::min(o.width, o.height), std::min(o.width, o.height),
            to_rgba8(splat, {0, 0, 0}, true));
  files.commit();
  progress.advance();
  progress.finish();
  fmt::print("  wrote {}/{{cloud.vtp, volume.vti, scatter_table.csv, raymarch.png, cloud.png}}\n",
             o.out);
  return 0;
}

int run_volume(const VolumeCliOptions& o) {
  const std::vector<Vec4d> tf = transfer(o.tf);  // every input is checked before any work
  const atom::ViewPreset view = atom::parse_view(o.view);
  if (o.mode != "front_to_back" && o.mode != "lerp")
    throw_invalid("masav volume", "--mode", o.mode, "front_to_back or lerp");
  if (o.preintegrate != "on" && o.preintegrate != "off")
    throw_invalid("masav volume", "--preintegrate", o.preintegrate, "on or off");
  if (o.preintegrate == "on" && o.mode != "front_to_back")
    throw_invalid("masav volume", "--preintegrate", "on with --mode " + o.mode,
                  "off, or on with --mode front_to_back (lerp has no step to integrate over)");
  volume::check_volume_file_options(o.source);
  const RaymarchParams::Clip clip = parse_clip(o.clip, "masav volume");
  // --out names a directory, as for every command; a .png name is the file it used to name.
  std::string png = o.out + "/volume.png";
  if (std::filesystem::path(o.out).extension() == ".png") {
    note_old_spelling("--out FILE.png", "--out DIR (which receives volume.png)");
    png = o.out;
    ensure_writable_file(png, "--out");
  } else {
    ensure_writable_dir(o.out, "--out");
  }
  // Reading, uploading and raymarching a large volume take seconds each on a CPU device.
  Progress progress("volume steps", 4);
  progress.update(0, "reading " + o.source.file);
  const volume::ScalarVolume vol = volume::load_volume_file(o.source);
  const VolumeDesc desc = volume::volume_desc(vol);
  progress.advance(fmt::format("uploading {}x{}x{} values", desc.dims.x, desc.dims.y, desc.dims.z));
  auto backend = open_backend(o.choice);
  auto buf = backend->create<Real>(vol.values.size(), "volume");
  backend->upload(buf, std::span<const float>(vol.values));
  progress.advance(fmt::format("raymarching {}x{} on {}", o.width, o.height, backend->name()));
  RaymarchParams rp = atom::default_raymarch(desc, view, o.width, o.height);
  rp.step *= 2.0f * o.step_voxels;
  rp.mode = o.mode == "lerp" ? Compositing::lerp : Compositing::front_to_back;
  rp.preintegrate = o.preintegrate == "on";
  rp.clip = clip;
  rp.shading.enabled = o.shade;
  rp.shading.specular = o.shade_specular;
  rp.volume = desc;
  rp.tf_size = uint32_t(tf.size());
  atom::RaymarchBuffers r = atom::prepare_raymarch(*backend, buf, tf, rp);
  atom::raymarch_frame(*backend, rp, buf, r);
  progress.advance("writing " + png);
  atom::write_image_png(backend->download(r.image), o.width, o.height, png);
  progress.advance();
  progress.finish();
  fmt::print("volume: {}x{}x{} values in [{}, {}] raymarched on {} to {}\n", desc.dims.x,
             desc.dims.y, desc.dims.z, vol.min, vol.max, backend->name(), png);
  if (o.reps > 0) {
    const TimingStats s =
        time_work(*backend, o.reps, [&] { atom::raymarch_frame(*backend, rp, buf, r); });
    fmt::print(
        "raymarch: {:.2f} ms/frame on {} ({}x{}, step {} voxels, pre-integration {}; "
        "median of {})\n",
        s.median_ms, backend->name(), o.width, o.height, o.step_voxels, o.preintegrate, o.reps);
  }
  return 0;
}

}  // namespace

// An option that sets what a scene key of the atom-volume scene sets, over the key's range: the
// command line accepts what scene files accept.
template <class T>
void add_scene_ranged(CLI::App& cmd, const std::string& name, T& value, const std::string& help,
                      const std::string& key) {
  static const scene::ParamSet params =
      scene::default_params(scene::find_scene_type("atom-volume"));
  const scene::ParamSpec& s = params.spec(key);
  const std::string text = fmt::format("{} (scene key {})", help, key);
  if constexpr (std::is_integral_v<T>)
    add_ranged_option(cmd, name, value, text, T(s.int_min),
                      T(std::min<int64_t>(s.int_max, int64_t(std::numeric_limits<T>::max()))));
  else
    add_ranged_option(cmd, name, value, text, T(s.real_min), T(s.real_max));
}

void add_atom_command(CLI::App& app) {
  static AtomCliOptions o;
  auto* cmd = add_command(app, "atom",
                          "hydrogen electron cloud as a reflection nebula: cloud, "
                          "lighting, volume, raymarch; writes .vtp/.vti/.csv/.png",
                          o, run_atom);
  add_backend_options(*cmd, o.choice, false);
  auto* state = cmd->add_option("--state", o.preset, "thesis Table 2.1 preset: state1 .. state10");
  // A preset and quantum numbers name two states: refused rather than one silently winning.
  for (auto* q :
       {cmd->add_option("--n", o.n, "principal quantum number")->check(CLI::Range(1, atom::kMaxN)),
        cmd->add_option("--l", o.l, "azimuthal quantum number, 0 <= l < n"),
        cmd->add_option("--m", o.m, "magnetic quantum number, -l <= m <= l (0: no angular momentum about z)")})
    state->excludes(q);
  cmd->add_flag("--real", o.real, "real orbital (cos/sin of m phi) instead of e^{i m phi}");
  cmd->add_option("--placement", o.placement, "exact (inverse CDF) or shells (thesis Alg. 2.1)")
      ->capture_default_str();
  add_scene_ranged(*cmd, "--particles", o.particles, "cloud size", "atom.count");
  cmd->add_option("--seed", o.seed, "random seed (Philox key; 0 is a key like any other)")
      ->check(CLI::Range(uint64_t(0), uint64_t(1) << 62))
      ->capture_default_str();
  cmd->add_option("--out,-o", o.out, "output directory")->capture_default_str();
  add_scene_ranged(*cmd, "--power", o.power, "source power Phi in lumens", "nebula.power_lm");
  cmd->add_option("--view", o.view, "top, left or front")->capture_default_str();
  add_ranged_option(*cmd, "--width", o.width, "image width", 16u, 8192u);
  add_ranged_option(*cmd, "--height", o.height, "image height", 16u, 8192u);
  add_scene_ranged(*cmd, "--dims", o.dims, "voxel grid N (N^3 volume)", "volume.dims");
  add_scene_ranged(*cmd, "--density-dims", o.density_dims, "density grid N (cells of the lighting)",
                   "nebula.density_dims");
  add_scene_ranged(*cmd, "--photons", o.photons, "photons per tau row of the scattering table",
                   "scatter.photons");
  add_scene_ranged(*cmd, "--tau-peak", o.tau_peak,
                   "scattering depth of one cell at the peak density (0: a transparent cloud)",
                   "nebula.tau_peak");
  add_scene_ranged(*cmd, "--s", o.s, "volume mix: weight of the light g (0: the density alone)",
                   "volume.s");
  add_scene_ranged(*cmd, "--t", o.t, "volume mix: weight of the density p (0: the light alone)",
                   "volume.t");
  cmd->add_option("--tf", o.tf, "transfer function file (lines: value r g b a)");
  cmd->add_option("--clip", o.clip,
                  "AXIS:POSITION[:above|below]: raymarch only the volume above (or below) the "
                  "plane across axis x, y or z at POSITION in [0, 1] of the box (scene keys "
                  "volume.clip, clip_position, clip_keep)");
  cmd->add_flag("--shade", o.shade,
                "Blinn-Phong shading of the raymarch from the volume's gradient, lit from the "
                "camera (scene key volume.shade)");
  add_scene_ranged(*cmd, "--shade-specular", o.shade_specular, "specular weight of --shade (0: diffuse only)",
                   "volume.shade_specular");
  cmd->add_flag("--no-cache", o.no_cache, "recompute the scattering table");

  static VolumeCliOptions v;
  auto* vc = add_command(app, "volume", "raymarch a scalar volume (raw, .nrrd/.nhdr, .vti) to PNG",
                         v, run_volume);
  add_backend_options(*vc, v.choice, false);
  vc->add_option("file", v.source.file, "the volume file")->required();
  vc->add_option("--out,-o", v.out, "output directory: volume.png")->capture_default_str();
  vc->add_option("--dims", v.source.dims, "raw: sizes X Y Z")->delimiter(',')->expected(3);
  vc->add_option("--type", v.source.type,
                 "raw: uint8, int8, uint16, int16, uint32, int32, float32, float64");
  vc->add_option("--spacing", v.source.spacing, "raw: voxel size X,Y,Z")
      ->delimiter(',')
      ->expected(3);
  vc->add_flag("--big-endian", v.source.big_endian, "raw: big-endian samples");
  vc->add_option("--array", v.source.array, "vti: the array to read (default: the first)");
  vc->add_option("--tf", v.tf, "transfer function file (lines: value r g b a)");
  vc->add_option("--view", v.view, "top, left or front")->capture_default_str();
  accept_old_values(vc->add_option("--mode", v.mode, "front_to_back or lerp (the thesis)"))
      ->capture_default_str();
  vc->add_option("--width", v.width, "image width")->check(CLI::Range(16u, 8192u));
  vc->add_option("--height", v.height, "image height")->check(CLI::Range(16u, 8192u));
  vc->add_option("--step", v.step_voxels, "ray step in voxels")->check(CLI::Range(0.05f, 4.0f));
  vc->add_option("--preintegrate", v.preintegrate,
                 "on: integrate the transfer function over each step (front-to-back only)")
      ->capture_default_str();
  vc->add_option("--clip", v.clip,
                 "AXIS:POSITION[:above|below]: keep the volume above (or below) the plane across "
                 "axis x, y or z at POSITION in [0, 1] of the box, e.g. z:0.5:below");
  vc->add_flag("--shade", v.shade,
               "Blinn-Phong shading from the volume's gradient, lit from the camera");
  add_ranged_option(*vc, "--shade-specular", v.shade_specular,
                    "specular weight of --shade (ambient 0.3, diffuse 0.7, shininess 24; 0: diffuse only)", 0.0f,
                    1.0f);
  vc->add_option("--reps", v.reps, "also time this many more frames and print ms/frame (0: none)")
      ->check(CLI::Range(0, 1000));
}

}  // namespace masav::app
