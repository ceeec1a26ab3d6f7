#pragma once
// The demo's progressive rendering of raymarched scenes: while the view or a parameter changes,
// the volume is raymarched at a preview level (1/2^L of the viewport per axis, upsampled
// bilinearly when drawn), the level chosen from the measured frame time so that the frame rate
// stays at its target; once nothing changes, one frame at the full level (the image a one-shot
// render gives), and after it no raymarch at all until something changes again.
#include <cstdint>
#include <optional>
#include <string>

namespace masav::app {

// The frame rate a moving volume is held at.
constexpr double kProgressiveTargetFps = 20.0;

struct LevelInputs {
  bool moving = false;     // the view or a parameter changes in the coming frame
  uint32_t level = 0;      // the level of the last frame's raymarch
  double frame_ms = 0;     // the last frame's wall time (0: not measured yet)
  double raymarch_ms = 0;  // the last frame's raymarch device time, at `level` (0: none ran)
  double budget_ms = 1e3 / kProgressiveTargetFps;  // the frame time to stay under
  uint32_t max_level = 0;    // the scene's coarsest level (0: no progressive rendering)
  uint32_t first_level = 0;  // the level of a first moving frame, before anything was measured
};

// The level for the coming frame: 0 when still; when moving, the finest level whose predicted
// frame time (the rest of the last frame plus its raymarch scaled by the pixel count, 4x per
// level) is under the budget -- a finer level only with a quarter of the budget to spare, so
// that measurement noise does not flip the level every frame -- else the coarsest.
uint32_t next_preview_level(const LevelInputs& in);

// The first moving level on a device class ("CPU device" or "GPU", as sim_rate_defaults names
// them): a CPU device starts coarse, a GPU at full resolution.
uint32_t first_preview_level(const std::string& device_class, uint32_t max_level);

// How the demo picks the level while moving: adaptively (the default), never (off: every change
// raymarched at full resolution), or one fixed level (the script's `progressive N`, to measure
// a level's frame time).
struct ProgressiveMode {
  bool enabled = true;
  uint32_t fixed_level = 0;  // 0: adaptive
};
// "auto", "off" or a level 1..scene::kMaxPreviewLevel; none for anything else.
std::optional<ProgressiveMode> progressive_mode_from_word(const std::string& word);

// The overlay's words for a level: "volume: full resolution", "volume: 1/4 resolution (moving)".
std::string preview_label(uint32_t level);

}  // namespace masav::app
