#pragma once
// What the demo's keys, its panel buttons and its script's `key` and `button` commands do: one
// table, so the panel lists exactly the shortcuts that work.
#include <optional>
#include <string>
#include <vector>

namespace masav::app {

enum class Action {
  pause,       // pause or resume
  step,        // one frame, then paused
  reset,       // the scene from its start
  preset,      // state 1-10 (atom scenes) or preset 1-5 (SPH): `index`
  screenshot,  // the next frame as PNG
  record,      // start or stop recording PNG frames (and an MP4 with ffmpeg)
  save_scene,  // the current parameters as a scene file
  panel,       // collapse or expand the panel
};

struct ActionRequest {
  Action action;
  int index = 0;  // preset: 0-9
};

struct Shortcut {
  int key;            // GLFW key code
  const char* name;   // as the script writes it (`key space`)
  const char* label;  // as the panel shows it
  ActionRequest request;
  const char* what;
};

// Every shortcut: space, n, r, 1-9 and 0, p, v, s, tab.
const std::vector<Shortcut>& shortcuts();
// The panel's list of shortcuts, made from shortcuts(): one row per action, its keys joined
// ("1-9, 0" for the ten state keys).
struct ShortcutRow {
  std::string keys;
  std::string what;
};
std::vector<ShortcutRow> shortcut_rows();
// The key labels a row's `keys` stands for ("1-9, 0" -> 1, 2, ..., 9, 0).
std::vector<std::string> row_key_labels(const std::string& keys);
// A key by its script name ("space", "3", "tab"); nullopt if there is none.
std::optional<ActionRequest> shortcut_by_name(const std::string& name);
// A panel button by its script name: pause, step, reset, screenshot, record, save, panel.
std::optional<ActionRequest> button_by_name(const std::string& name);
// The names `key` and `button` accept, for error messages and the script's usage.
std::string shortcut_names();
std::string button_names();

}  // namespace masav::app
