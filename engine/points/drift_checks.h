#pragma once
// Validation of drift_points' inputs, shared by every backend.
#include "engine/core/backend.h"

namespace masav {

void check_drift(const DeviceApi& dev, const DriftParams& p, const Buffer<float>& start,
                 const Buffer<float>& direction, const Buffer<Real4>& positions);

}  // namespace masav
