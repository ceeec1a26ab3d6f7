#pragma once
// A device refused a size: a buffer over its per-buffer limit (DeviceCapabilities'
// max_buffer_bytes, as tuning lowers it). The cross-check reports such a kernel as "not compared",
// and a scene turns the limit into the largest setting that fits (SceneType::fit_advice).
#include <cstdint>
#include <string>
#include <utility>

#include "engine/core/error.h"

namespace masav {

class LimitError : public Error {
 public:
  LimitError(std::string backend, std::string kernel, std::string problem, std::string remedy,
             uint64_t limit_bytes)
      : Error(std::move(backend), std::move(kernel), std::move(problem), std::move(remedy)),
        limit_bytes_(limit_bytes) {}
  uint64_t limit_bytes() const { return limit_bytes_; }

 private:
  uint64_t limit_bytes_;
};

}  // namespace masav
