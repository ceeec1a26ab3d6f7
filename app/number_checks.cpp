#include "app/number_checks.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace masav::app {
namespace {

// "" for a finite number or for text that is no number at all (CLI11's conversion names that).
std::string finite_or_why(std::string& text) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    return "";
  }
  if (used != text.size() || std::isfinite(v)) return "";
  return "the value " + text + " is not a finite number";
}

template <class Fn>
void each_command(CLI::App& app, const Fn& fn) {
  fn(app);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) each_command(*sub, fn);
}

}  // namespace

CLI::Validator number_in(double lo, double hi, bool lo_open) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        size_t used = 0;
        double v = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          return "";  // not a number: CLI11's conversion says so
        }
        if (used != text.size()) return "";
        if (std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi) return "";
        return fmt::format("the value {} must be in {}{}, {}]", text, lo_open ? "(" : "[", lo, hi);
      },
      fmt::format("{}{}, {}]", lo_open ? "(" : "[", lo, hi));
}

void require_finite_numbers(CLI::App& app) {
  each_command(app, [](CLI::App& cmd) {
    for (CLI::Option* opt : cmd.get_options([](CLI::Option* o) { return o->get_type_name().rfind("FLOAT", 0) == 0; }))
      opt->check(CLI::Validator(finite_or_why, ""));
  });
}

void skip_commands(CLI::App& app) {
  each_command(app, [](CLI::App& cmd) {
    if (cmd.get_parent()) cmd.callback([] {});
  });
}

}  // namespace masav::app
