// `masav run scene.toml`: the scene rendered headless (offscreen Vulkan, lavapipe included) to
// PNG frames, after the cross-check; an MP4 when ffmpeg is present. Every file is written to a
// temporary name and renamed, and Ctrl-C stops after the frame in progress. The run owns its
// directory: an earlier run's files of its names are refused (removed with --overwrite), and
// OUT/manifest.json lists what this run wrote (engine/io/run_outputs.h).
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "app/commands.h"
#include "app/host_environment.h"
#include "app/interrupt.h"
#include "app/number_checks.h"
#include "app/progress.h"
#include "app/scene_options.h"
#include "app/video.h"
#include "app/vocabulary.h"
#include "engine/core/error.h"
#include "engine/io/output_lock.h"
#include "engine/io/run_outputs.h"
#include "engine/util/json_writer.h"
#include "render/png_queue.h"
#include "render/scene_player.h"

namespace masav::app {
namespace {

struct RunOptions {
  SceneChoice scene;
  BackendChoice choice;
  int frames = 0;  // 0: the scene's run.frames
  std::string out = "out/run";
  bool stats = false;
  bool no_verify = false;
  bool no_video = false;
  double video_timeout = 0;  // s; 0: video_time_limit(frames)
  bool overwrite = false;
};

std::string frame_name(int i) {
  return fmt::format("frame_{:05d}.png", i);
}

// Every name a run writes into its directory (the video is named after the scene's type).
OutputNames run_output_names(const std::string& type) {
  return {{"frame_#.png", "scene.toml", "verify.json", type + ".mp4", RunManifest::kFileName}};
}

int run(const RunOptions& o) {
  refuse_set_conflict(o.scene, o.frames > 0, "--frames", "run.frames");
  scene::SceneFile file = load_scene(o.scene);
  const scene::ParamSet& p0 = file.params;
  const int frames = o.frames > 0 ? o.frames : int(p0.get_int("run.frames"));
  ensure_writable_dir(o.out, "--out");
  const OutputLock lock(o.out, "--out");  // two runs into one directory would mix their frames
  // and so would two in turn: an earlier run's frames are refused, or removed with --overwrite
  claim_outputs(o.out, run_output_names(file.type), o.overwrite, "--out");
  RunManifest manifest(o.out, {{"command", "run"}, {"scene", file.source}, {"type", file.type}});
  install_interrupt_handler();

  render::PlayerOptions po;
  po.backend = o.choice.backend;
  po.device = o.choice.device;
  po.tuning = o.choice.tuning();
  po.fault = fault_kernel(o.choice);
  po.graphics = render::graphics_options(vulkan_options(host_environment()),
                                         o.choice.backend == "vulkan" ? o.choice.device : "");
  po.cache_dir = host_environment().cache_dir().string();
  render::ScenePlayer player(std::move(file), po);
  const scene::ParamSet& p = player.scene().params();
  fmt::print("scene '{}' ({}) on {} ({}), drawn on {}{}\n", player.file().source,
             player.file().type, player.backend().name(), player.backend().caps().device_name,
             player.render_device().ctx().caps().device_name,
             player.render_device().shared() ? " (same device: no copies)" : " (copies)");
  write_file_atomic(o.out + "/scene.toml", scene::scene_to_toml(p, false));
  manifest.add("scene.toml");

  if (!o.no_verify && p.get_flag("verify.enabled")) {
    const verify::CrossCheckReport r = player.verify();
    fmt::print("{}", verify::format_report(r));
    write_file_atomic(o.out + "/verify.json", verify::report_json(r));
    manifest.add("verify.json");
    // A kernel not compared stops the run too: the render would run what nobody checked (and
    // the refused buffer would refuse the render as well).
    if (!r.pass() && r.failures() == 0) {
      fmt::print(stderr,
                 "masav: error: cross-check incomplete: {}; rendering stopped (report: "
                 "{}/verify.json)\n",
                 verify::failure_summary(r), o.out);
      manifest.write("failed");
      return kExitNotCompared;
    }
    if (!r.pass())
      throw Error("", "cross-check",
                  fmt::format("{}; rendering stopped (report: {}/verify.json)",
                              verify::failure_summary(r), o.out),
                  "this backend computes something else than the reference: report the device "
                  "and driver; --no-verify renders anyway");
  } else {
    player.set_verify_status("cross-check skipped (--no-verify)");
    fmt::print("cross-check skipped\n");
  }

  const double fps = p.get_real("run.fps");
  const double start = p.get_real("run.start_time_s");
  Progress progress("frames", uint64_t(frames));
  render::PngQueue pngs;
  const auto t0 = std::chrono::steady_clock::now();
  int written = 0;
  uint64_t ran = 0, skipped = 0;
  double update_s = 0, draw_s = 0, png_s = 0;  // wall time of each part of a frame
  auto lap = [](std::chrono::steady_clock::time_point& t) {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - t).count();
    t = now;
    return s;
  };
  for (int i = 0; i < frames && !interrupted(); ++i) {
    player.clock().frame = uint64_t(i);
    player.clock().time_s = start + double(i) / fps;
    auto t = std::chrono::steady_clock::now();
    const scene::UpdateReport u = player.update();
    update_s += lap(t);
    ran += u.ran.size();
    skipped += u.skipped.size();
    render::FrameRequest req;
    req.readback = true;
    player.draw(req);
    draw_s += lap(t);
    manifest.add(frame_name(i));
    pngs.push(o.out + "/" + frame_name(i), player.renderer().width(), player.renderer().height(),
              player.renderer().pixels());
    png_s += lap(t);  // waiting for the encoder (it works while the next frame is drawn)
    ++written;
    progress.update(uint64_t(written));
  }
  pngs.finish();
  progress.finish();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("wrote {} frames ({}x{}) to {}/ in {:.2f} s ({:.1f} ms per frame)\n", written,
             player.renderer().width(), player.renderer().height(), o.out, s,
             written ? 1e3 * s / written : 0.0);
  if (o.stats) {
    fmt::print("stages over {} frames: {} runs, {} skipped\n", written, ran, skipped);
    if (written)
      fmt::print(
          "per frame: stages {:.1f} ms, drawing and readback {:.1f} ms, waiting for the "
          "PNG encoder {:.1f} ms (wall time)\n",
          1e3 * update_s / written, 1e3 * draw_s / written, 1e3 * png_s / written);
    fmt::print("{}", scene::format_stage_stats(player.scene().graph().counters()));
    fmt::print("bytes copied to the renderer: {}\n", player.renderer().bridge().bytes_copied());
  }
  if (interrupted()) {
    fmt::print(stderr,
               "masav: interrupted after {} of {} frames; every file written is "
               "complete\n",
               written, frames);
    manifest.write("interrupted");
    return 130;
  }
  if (!o.no_video) {
    const std::string ffmpeg = find_ffmpeg();
    if (ffmpeg.empty())
      fmt::print("note: ffmpeg not found: PNG frames only (install ffmpeg for an MP4)\n");
    else if (written > 0 &&
             write_video(ffmpeg, o.out, player.file().type, fps,
                         o.video_timeout > 0 ? o.video_timeout
                                             : video_time_limit(uint64_t(written))))
      manifest.add(player.file().type + ".mp4");
  }
  manifest.write("completed");
  return 0;
}

}  // namespace

