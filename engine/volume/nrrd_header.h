#pragma once
// A NRRD header read field by field: each field is honoured (type, dimension, sizes, encoding,
// endian, spacings, space directions, space origin, data file, line skip, byte skip), accepted as
// information that does not change the samples (content, kinds, labels, units, ...), or refused by
// name. Sizes are whole 64-bit integers checked against the allowed range, never wrapped. As NRRD
// requires, raw data of multi-byte samples must name its endian.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "engine/volume/volume_io.h"

namespace masav::volume {

enum class NrrdEncoding { raw, ascii };

struct NrrdHeader {
  SampleType type = SampleType::u8;
  UVec3 dims{1, 1, 1};
  NrrdEncoding encoding = NrrdEncoding::raw;
  bool big_endian = false;
  Vec3f spacing{1, 1, 1};
  Vec3f origin{0, 0, 0};
  std::string data_file;            // "" = the data follow the header in the same file
  std::optional<uint64_t> data_at;  // where attached data start (after the blank line)
  uint64_t line_skip = 0;           // lines skipped at the start of the data
  int64_t byte_skip = 0;            // bytes skipped after them; -1: the data end the file (raw)
  std::string sizes_text;           // the sizes line as written, for messages
};

// `head`: the file's first bytes (up to the blank line that ends the header, or all of a detached
// header). `where` names the file in messages.
NrrdHeader parse_nrrd_header(std::string_view head, const std::string& where);

}  // namespace masav::volume
