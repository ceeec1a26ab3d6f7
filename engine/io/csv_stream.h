#pragma once
// A CSV table written to its file row by row, each row handed to the OS as soon as it is made:
// an interrupted run keeps every completed row, and a failed write (a full disk) stops the run
// at that row with the file and the reason named.
#include <string>
#include <vector>

#include "engine/io/csv_writer.h"

namespace masav {

class CsvStream {
 public:
  // Creates (truncates) `path` and writes the header; throws masav::Error naming `option` when
  // the file cannot be created.
  CsvStream(const std::string& path, std::vector<std::string> columns, std::string option);
  ~CsvStream();
  CsvStream(const CsvStream&) = delete;
  CsvStream& operator=(const CsvStream&) = delete;

  void row(const std::vector<double>& values);
  const std::string& path() const { return path_; }
  uint64_t rows() const { return rows_; }

 private:
  void flush_pending();
  std::string path_, option_;
  CsvWriter table_;
  int fd_ = -1;
  uint64_t rows_ = 0;
};

}  // namespace masav
