#pragma once
// Whether two arrays hold the same bits (float results that must be exactly equal, where
// operator== would also equate 0 and -0 and never equate NaNs, or is not defined).
#include <cstring>
#include <vector>

namespace masav::test {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace masav::test
