#include "app/demo/demo_script.h"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <map>
#include <sstream>

#include "app/demo/demo_actions.h"
#include "app/demo/progressive.h"
#include "app/demo/tf_points.h"
#include "app/demo/volume_open.h"
#include "engine/core/error.h"
#include "engine/scene/scene.h"
#include "engine/util/bounded_file.h"

namespace masav::app {
namespace {

struct Form {
  size_t args;  // at least this many; exactly this many unless `more`
  std::string usage;
  bool more = false;
};

const std::map<std::string, Form>& forms() {
  static const std::map<std::string, Form> f = {
      {"wait", {1, "wait N"}},
      {"set", {2, "set TABLE.KEY VALUE"}},
      {"view", {1, "view front|top|left|orbit"}},
      {"orbit", {2, "orbit YAW_DEG PITCH_DEG"}},
      {"scene", {1, "scene PATH"}},
      {"backend", {1, "backend vulkan|cuda|cpu"}},
      {"pause", {0, "pause"}},
      {"resume", {0, "resume"}},
      {"step", {0, "step"}},
      {"reset", {0, "reset"}},
      {"verify", {0, "verify"}},
      {"panel", {1, "panel on|off"}},
      {"screenshot", {1, "screenshot PATH"}},
      {"key", {1, "key " + shortcut_names()}},
      {"button", {1, "button pause|step|reset|screenshot|record|save|panel"}},
      {"rate", {1, "rate SIMULATED_SECONDS_PER_SECOND|off"}},
      {"progressive", {1, "progressive auto|off|LEVEL"}},
      {"open",
       {1, "open PATH [dims=X,Y,Z] [type=T] [spacing=X,Y,Z] [big_endian] [array=NAME]", true}},
      {"tf", {1, "tf load FILE|save FILE|reset|point V R G B A|delete V", true}},
      {"drop", {1, "drop PATH [PATH...] (as files dropped on the window)", true}},
      {"quit", {0, "quit"}},
  };
  return f;
}

}  // namespace

std::vector<ScriptCommand> load_script(const std::string& path) {
  std::istringstream in(read_bounded_file(path, "--script"));
  std::vector<ScriptCommand> out;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    ScriptCommand c;
    c.line = line;
    if (!(words >> c.verb)) continue;
    for (std::string w; words >> w;) c.args.push_back(w);
    const std::string at = fmt::format("{}:{}", path, line);
    const auto it = forms().find(c.verb);
    if (it == forms().end()) {
      std::string all;
      for (const auto& [verb, form] : forms()) all += (all.empty() ? "" : ", ") + verb;
      throw_invalid(at, "script command", c.verb, "one of " + all);
    }
    if (c.args.size() < it->second.args || (c.args.size() > it->second.args && !it->second.more))
      throw_invalid(at, "arguments of " + c.verb, std::to_string(c.args.size()),
                    fmt::format("{}{} (as in: {})", it->second.more ? "at least " : "",
                                it->second.args, it->second.usage));
    if (c.verb == "wait") {
      int n = 0;
      const auto& a = c.args[0];
      const auto [p, ec] = std::from_chars(a.data(), a.data() + a.size(), n);
      if (ec != std::errc() || p != a.data() + a.size() || n < 1 || n > 100000)
        throw_invalid(at, "wait", a, "a frame count in [1, 100000]");
    }
    if (c.verb == "view" && c.args[0] != "front" && c.args[0] != "top" && c.args[0] != "left" &&
        c.args[0] != "orbit")
      throw_invalid(at, "view", c.args[0], "front, top, left or orbit");
    if (c.verb == "panel" && c.args[0] != "on" && c.args[0] != "off")
      throw_invalid(at, "panel", c.args[0], "on or off");
    if (c.verb == "key" && !shortcut_by_name(c.args[0]))
      throw_invalid(at, "key", c.args[0], "one of " + shortcut_names());
    if (c.verb == "button" && !button_by_name(c.args[0]))
      throw_invalid(at, "button", c.args[0], "one of " + button_names());
    if (c.verb == "open") (void)open_fields_from_words(c.args, at);
    if (c.verb == "tf") check_tf_words(c.args, at);
    if (c.verb == "rate" && c.args[0] != "off") {
      char* end = nullptr;
      const double r = std::strtod(c.args[0].c_str(), &end);
      if (end != c.args[0].c_str() + c.args[0].size() || !(r >= 0.001 && r <= 10))
        throw_invalid(at, "rate", c.args[0], "simulated seconds per second in [0.001, 10], or off");
    }
    if (c.verb == "progressive" && !progressive_mode_from_word(c.args[0]))
      throw_invalid(
          at, "progressive", c.args[0],
          fmt::format("auto, off, or a preview level in [1, {}]", scene::kMaxPreviewLevel));
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace masav::app
