#pragma once
// Scalar volumes from files for raymarch: raw (with dims and type given), NRRD (attached or
// detached data, raw or ASCII encoding) and VTK ImageData (.vti: ASCII, inline base64 or appended
// data, uncompressed). Samples are voxel centres; values are converted to fp32. Every
// inconsistency (a size that does not match the dims, an unknown type, a compressed file, a header
// field masav does not read) is an error naming the field. Files are read bounded: regular files
// only, sizes parsed as whole 64-bit numbers (never wrapped), each axis in [2, 8192], and the
// declared data checked against the file's size before anything is allocated for it.
//
// Every type's extremes survive: samples are read as double, their range is found in double, and
// only then do they become fp32. A range fp32 cannot hold or resolve -- magnitudes beyond 2^64
// (float32 near +-FLT_MAX, float64 beyond it), a width below 2^-64 (1e-300, denormals) or below
// 2^-12 of the values' magnitude (1e9 + [0, 100]) -- is normalised to [0, 1] in double first, so
// it keeps fp32's 24 bits across the range; min and max still report the raw range. Non-finite
// samples are an error. A multi-byte raw NRRD must say its endian (little or big).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/kernels/atom_params.h"

namespace masav::volume {

enum class SampleType { u8, i8, u16, i16, u32, i32, f32, f64 };
SampleType parse_sample_type(const std::string& name);  // uint8, int16, float32, ...
size_t sample_bytes(SampleType t);

struct ScalarVolume {
  UVec3 dims{1, 1, 1};
  Vec3f origin{0, 0, 0};   // corner of the box (box_min)
  Vec3f spacing{1, 1, 1};  // voxel size
  // The samples as raymarch reads them, x fastest: the raw values, or (raw - min) / (max - min)
  // when `normalised` (a constant volume then holds 1, or 0 where it is 0).
  std::vector<float> values;
  double min = 0, max = 0;  // the raw samples' range
  bool normalised = false;
};

// Sets v.values, v.min, v.max and v.normalised from raw samples, as every loader does; a NaN or
// infinite sample is an error naming `where`.
void set_samples(ScalarVolume& v, std::span<const double> raw, const std::string& where);

ScalarVolume load_raw(const std::string& path, UVec3 dims, SampleType type, bool big_endian = false,
                      Vec3f spacing = {1, 1, 1});
ScalarVolume load_nrrd(const std::string& path);
// `array`: the PointData/CellData array to read ("" = the first one).
ScalarVolume load_vti(const std::string& path, const std::string& array = "");

// The raymarch description: box from origin and spacing, the stored values' range ([0, 1] when
// normalised). A constant volume's range ends at its value, so that it shows as the transfer
// function's top: [0, c] for c > 0, [2c, c] for c < 0, [0, 1] for 0 (empty).
VolumeDesc volume_desc(const ScalarVolume& v);

}  // namespace masav::volume
