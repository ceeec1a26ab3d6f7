#include "app/demo/demo_actions.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace masav::app {

const std::vector<Shortcut>& shortcuts() {
  static const std::vector<Shortcut> all = [] {
    std::vector<Shortcut> s = {
        {GLFW_KEY_SPACE, "space", "Space", {Action::pause}, "pause / resume"},
        {GLFW_KEY_N, "n", "N", {Action::step}, "step one frame"},
        {GLFW_KEY_R, "r", "R", {Action::reset}, "reset the scene"},
        {GLFW_KEY_P, "p", "P", {Action::screenshot}, "screenshot (PNG)"},
        {GLFW_KEY_V, "v", "V", {Action::record}, "record / stop (PNG frames, MP4)"},
        {GLFW_KEY_S, "s", "S", {Action::save_scene}, "save the scene (TOML)"},
        {GLFW_KEY_TAB, "tab", "Tab", {Action::panel}, "collapse / expand this panel"},
    };
    static const char* digits[] = {"1", "2", "3", "4", "5", "6", "7", "8", "9", "0"};
    for (int i = 0; i < 10; ++i)
      s.push_back({i == 9 ? GLFW_KEY_0 : GLFW_KEY_1 + i,
                   digits[i],
                   digits[i],
                   {Action::preset, i},
                   "state 1-10 (atom) / preset 1-5 (SPH)"});
    return s;
  }();
  return all;
}

std::optional<ActionRequest> shortcut_by_name(const std::string& name) {
  for (const Shortcut& s : shortcuts())
    if (name == s.name) return s.request;
  return std::nullopt;
}

std::optional<ActionRequest> button_by_name(const std::string& name) {
  if (name == "pause") return ActionRequest{Action::pause};
  if (name == "step") return ActionRequest{Action::step};
  if (name == "reset") return ActionRequest{Action::reset};
  if (name == "screenshot") return ActionRequest{Action::screenshot};
  if (name == "record") return ActionRequest{Action::record};
  if (name == "save") return ActionRequest{Action::save_scene};
  if (name == "panel") return ActionRequest{Action::panel};
  return std::nullopt;
}

std::string shortcut_names() {
  std::string out;
  for (const Shortcut& s : shortcuts()) out += (out.empty() ? "" : ", ") + std::string(s.name);
  return out;
}

std::string button_names() {
  return "pause, step, reset, screenshot, record, save, panel";
}

}  // namespace masav::app
