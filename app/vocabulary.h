#pragma once
// One name and one meaning per concept on the command line (README "One vocabulary"): a count of
// particles is --particles, frames are --frames, --n/--l/--m are quantum numbers, --out is an
// output directory, and a value is spelled as scene files spell it (dambreak, front_to_back).
// The spellings used before are hidden from --help and still accepted, with a note on stderr
// naming the new one.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace masav::app {

// Prints once per process and spelling: "note: OLD is now NEW (...)".
void note_old_spelling(const std::string& old_spelling, const std::string& new_spelling);

// A hidden option `old_name` that sets the same value as `new_name`.
template <class T>
CLI::Option* add_old_option(CLI::App& cmd, const std::string& old_name, const std::string& new_name,
                            T& value) {
  return cmd.add_option(old_name, value)->group("")->each([old_name, new_name](const std::string&) {
    note_old_spelling(old_name, new_name);
  });
}

// The value as scene files spell it: dam-break -> dambreak, front-to-back -> front_to_back
// (with the note); any other value unchanged.
std::string new_value(const std::string& option, const std::string& value);
// Adds new_value as the option's first transform.
CLI::Option* accept_old_values(CLI::Option* option);

// The SPH presets as scene files spell them (dambreak), and a preset's name in the engine.
std::vector<std::string> sph_preset_names();
std::string engine_sph_preset(const std::string& name);

}  // namespace masav::app
