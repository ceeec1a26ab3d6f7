#pragma once
// A small streaming JSON writer for benchmark records and reports, and atomic file writes
// (temporary name, then rename: an interrupted run never leaves a truncated file).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/util/output_file.h"

namespace masav {

class JsonWriter {
 public:
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view k);
  JsonWriter& value(std::string_view v);
  JsonWriter& value(const char* v) { return value(std::string_view(v)); }
  JsonWriter& value(double v);
  JsonWriter& value(int64_t v);
  JsonWriter& value(uint64_t v);
  JsonWriter& value(int v) { return value(int64_t(v)); }
  JsonWriter& value(unsigned v) { return value(uint64_t(v)); }
  JsonWriter& value(bool v);
  template <class T>
  JsonWriter& field(std::string_view k, const T& v) {
    key(k);
    return value(v);
  }
  const std::string& str() const { return out_; }

 private:
  void before_value();
  void newline();
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

std::string json_escape(std::string_view s);
// Writes `content` to path: a regular file via a temporary file in the same directory and a
// rename, a device or pipe in place (write_output, engine/util/output_file.h).
void write_file_atomic(const std::string& path, std::string_view content);

}  // namespace masav
