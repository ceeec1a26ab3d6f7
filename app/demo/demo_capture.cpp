#include "app/demo/demo_capture.h"

#include <fmt/format.h>

#include <filesystem>

#include "app/scene_options.h"
#include "app/video.h"
#include "engine/util/json_writer.h"
#include "registry/scene_file.h"

namespace masav::app {

std::string DemoCapture::next_free(const std::string& stem, const std::string& ext) {
  ensure_writable_dir(out_, "--out");
  for (int i = 1;; ++i) {
    const std::string path = fmt::format("{}/{}_{:04d}{}", out_, stem, i, ext);
    if (!std::filesystem::exists(path)) return path;
  }
}

std::string DemoCapture::next_screenshot() {
  return next_free("screenshot", ".png");
}

void DemoCapture::start_recording() {
  recording_dir_ = next_free("recording", "");
  std::filesystem::create_directories(recording_dir_);
  frames_ = 0;
}

std::string DemoCapture::next_frame() {
  return fmt::format("{}/frame_{:05d}.png", recording_dir_, frames_++);
}

std::string DemoCapture::stop_recording(double fps) {
  const std::string dir = recording_dir_;
  const uint64_t frames = frames_;
  recording_dir_.clear();
  frames_ = 0;
  const std::string pngs = fmt::format("{} PNG frames in {}", frames, dir);
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty())
    return fmt::format("{} (ffmpeg not found: PNG frames only; install ffmpeg for an MP4)", pngs);
  if (frames > 0 && write_video(ffmpeg, dir, "recording", fps, video_time_limit(frames)))
    return fmt::format("{} and {}/recording.mp4", pngs, dir);
  return pngs;
}

std::string DemoCapture::save_scene(const scene::ParamSet& params) {
  const std::string path = next_free("scene", ".toml");
  write_file_atomic(path, fmt::format("# saved by masav demo; `masav run {}` renders it\n{}", path,
                                      scene::scene_to_toml(params, false)));
  return path;
}

}  // namespace masav::app
