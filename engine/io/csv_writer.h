#pragma once
// CSV tables (header + rows of numbers or text), written atomically (CsvStream streams them).
#include <string>
#include <vector>

namespace masav {

class CsvWriter {
 public:
  explicit CsvWriter(std::vector<std::string> columns);
  CsvWriter& row(const std::vector<double>& values);
  CsvWriter& row_text(const std::vector<std::string>& cells);
  const std::string& str() const { return out_; }
  // The text made so far, which is then forgotten (for writers that stream rows out).
  std::string take();
  void write(const std::string& path) const;

 private:
  size_t columns_;
  std::string out_;
};

}  // namespace masav
