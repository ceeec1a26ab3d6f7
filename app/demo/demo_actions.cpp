#include "app/demo/demo_actions.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>

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

std::vector<ShortcutRow> shortcut_rows() {
  std::vector<ShortcutRow> rows;
  const Shortcut* prev = nullptr;
  for (const Shortcut& k : shortcuts()) {
    if (prev && prev->request.action == k.request.action && std::string(prev->what) == k.what)
      rows.back().keys += std::string(", ") + k.label;
    else
      rows.push_back({k.label, k.what});
    prev = &k;
  }
  for (ShortcutRow& r : rows)
    if (r.keys == "1, 2, 3, 4, 5, 6, 7, 8, 9, 0") r.keys = "1-9, 0";
  return rows;
}

std::vector<std::string> row_key_labels(const std::string& keys) {
  std::vector<std::string> out;
  size_t at = 0;
  while (at <= keys.size()) {
    const size_t comma = std::min(keys.find(", ", at), keys.size());
    const std::string label = keys.substr(at, comma - at);
    if (label.size() == 3 && label[1] == '-' && label[0] < label[2]) {
      for (char c = label[0]; c <= label[2]; ++c) out.push_back(std::string(1, c));
    } else {
      out.push_back(label);
    }
    at = comma + 2;
  }
  return out;
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
