#include <set>

#include "engine/core/error.h"
#include "masav/cross_check.h"
#include "registry/check_catalog.h"
#include "registry/kernel_check_inputs.h"

namespace masav {
namespace {

KernelId kernel_named(std::string_view name) {
  const auto k = find_kernel(name);
  if (!k) throw_invalid("masav::cross_check", "kernel", name, std::string(kernel_names_list()));
  return *k;
}

}  // namespace

verify::CrossCheckReport cross_check(std::string_view kernel, Backend& backend, Backend& reference,
                                     const CrossCheckOptions& options) {
  return cross_check(std::vector<std::string>{std::string(kernel)}, backend, reference, options);
}

verify::CrossCheckReport cross_check(const std::vector<std::string>& kernels, Backend& backend,
                                     Backend& reference, const CrossCheckOptions& options) {
  std::vector<std::string> names = kernels;
  if (names.size() == 1 && names[0] == "all") {
    names.clear();
    for (KernelId k : kAllKernels) names.emplace_back(kernel_name(k));
  }
  if (names.empty()) throw_invalid("masav::cross_check", "kernels", "{}", "at least one kernel");
  // Each kernel on the inputs of its own scene, as `masav verify` sizes them; one report.
  verify::CrossCheckReport all;
  std::set<std::string> scenes;
  for (const std::string& name : names) {
    const verify::KernelCheckInputs ki = verify::kernel_check_inputs(
        kernel_named(name), options.points, options.seed, "masav::cross_check");
    verify::CrossCheckReport r = verify::cross_check(backend, reference, {name}, ki.in,
                                                     options.inject_fault);
    if (all.rows.empty()) all = r, all.rows.clear();
    scenes.insert(ki.scene);
    for (auto& row : r.rows) all.rows.push_back(std::move(row));
  }
  all.scene.clear();
  for (const std::string& s : scenes) all.scene += (all.scene.empty() ? "" : "+") + s;
  return all;
}

std::string report_text(const verify::CrossCheckReport& report) {
  return verify::format_report(report);
}

std::string report_json_text(const verify::CrossCheckReport& report) {
  return verify::report_json(report);
}

}  // namespace masav
