#pragma once
// The pre-integrated table of a transfer function, which raymarch reads (its tf_integral) when
// RaymarchParams::preintegrate is on: per entry, the emission and optical depth there and their
// integrals from the first entry (layout: volume::segment_mean in
// engine/kernels/volume_transfer.h).
#include <vector>

#include "engine/core/types.h"
#include "engine/kernels/backend.h"

namespace masav::volume {

// Optical depth is capped at -ln(kMinTransmittance) per reference step, so that an entry of
// alpha 1 (transmittance 0) has a finite depth: beyond it a reference step is opaque anyway.
inline constexpr double kMinTransmittance = 1e-6;

// kPreintegratedPerEntry * tf.size() entries, computed in double.
std::vector<Vec4d> preintegrate_transfer(const std::vector<Vec4d>& tf);
// That table on backend b.
Buffer<Real4> upload_preintegrated(Backend& b, const std::vector<Vec4d>& tf);

}  // namespace masav::volume
