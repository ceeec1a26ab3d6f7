// `masav export scene.toml`: the scene's state at a frame, for other tools -- particles as VTK
// PolyData (.vtp, ParaView) with their scalar, the resolved scene as TOML, the stage counters as
// CSV. Runs the kernels only (no renderer, no Vulkan needed with --backend cpu). The export owns
// its directory as a run does (engine/io/run_outputs.h): an earlier export's files there are
// refused, or with --overwrite replaced by the new set (the old ones go once it is complete).
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <set>

#include "app/commands.h"
#include "app/host_environment.h"
#include "app/progress.h"
#include "app/scene_options.h"
#include "engine/core/error.h"
#include "engine/io/csv_writer.h"
#include "engine/io/output_lock.h"
#include "engine/io/run_outputs.h"
#include "engine/io/staged_files.h"
#include "engine/io/vtk_writer.h"
#include "engine/scene/scene.h"
#include "engine/util/json_writer.h"
#include "registry/backends.h"
#include "registry/scene_catalog.h"

namespace masav::app {
namespace {

struct ExportOptions {
  SceneChoice scene;
  BackendChoice choice;
  int frame = 0;
  std::string out = "out/export";
  bool overwrite = false;
};

// Every name an export writes: another frame's .vtp beside this scene.toml would mix two states.
OutputNames export_output_names(const std::string& type) {
  return {{"scene.toml", "stages.csv", type + "_frame#.vtp", RunManifest::kFileName}};
}

// `count` reals (f32 or f64 as the backend stores them), as floats.
std::vector<float> download_reals(Backend& b, const BufferImpl& buf, size_t count) {
  std::vector<float> v(count);
  if (buf.kind() == ElemKind::f32 || b.real_bytes() == 4) {
    b.download_bytes(buf, v.data(), count * 4, 0);
  } else {
    std::vector<double> d(count);
    b.download_bytes(buf, d.data(), count * 8, 0);
    for (size_t i = 0; i < count; ++i) v[i] = float(d[i]);
  }
  return v;
}

// The per-point scalar the renderer colours by, computed the way its shader does.
std::vector<float> scalar_values(Backend& b, const scene::PointLayer& pl,
                                 const std::vector<Vec4f>& pos) {
  std::vector<float> v(pl.count, 0.0f);
  using From = scene::PointLayer::ScalarFrom;
  if (pl.from == From::buffer && pl.scalar) {
    if (pl.scalar->kind() == ElemKind::u32) {
      std::vector<uint32_t> w(pl.count);
      b.download_bytes(*pl.scalar, w.data(), w.size() * 4, 0);
      for (size_t i = 0; i < v.size(); ++i) v[i] = float(w[i]);
    } else {
      v = download_reals(b, *pl.scalar, pl.count);
    }
  } else if (pl.from == From::vector_length && pl.scalar) {
    const std::vector<float> xyzw = download_reals(b, *pl.scalar, 4 * size_t(pl.count));
    for (size_t i = 0; i < v.size(); ++i) {
      const float* q = &xyzw[4 * i];
      v[i] = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    }
  } else if (pl.from == From::position_w || pl.from == From::position_z) {
    for (size_t i = 0; i < v.size(); ++i) v[i] = pl.from == From::position_w ? pos[i].w : pos[i].z;
  }
  return v;
}

int run_export(const ExportOptions& o) {
  scene::SceneFile f = load_scene(o.scene);
  ensure_writable_dir(o.out, "--out");
  const OutputLock lock(o.out, "--out");
  const OutputNames names = export_output_names(f.type);
  if (!o.overwrite) refuse_outputs(o.out, names, "--out");
  auto backend = open_backend(o.choice);
  const scene::SceneType& type = scene::find_scene_type(f.type);
  auto s = type.create(*backend, f.params,
                       scene::SceneHost{.cache_dir = host_environment().cache_dir().string()});
  // Every frame up to the one asked for, on the clock `masav run` uses: a stepped scene (SPH)
  // advances once per frame, so frame N is the state after N frames of steps.
  const double start = f.params.get_real("run.start_time_s"), fps = f.params.get_real("run.fps");
  Progress progress("frames", uint64_t(o.frame) + 1);
  scene::FrameClock clock;
  for (int i = 0; i <= o.frame; ++i) {
    clock.frame = uint64_t(i);
    clock.time_s = start + double(i) / fps;
    s->update(clock);
    if (o.frame > 0) progress.update(uint64_t(i) + 1);
  }
  progress.finish();
  backend->finish();
  if (const std::optional<double> t = s->simulated_time_s())
    fmt::print("frame {} (frame clock {:.4g} s): simulated time {:.6g} s\n", o.frame, clock.time_s,
               *t);
  const scene::SceneView v = s->view();
  // The files appear together or not at all: never a new scene.toml beside an old .vtp.
  StagedFiles files(o.out);
  std::vector<std::string> wrote;
  std::set<std::string> written = {"scene.toml", "stages.csv"};
  write_file_atomic(files.stage("scene.toml"), scene::scene_to_toml(s->params(), false));
  wrote.push_back(o.out + "/scene.toml");
  if (v.points && v.points->positions) {
    const scene::PointLayer& pl = *v.points;
    std::vector<Vec4f> pos = backend->download_f32(*pl.positions);
    pos.resize(pl.count);
    std::vector<float> xyz;
    xyz.reserve(3 * pos.size());
    for (const auto& q : pos) xyz.insert(xyz.end(), {q.x, q.y, q.z});
    std::vector<VtkArray> arrays;
    if (pl.from != scene::PointLayer::ScalarFrom::none)
      arrays.push_back(
          {pl.scalar_key.empty() ? "scalar" : pl.scalar_key, 1, scalar_values(*backend, pl, pos)});
    const std::string name = fmt::format("{}_frame{:05d}.vtp", f.type, o.frame);
    write_vtp(files.stage(name), xyz, arrays);
    written.insert(name);
    wrote.push_back(fmt::format("{}/{} ({} points{})", o.out, name, pl.count,
                                arrays.empty() ? "" : ", point array '" + arrays[0].name + "'"));
  }
  CsvWriter csv({"stage", "created", "runs", "skipped", "last_ms"});
  for (const auto& c : s->graph().counters())
    csv.row_text({c.name, c.created ? "1" : "0", std::to_string(c.runs), std::to_string(c.skips),
                  fmt::format("{}", c.last_ms)});
  csv.write(files.stage("stages.csv"));
  wrote.push_back(o.out + "/stages.csv");
  files.commit();
  std::set<std::string> keep = written;
  keep.insert(RunManifest::kFileName);  // replaced below, atomically
  remove_outputs(o.out, names, keep);  // none without --overwrite (refused above)
  RunManifest manifest(o.out, {{"command", "export"},
                               {"scene", f.source},
                               {"type", f.type},
                               {"frame", std::to_string(o.frame)}});
  for (const std::string& name : written) manifest.add(name);
  manifest.write("completed");
  for (const auto& w : wrote) fmt::print("wrote {}\n", w);
  return 0;
}

}  // namespace

void add_export_command(CLI::App& app) {
  static ExportOptions o;
  auto* cmd = add_scene_command(app, "export",
                                "write a scene's particles (.vtp), resolved scene "
                                "(.toml) and stage counters (.csv) at a frame",
                                o, run_export);
  add_ranged_option(*cmd, "--frame", o.frame, "frame to export (0: the first)", 0, 10000000);
  cmd->add_option("--out,-o", o.out, "output directory")->capture_default_str();
  cmd->add_flag("--overwrite", o.overwrite,
                "replace an earlier export's files in --out (only the names an export writes)");
}

}  // namespace masav::app
