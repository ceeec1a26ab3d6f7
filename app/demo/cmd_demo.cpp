// `masav demo [scene.toml]`: the desktop demo -- a GLFW window sized to the screen, the scene
// drawn with Vulkan in its own viewport beside an ImGui panel holding SPEC §3's controls, with
// keyboard shortcuts, screenshots, recordings, saved scenes and volume files opened from the panel
// or dropped on the window. `--script FILE` drives it without a user (the tests run it under
// xvfb-run and inspect its screenshots). This file holds the command's options and their checks;
// the demo itself is DemoApp (demo_app.h).
#include <cstdio>
#include <string>
#include <utility>

#include "app/commands.h"
#include "app/demo/demo_app.h"
#include "app/demo/demo_script.h"
#include "app/interrupt.h"
#include "app/scene_options.h"
#include "engine/core/error.h"

namespace masav::app {
namespace {

// --window WxH: both in [480, 16384] x [320, 16384] (the window's own minimum).
void parse_window(const std::string& text, uint32_t& w, uint32_t& h) {
  w = h = 0;
  if (text.empty()) return;
  unsigned a = 0, b = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &x, &b, &extra) != 3 || x != 'x' || a < 480 ||
      b < 320 || a > 16384 || b > 16384)
    throw_invalid("masav demo", "--window", text, "WIDTHxHEIGHT, at least 480x320");
  w = a, h = b;
}

int run_demo(const DemoOptions& o) {
  scene::SceneFile file = load_scene(o.scene);
  if (!o.script.empty()) (void)load_script(o.script);  // report script errors before the window
  uint32_t w = 0, h = 0;
  parse_window(o.window, w, h);
  install_interrupt_handler();
  DemoApp demo(o, std::move(file), w, h);
  return demo.loop();
}

}  // namespace

void add_demo_command(CLI::App& app) {
  static DemoOptions o;
  auto* cmd = add_scene_command(app, "demo",
                                "the desktop demo: the scene in a window with a control "
                                "panel (needs a display; `masav run` renders headless)",
                                o, run_demo);
  add_fault_option(*cmd, o.choice);
  cmd->add_option("--script", o.script,
                  "drive the demo from a script (wait N, set K V, view V, scene F, backend B, "
                  "pause, step, reset, verify, panel on|off, key K, button B, rate R, "
                  "progressive auto|off|LEVEL, "
                  "open FILE [dims=X,Y,Z type=T ...], screenshot F, quit)");
  cmd->add_option("--window", o.window, "window size WIDTHxHEIGHT (default: 90% of the screen)");
  cmd->add_option("--out,-o", o.out, "output directory of screenshots, recordings, saved scenes")
      ->capture_default_str();
  cmd->add_flag("--no-verify", o.no_verify, "start without the cross-check");
}

}  // namespace masav::app
