#pragma once
// The one exception type masav throws at its API edge. Its message names where the problem
// happened (backend and kernel, or the input field), what went wrong, and what to do about it.
#include <stdexcept>
#include <string>
#include <string_view>

namespace masav {

class Error : public std::runtime_error {
 public:
  Error(std::string backend, std::string kernel, std::string problem, std::string remedy);

  const std::string& backend() const { return backend_; }
  const std::string& kernel() const { return kernel_; }
  const std::string& problem() const { return problem_; }
  const std::string& remedy() const { return remedy_; }

 private:
  std::string backend_, kernel_, problem_, remedy_;
};

// Input validation failures: `field` names the flag, key or argument, `allowed` the valid range.
[[noreturn]] void throw_invalid(std::string_view where, std::string_view field,
                                std::string_view value, std::string_view allowed);

}  // namespace masav
