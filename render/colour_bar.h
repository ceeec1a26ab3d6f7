#pragma once
// The colour bar drawn with the overlay: the colours a scene's scalar is shown in, from the
// bottom (lo) to the top (hi), with "nice" tick values and the quantity's name and unit as its
// title. The layout is a function of its own so tests can find the bar and its labels in a
// frame without reading text back.
#include <string>
#include <vector>

#include "engine/core/types.h"

namespace masav::render {

struct ColourBar {
  std::string title;  // "quantity (unit)"
  float lo = 0, hi = 1;
  std::vector<Vec4f> colours;  // evenly spaced from lo (first) to hi (last); at least one
};

struct ColourBarTick {
  double value = 0;
  std::string label;
  float y = 0;  // pixel row of the tick's line
};

struct ColourBarLayout {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the gradient's rectangle (y0 at the top: hi)
  float title_x = 0, title_y = 0;        // the title's top-left corner
  std::vector<ColourBarTick> ticks;
};

// Round values (1, 2 or 5 times a power of ten) between lo and hi, about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 5);
std::string tick_label(double value, double step);

// Where the bar goes in a frame `height` px high: at the bottom left (the overlay's text is at
// the top left, the demo's panel at the right), its title above it, its tick labels right of it.
// `scale` is the UI scale, `line_height` the font's.
ColourBarLayout colour_bar_layout(const ColourBar& bar, float height, float scale,
                                  float line_height);

// The layout in the current ImGui context's frame (its display size, scale and font).
ColourBarLayout colour_bar_layout_in_frame(const ColourBar& bar);

// The bar's colour at `value` (clamped to [lo, hi]), as the gradient draws it.
Vec4f colour_at(const ColourBar& bar, double value);

// Adds the bar to the current ImGui frame (between NewFrame and Render); returns its layout.
ColourBarLayout draw_colour_bar(const ColourBar& bar);

}  // namespace masav::render
