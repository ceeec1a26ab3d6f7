#include "app/demo/progressive.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/scene/scene.h"

namespace masav::app {

uint32_t next_preview_level(const LevelInputs& in) {
  if (!in.moving || in.max_level == 0) return 0;
  const uint32_t level = std::min(in.level, in.max_level);
  if (in.frame_ms <= 0 || in.raymarch_ms <= 0) return std::min(in.first_level, in.max_level);
  // The frame's time besides the raymarch (the other stages, drawing, presenting) stays.
  const double rest_ms = std::max(0.0, in.frame_ms - in.raymarch_ms);
  auto predicted_ms = [&](uint32_t l) {
    return rest_ms + in.raymarch_ms * std::pow(4.0, double(level) - double(l));
  };
  for (uint32_t l = 0; l <= in.max_level; ++l) {
    const double budget = l < level ? 0.75 * in.budget_ms : in.budget_ms;
    if (predicted_ms(l) <= budget) return l;
  }
  return in.max_level;
}

uint32_t first_preview_level(const std::string& device_class, uint32_t max_level) {
  return device_class == "GPU" ? 0 : max_level;
}

std::optional<ProgressiveMode> progressive_mode_from_word(const std::string& word) {
  if (word == "auto") return ProgressiveMode{};
  if (word == "off") return ProgressiveMode{false, 0};
  for (uint32_t l = 1; l <= scene::kMaxPreviewLevel; ++l)
    if (word == std::to_string(l)) return ProgressiveMode{true, l};
  return std::nullopt;
}

std::string preview_label(uint32_t level) {
  if (level == 0) return "volume: full resolution";
  return fmt::format("volume: 1/{} resolution (moving)", 1u << level);
}

}  // namespace masav::app