void add_run_command(CLI::App& app) {
  static RunOptions o;
  auto* cmd = add_scene_command(app, "run",
                                "render a scene headless to PNG frames (and an MP4), "
                                "after the cross-check",
                                o, run);
  add_fault_option(*cmd, o.choice);
  cmd->add_option("--frames", o.frames, "frames to render (default: the scene's run.frames)")
      ->check(CLI::Range(1, 1000000));
  add_old_option(*cmd, "-n", "--frames", o.frames)->check(CLI::Range(1, 1000000));
  cmd->add_option("--out,-o", o.out, "output directory")->capture_default_str();
  cmd->add_flag("--stats", o.stats, "print which stages ran and which were skipped");
  cmd->add_flag("--no-verify", o.no_verify, "render without the cross-check");
  cmd->add_flag("--no-video", o.no_video, "PNG frames only, even with ffmpeg present");
  cmd->add_option("--video-timeout", o.video_timeout,
                  "seconds ffmpeg may take before it is killed (the frames stay); 0: 60 s plus "
                  "0.5 s per frame")
      ->check(number_in(0.0, 86400.0));
  cmd->add_flag("--overwrite", o.overwrite,
                "remove an earlier run's frames, video and reports from --out first (only the "
                "names a run writes)");
}

}  // namespace masav::app
