#pragma once
// The kernel checks of each domain, collected by kernel_checks() (check_registry.cpp).
#include <vector>

#include "engine/verify/kernel_check.h"

namespace masav::verify {

std::vector<KernelCheck> foundation_checks();  // engine/verify/foundation_checks.cpp
std::vector<KernelCheck> points_checks();      // engine/points/points_checks.cpp
std::vector<KernelCheck> sph_checks();         // engine/sph/sph_cross_checks.cpp
std::vector<KernelCheck> atom_checks();        // engine/atom/atom_cross_checks.cpp

}  // namespace masav::verify
