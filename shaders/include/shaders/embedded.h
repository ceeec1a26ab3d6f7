#pragma once
// SPIR-V of every compute kernel (shaders/*.comp, by name) and render shader (shaders/render/*,
// as "render/<file>"), compiled at build time.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace masav::shaders {

// The kernel's SPIR-V words; empty if no shader has that name.
std::span<const uint32_t> find(std::string_view name);
std::vector<std::string_view> names();

}  // namespace masav::shaders
