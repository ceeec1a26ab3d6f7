#pragma once
// Colour maps for per-point scalars: 256 RGBA entries, interpolated between published anchor
// colours (viridis and inferno at nine evenly spaced samples), the thesis's blue -> green -> red
// transfer function, and grey.
#include <array>
#include <string_view>

#include "engine/core/types.h"

namespace masav::render {

using ColormapTable = std::array<Vec4f, 256>;
ColormapTable colormap_table(std::string_view name);  // viridis, inferno, thesis, grey

}  // namespace masav::render
