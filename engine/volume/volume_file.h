#pragma once
// A volume file as `masav volume` and the demo's "Open" read it: the format from the extension
// (.nrrd/.nhdr, .vti, anything else raw), with the options each format reads. Both callers go
// through load_volume_file, so a file is accepted or refused with the same message everywhere.
#include <string>
#include <vector>

#include "engine/volume/volume_io.h"

namespace masav::volume {

struct VolumeFileOptions {
  std::string file;
  std::vector<uint32_t> dims;  // raw: X, Y, Z
  std::string type;            // raw: uint8, int16, float32, ...
  std::vector<float> spacing;  // raw: voxel size X, Y, Z (empty: 1, 1, 1)
  bool big_endian = false;     // raw
  std::string array;           // vti: the array to read ("" = the first)
};

// Options that only a raw file (or only a .vti) reads are refused for the other formats, whose
// headers say the same thing: naming both beats silently ignoring one.
void check_volume_file_options(const VolumeFileOptions& o);
// Checks the options, then reads the file with its format's loader.
ScalarVolume load_volume_file(const VolumeFileOptions& o);

}  // namespace masav::volume
