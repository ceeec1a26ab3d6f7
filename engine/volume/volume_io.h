#pragma once
// Scalar volumes from files for raymarch: raw (with dims and type given), NRRD (attached or
// detached data, raw or ASCII encoding) and VTK ImageData (.vti: ASCII, inline base64 or appended
// data, uncompressed). Samples are voxel centres; values are converted to fp32. Every
// inconsistency (a size that does not match the dims, an unknown type, a compressed file, a header
// field masav does not read) is an error naming the field. Files are read bounded: regular files
// only, sizes parsed as whole 64-bit numbers (never wrapped), each axis in [2, 8192], and the
// declared data checked against the file's size before anything is allocated for it.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/kernels/atom_params.h"

namespace masav::volume {

enum class SampleType { u8, i8, u16, i16, u32, i32, f32, f64 };
SampleType parse_sample_type(const std::string& name);  // uint8, int16, float32, ...
size_t sample_bytes(SampleType t);

struct ScalarVolume {
  UVec3 dims{1, 1, 1};
  Vec3f origin{0, 0, 0};      // corner of the box (box_min)
  Vec3f spacing{1, 1, 1};     // voxel size
  std::vector<float> values;  // x fastest
  float min = 0, max = 0;
};

ScalarVolume load_raw(const std::string& path, UVec3 dims, SampleType type, bool big_endian = false,
                      Vec3f spacing = {1, 1, 1});
ScalarVolume load_nrrd(const std::string& path);
// `array`: the PointData/CellData array to read ("" = the first one).
ScalarVolume load_vti(const std::string& path, const std::string& array = "");

// The raymarch description: box from origin and spacing, value range [min, max] (widened when
// the volume is constant).
VolumeDesc volume_desc(const ScalarVolume& v);

}  // namespace masav::volume
