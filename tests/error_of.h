#pragma once
// The message of the masav::Error that `f()` throws, or "(no error)" when it returns: what the
// tests of bad input compare with the text a user sees.
#include <string>

#include "engine/core/error.h"

namespace masav::test {

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace masav::test
