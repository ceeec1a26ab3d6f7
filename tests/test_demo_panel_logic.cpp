// The demo panel's logic without a window: the shortcut list the panel shows against the keys the
// demo handles (one table, app/demo/demo_actions.cpp), and the tooltip's hover delay.
#include <doctest/doctest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <map>
#include <set>
#include <string>

#include "app/demo/demo_actions.h"
#include "app/demo/hover_delay.h"

using namespace masav::app;

TEST_CASE("demo shortcuts: the panel's list and the handled keys are the same set") {
  // Every binding the demo's key handler polls appears in the panel's list, with its action's
  // description, and every key the list names is a binding.
  std::map<std::string, std::string> listed;  // key label -> what the panel says it does
  for (const ShortcutRow& row : shortcut_rows()) {
    CAPTURE(row.keys);
    CHECK(!row.what.empty());
    for (const std::string& label : row_key_labels(row.keys)) {
      CHECK(listed.count(label) == 0);  // listed once
      listed[label] = row.what;
    }
  }
  std::set<std::string> bound;
  std::set<int> codes;
  for (const Shortcut& k : shortcuts()) {
    CAPTURE(k.label);
    CHECK(codes.insert(k.key).second);  // one action per key
    CHECK(bound.insert(k.label).second);
    REQUIRE(listed.count(k.label) == 1);
    CHECK(listed[k.label] == k.what);
    // The script's `key NAME` reaches the same binding.
    const auto by_name = shortcut_by_name(k.name);
    REQUIRE(by_name);
    CHECK(by_name->action == k.request.action);
    CHECK(by_name->index == k.request.index);
  }
  for (const auto& [label, what] : listed) {
    CAPTURE(label);
    CHECK(bound.count(label) == 1);
  }
  // The digits: states 1-10 in order, 0 the tenth.
  std::map<int, int> preset_of_key;
  for (const Shortcut& k : shortcuts())
    if (k.request.action == Action::preset) preset_of_key[k.key] = k.request.index;
  REQUIRE(preset_of_key.size() == 10);
  for (int i = 0; i < 9; ++i) CHECK(preset_of_key[GLFW_KEY_1 + i] == i);
  CHECK(preset_of_key[GLFW_KEY_0] == 9);
  // Every action has a key (the panel promises a shortcut for each).
  std::set<Action> with_key;
  for (const Shortcut& k : shortcuts()) with_key.insert(k.request.action);
  for (Action a : {Action::pause, Action::step, Action::reset, Action::preset, Action::screenshot,
                   Action::record, Action::save_scene, Action::panel})
    CHECK(with_key.count(a) == 1);
}

TEST_CASE("demo shortcuts: the panel's key column reads back to its keys") {
  CHECK(row_key_labels("Space") == std::vector<std::string>{"Space"});
  CHECK(row_key_labels("1-9, 0") ==
        std::vector<std::string>{"1", "2", "3", "4", "5", "6", "7", "8", "9", "0"});
  CHECK(row_key_labels("P, F12") == std::vector<std::string>{"P", "F12"});
}

TEST_CASE("demo tooltips: shown only after the pointer rests half a second on one control") {
  HoverDelay d;
  const double dt = 1.0 / 60;
  int frame = 0;
  double t = 0;
  // Moving across controls: a new control every few frames, never a tooltip.
  for (uint64_t item = 1; item <= 20; ++item)
    for (int i = 0; i < 5; ++i, ++frame, t += dt) CHECK_FALSE(d.due(item, true, t, frame));
  // Resting on one: nothing before 0.5 s, the tooltip from then on.
  const double rest = t;
  bool shown = false;
  while (t - rest < kTooltipDelayS - 1e-9) {
    CHECK_FALSE(d.due(99, false, t, frame));
    ++frame, t += dt;
  }
  for (int i = 0; i < 10; ++i, ++frame, t += dt) shown = d.due(99, i == 3, t, frame);
  CHECK(shown);  // a small move once it shows keeps it
  // Moving while on a control restarts the rest.
  HoverDelay m;
  for (int i = 0; i < 120; ++i) CHECK_FALSE(m.due(5, true, i * dt, i));
  // Leaving for a frame and coming back: the wait starts again.
  HoverDelay r;
  CHECK_FALSE(r.due(7, false, 0.0, 0));
  CHECK(r.due(7, false, 0.6, 1));
  CHECK_FALSE(r.due(7, false, 0.7, 3));  // frame 2 had no hover
  CHECK_FALSE(r.due(7, false, 1.0, 4));
  CHECK(r.due(7, false, 1.3, 5));
}
