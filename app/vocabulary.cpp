#include "app/vocabulary.h"

#include <fmt/format.h>

#include <cstdio>
#include <set>
#include <utility>

#include "engine/sph/sph_presets.h"

namespace masav::app {

void note_old_spelling(const std::string& old_spelling, const std::string& new_spelling) {
  static std::set<std::string> said;
  if (!said.insert(old_spelling).second) return;
  std::fflush(stdout);
  fmt::print(stderr, "note: {} is now {} (the old spelling still works in this release)\n",
             old_spelling, new_spelling);
}

std::string new_value(const std::string& option, const std::string& value) {
  static const std::pair<const char*, const char*> renamed[] = {
      {"dam-break", "dambreak"},
      {"front-to-back", "front_to_back"},
  };
  for (const auto& [old_value, value_now] : renamed)
    if (value == old_value) {
      note_old_spelling(option + " " + old_value, option + " " + value_now);
      return value_now;
    }
  return value;
}

CLI::Option* accept_old_values(CLI::Option* option) {
  const std::string name = option->get_name();
  return option->transform([name](std::string v) { return new_value(name, v); });
}

std::vector<std::string> sph_preset_names() {
  std::vector<std::string> out;
  for (const auto& p : sph_presets()) out.push_back(p.name == "dam-break" ? "dambreak" : p.name);
  return out;
}

std::string engine_sph_preset(const std::string& name) {
  return name == "dambreak" ? "dam-break" : name;
}

}  // namespace masav::app
