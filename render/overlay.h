#pragma once
// The text overlay drawn on every frame (SPEC §3): scene, frame and time, fps, the backend and
// its device, and each stage's device time of the last update -- through ImGui's foreground
// draw list, so headless frames and the demo show the same thing.
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/stage_graph.h"
#include "render/colour_bar.h"

namespace masav::render {

struct OverlayInfo {
  std::string title;
  std::string backend, device;
  std::string render_device;  // "" when the renderer shares the compute device
  uint64_t frame = 0;
  double time_s = 0;  // the frame clock
  // A stepped scene's own time (SPH): shown as "t", the frame clock then labelled as such.
  std::optional<double> simulated_time_s;
  double fps = 0;        // frames per wall-clock second (0: not measured, e.g. headless)
  double frame_ms = 0;   // wall time of the last frame
  std::string progress;  // the demo's progressive rendering: the level drawn ("" = none)
  std::string verify;    // cross-check status line
  std::string legend;    // colour-map legend: scalar name and range
  std::optional<ColourBar> colour_bar;  // drawn at the right edge
  std::vector<scene::StageCounters> stages;
};

// The overlay's lines, top to bottom: the title first.
std::vector<std::string> overlay_lines(const OverlayInfo& info);
// The line with the frame, the time and the frame rate.
std::string clock_line(uint64_t frame, double clock_s, std::optional<double> simulated_s);

// Adds the overlay (and its colour bar) to the current ImGui frame (between NewFrame and Render).
void draw_overlay(const OverlayInfo& info);

}  // namespace masav::render
