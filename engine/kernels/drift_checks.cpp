#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/kernels/drift_params.h"

namespace masav {

void validate(const DeviceApi&, const DriftParams& p, const Buffer<float>& start,
              const Buffer<float>& direction, const Buffer<Real4>& positions) {
  constexpr const char* k = "drift_points";
  if (uint64_t(p.n) * 4 > start.size() || uint64_t(p.n) * 4 > direction.size() ||
      p.n > positions.size())
    throw_invalid(k, "n", std::to_string(p.n),
                  fmt::format("at most the buffers' sizes (start {} / 4, direction {} / 4, "
                              "positions {})",
                              start.size(), direction.size(), positions.size()));
  const float lo[3] = {p.box_lo.x, p.box_lo.y, p.box_lo.z};
  const float ext[3] = {p.box_extent.x, p.box_extent.y, p.box_extent.z};
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(lo[a]))
      throw_invalid(k, "box_lo", fmt::format("({}, {}, {})", lo[0], lo[1], lo[2]), "finite");
    if (!std::isfinite(ext[a]) || !(ext[a] > 0))
      throw_invalid(k, "box_extent", fmt::format("({}, {}, {})", ext[0], ext[1], ext[2]),
                    "finite and > 0 on every axis");
  }
  if (!std::isfinite(p.speed) || p.speed < 0 || p.speed > 1000)
    throw_invalid(k, "speed", fmt::format("{}", p.speed), "in [0, 1000] box lengths per second");
  // Beyond |speed * time| = 2^16 box lengths a float keeps fewer than 8 bits of the fraction.
  if (!std::isfinite(p.time_s) || std::abs(double(p.speed) * p.time_s) > 65536.0)
    throw_invalid(k, "time_s", fmt::format("{}", p.time_s),
                  "finite, with |speed * time_s| <= 65536 box lengths");
}

}  // namespace masav
