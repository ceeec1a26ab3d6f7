#pragma once
// Scene parameters, declared once per domain: name, type, default, range, unit and help. From
// the declaration a domain gets parsing and validation of scene files (scene_file.h), the
// documented TOML template (`masav schema`), command-line/script overrides and the demo's ImGui
// controls (app/demo/param_widgets.cpp). Values always exist: a ParamSet starts at the defaults.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace masav::scene {

enum class ParamType : uint8_t { flag, integer, real, choice, text };
const char* param_type_name(ParamType t);

using ParamValue = std::variant<bool, int64_t, double, std::string>;
std::string format_value(const ParamValue& v);

struct ParamSpec {
  std::string key;  // inside its table, e.g. "count"
  ParamType type = ParamType::real;
  std::string help;
  std::string unit;  // "s", "lm", "px", ... (for help text and widgets)
  ParamValue def;
  int64_t int_min = 0, int_max = 0;
  double real_min = 0, real_max = 0;
  std::vector<std::string> choices;
  // Widget hints: a slider moving in `step`s (0: continuous), a logarithmic slider.
  double step = 0;
  bool logarithmic = false;

  // "an integer in [1, 4000000]", "one of front, top, left, orbit", ...
  std::string allowed() const;
  // Converts and range-checks; throws masav::Error naming `path`, the value and allowed().
  ParamValue validate(std::string_view path, const ParamValue& v) const;
};

// The parameters of one TOML table, e.g. [particles] or [render].
class TableSchema {
 public:
  TableSchema(std::string name, std::string help);

  TableSchema& flag(std::string key, bool def, std::string help);
  TableSchema& integer(std::string key, int64_t def, int64_t lo, int64_t hi, std::string help,
                       std::string unit = "");
  TableSchema& real(std::string key, double def, double lo, double hi, std::string help,
                    std::string unit = "");
  TableSchema& choice(std::string key, std::string def, std::vector<std::string> choices,
                      std::string help);
  TableSchema& text(std::string key, std::string def, std::string help);
  // Hints for the parameter declared last.
  TableSchema& steps(double step);
  TableSchema& log_scale();

  const std::string& name() const { return name_; }
  const std::string& help() const { return help_; }
  const std::vector<ParamSpec>& params() const { return params_; }
  const ParamSpec* find(std::string_view key) const;
  std::string keys() const;  // "count, seed, ..." for error messages

 private:
  ParamSpec& add(std::string key, ParamType type, std::string help);
  std::string name_, help_;
  std::vector<ParamSpec> params_;
};

// The values of every table a scene uses, addressed as "table.key". Each value carries a
// version that changes when the value does, so stages can tell what changed (stage_graph.h).
class ParamSet {
 public:
  void add_table(const TableSchema& t);
  bool has_table(std::string_view name) const;
  const std::vector<const TableSchema*>& tables() const { return tables_; }

  bool has(std::string_view path) const { return values_.count(std::string(path)) != 0; }
  const ParamSpec& spec(std::string_view path) const;
  const ParamValue& get(std::string_view path) const;
  bool get_flag(std::string_view path) const;
  int64_t get_int(std::string_view path) const;
  double get_real(std::string_view path) const;
  const std::string& get_text(std::string_view path) const;  // text and choice
  uint64_t version(std::string_view path) const;

  // Validates and stores; returns whether the value changed. Throws masav::Error naming the
  // key, the value and the allowed range (unknown keys list the known ones).
  bool set(std::string_view path, const ParamValue& v);
  // "table.key=value" or (path, text) as typed on a command line or in a script.
  bool set_from_string(std::string_view path, std::string_view text);
  // Paths changed since `version` (for callers that poll).
  std::vector<std::string> changed_since(uint64_t version) const;
  uint64_t clock() const { return clock_; }

 private:
  struct Entry {
    const ParamSpec* spec;
    ParamValue value;
    uint64_t version;
  };
  Entry& entry(std::string_view path);
  const Entry& entry(std::string_view path) const;

  std::vector<const TableSchema*> tables_;
  std::map<std::string, Entry, std::less<>> values_;
  uint64_t clock_ = 0;
};

}  // namespace masav::scene
