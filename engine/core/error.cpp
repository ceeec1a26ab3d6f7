#include "engine/core/error.h"

#include <fmt/format.h>

namespace masav {
namespace {
std::string compose(const std::string& backend, const std::string& kernel,
                    const std::string& problem, const std::string& remedy) {
  std::string where = backend.empty() ? kernel : (kernel.empty() ? backend : backend + "/" + kernel);
  std::string msg = where.empty() ? problem : fmt::format("{}: {}", where, problem);
  if (!remedy.empty()) msg += fmt::format(" (remedy: {})", remedy);
  return msg;
}
}  // namespace

Error::Error(std::string backend, std::string kernel, std::string problem, std::string remedy)
    : std::runtime_error(compose(backend, kernel, problem, remedy)),
      backend_(std::move(backend)),
      kernel_(std::move(kernel)),
      problem_(std::move(problem)),
      remedy_(std::move(remedy)) {}

void throw_invalid(std::string_view where, std::string_view field, std::string_view value,
                   std::string_view allowed) {
  throw Error("", std::string(where), fmt::format("invalid {} = {}", field, value),
              fmt::format("{} must be {}", field, allowed));
}

}  // namespace masav
