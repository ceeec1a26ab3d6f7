#pragma once
// The byte level of SPH checkpoints (sph_checkpoint.h): a writer of a section's payload, a
// bounded reader over one (every size checked against the bytes left before anything is
// allocated, every failure naming the file, the section, the field and what was expected).
// Shared by the file framing (sph_checkpoint.cpp) and the sections (sph_checkpoint_sections.cpp).
#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "engine/core/error.h"

namespace masav::checkpoint_io {

inline constexpr const char* kRemedy =
    "restart from an intact checkpoint (the run keeps only the newest: copy it away to keep "
    "more), or start the run again";

[[noreturn]] inline void fail(const std::string& path, std::string_view field,
                              std::string_view problem) {
  throw Error("", "sph checkpoint", fmt::format("{}: {}: {}", path, field, problem), kRemedy);
}

// ---- writing

class Out {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    put(uint64_t(v.size()));
    const auto* p = reinterpret_cast<const uint8_t*>(v.data());
    bytes_.insert(bytes_.end(), p, p + v.size() * sizeof(T));
  }
  void string(const std::string& s) {
    put(uint32_t(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

// ---- reading: a bounded cursor over one section's payload

class In {
 public:
  In(std::span<const uint8_t> b, const std::string& path, std::string section)
      : b_(b), path_(path), section_(std::move(section)) {}

  template <class T>
  T get(std::string_view field) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), field);
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  bool flag(std::string_view field) {
    const uint8_t v = get<uint8_t>(field);
    if (v > 1) fail(path_, name(field), fmt::format("{} where 0 or 1 was expected", v));
    return v == 1;
  }
  double real(std::string_view field) { return get<double>(field); }
  template <class E>
  E enumeration(std::string_view field, E last) {
    const uint32_t v = get<uint32_t>(field);
    if (v > uint32_t(last))
      fail(path_, name(field), fmt::format("{} where 0 to {} was expected", v, uint32_t(last)));
    return E(v);
  }
  // `count` values exactly (0 or the particle count), checked against the bytes left before
  // anything is allocated.
  template <class T>
  std::vector<T> array(std::string_view field, uint64_t count) {
    const uint64_t n = get<uint64_t>(field);
    if (n != count)
      fail(path_, name(field), fmt::format("{} values where {} were expected", n, count));
    if (n > (b_.size() - pos_) / sizeof(T))
      fail(path_, name(field),
           fmt::format("{} values need {} bytes, the section has {} left (truncated?)", n,
                       n * sizeof(T), b_.size() - pos_));
    std::vector<T> v(n);
    std::memcpy(v.data(), b_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return v;
  }
  std::string string(std::string_view field, uint32_t max_bytes) {
    const uint32_t n = get<uint32_t>(field);
    if (n > max_bytes)
      fail(path_, name(field),
           fmt::format("{} bytes where at most {} were expected", n, max_bytes));
    need(n, field);
    std::string s(reinterpret_cast<const char*>(b_.data() + pos_), n);
    pos_ += n;
    return s;
  }
  void end() {
    if (pos_ != b_.size())
      fail(path_, section_,
           fmt::format("{} bytes past its last field (a file of another layout?)",
                       b_.size() - pos_));
  }

 private:
  std::string name(std::string_view field) const { return fmt::format("{}.{}", section_, field); }
  void need(uint64_t bytes, std::string_view field) {
    if (bytes > b_.size() - pos_)
      fail(path_, name(field),
           fmt::format("needs {} bytes, the section has {} left (truncated?)", bytes,
                       b_.size() - pos_));
  }
  std::span<const uint8_t> b_;
  size_t pos_ = 0;
  const std::string& path_;
  std::string section_;
};

}  // namespace masav::checkpoint_io
