#pragma once
// What the demo saves by itself, under its --out directory: screenshots (screenshot_0001.png, ...),
// recordings (recording_0001/frame_00000.png, ... and recording.mp4 when ffmpeg is present) and
// the current scene as a file `masav run` loads (scene_0001.toml, ...). Numbers continue after
// the files already there, so nothing is overwritten.
#include <cstdint>
#include <string>

#include "engine/scene/param_schema.h"

namespace masav::app {

class DemoCapture {
 public:
  explicit DemoCapture(std::string out_dir) : out_(std::move(out_dir)) {}
  const std::string& out_dir() const { return out_; }

  // The path of the next screenshot (the directory is created).
  std::string next_screenshot();

  bool recording() const { return !recording_dir_.empty(); }
  const std::string& recording_dir() const { return recording_dir_; }
  uint64_t recorded_frames() const { return frames_; }
  // A new recording_NNNN directory; frames go there until stop_recording.
  void start_recording();
  // The path of the next frame of the recording.
  std::string next_frame();
  // Ends the recording: an MP4 through ffmpeg when it is on PATH. Returns what was written.
  std::string stop_recording(double fps);

  // Writes the scene (its [scene] type and every parameter) as TOML; returns the path.
  std::string save_scene(const scene::ParamSet& params);

 private:
  std::string next_free(const std::string& stem, const std::string& ext);

  std::string out_;
  std::string recording_dir_;
  uint64_t frames_ = 0;
};

}  // namespace masav::app
