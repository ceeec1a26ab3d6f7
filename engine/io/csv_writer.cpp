#include "engine/io/csv_writer.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav {
namespace {
std::string quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
}  // namespace

CsvWriter::CsvWriter(std::vector<std::string> columns) : columns_(columns.size()) {
  row_text(columns);
}

CsvWriter& CsvWriter::row(const std::vector<double>& values) {
  std::vector<std::string> cells;
  for (double v : values) cells.push_back(fmt::format("{:.9g}", v));
  return row_text(cells);
}

CsvWriter& CsvWriter::row_text(const std::vector<std::string>& cells) {
  if (cells.size() != columns_)
    throw Error("", "csv", fmt::format("row of {} cells for {} columns", cells.size(), columns_),
                "internal error: report it");
  for (size_t i = 0; i < cells.size(); ++i) out_ += (i ? "," : "") + quote(cells[i]);
  out_ += '\n';
  return *this;
}

std::string CsvWriter::take() {
  std::string text;
  text.swap(out_);
  return text;
}

void CsvWriter::write(const std::string& path) const {
  write_file_atomic(path, out_);
}

}  // namespace masav
