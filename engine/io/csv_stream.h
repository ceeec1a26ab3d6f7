#pragma once
// A CSV table written to a file row by row, each row handed to the OS as soon as it is made, and
// the old file replaced only when the table is committed:
//   - a regular file (or a link to one) is streamed into a partial file beside it,
//     `.NAME.masav-partial`, renamed over the path by commit(); a run that is refused before it
//     commits leaves an existing file as it was, and the partial is removed;
//   - a device or pipe (/dev/stdout, a FIFO) is written in place, row by row;
//   - a directory or anything else is refused (engine/util/output_file.h).
// A failed write (a full disk) cuts the partial back to its last whole row and throws, naming
// the file, the rows already in it and the reason. Two runs streaming into one file are refused:
// the partial is locked by its writer.
#include <string>
#include <vector>

#include "engine/io/csv_writer.h"

namespace masav {

class CsvStream {
 public:
  // Opens the partial (or the device) and writes the header; throws masav::Error naming
  // `option` when it cannot.
  CsvStream(const std::string& path, std::vector<std::string> columns, std::string option);
  ~CsvStream();  // removes an uncommitted partial
  CsvStream(const CsvStream&) = delete;
  CsvStream& operator=(const CsvStream&) = delete;

  void row(const std::vector<double>& values);
  // The rows so far become the file at path(): the partial renamed over it (nothing to do for a
  // device). Later rows go on into the file. Throws masav::Error when the rename fails.
  void commit();
  const std::string& path() const { return path_; }
  // Where the rows are being written before commit() (the path itself for a device).
  const std::string& partial_path() const { return partial_; }
  uint64_t rows() const { return rows_; }

 private:
  void flush_pending();
  std::string path_, target_, partial_, option_;
  CsvWriter table_;
  int fd_ = -1;
  bool in_place_ = false, committed_ = false;
  uint64_t rows_ = 0;
  uint64_t bytes_ = 0;  // written so far: the length to cut back to after a failed row
};

}  // namespace masav
