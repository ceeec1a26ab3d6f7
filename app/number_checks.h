#pragma once
// One rule for every number a command takes: CLI11 parses it into its option's type and checks
// the option's range; this adds, to every floating-point option of every command, that the value
// is finite (CLI11 takes nan and inf as numbers, and nan passes every range test). The test
// cli.numbers walks every numeric option of every command with nan, inf, -0, 0 and 2^64.
#include <CLI/CLI.hpp>

namespace masav::app {

// A number in [lo, hi] (lo_open: (lo, hi]), named in the message as the user wrote it and the
// range as a person reads it ("must be in (0, 10]").
CLI::Validator number_in(double lo, double hi, bool lo_open = false);

// Every floating-point option of `app` and of its subcommands, recursively, refuses a value that
// is not finite, naming the option.
void require_finite_numbers(CLI::App& app);
// For the tests: every command's callback does nothing, so that a command line is parsed and
// checked without running (`masav --parse-only COMMAND ...`).
void skip_commands(CLI::App& app);

}  // namespace masav::app
