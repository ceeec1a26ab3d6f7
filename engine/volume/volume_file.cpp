#include "engine/volume/volume_file.h"

#include <fmt/format.h>

#include <filesystem>
#include <utility>

#include "engine/core/error.h"

namespace masav::volume {
namespace {

std::string extension_of(const std::string& file) {
  return std::filesystem::path(file).extension().string();
}

bool is_nrrd(const std::string& ext) {
  return ext == ".nrrd" || ext == ".nhdr";
}

}  // namespace

void check_volume_file_options(const VolumeFileOptions& o) {
  const std::string ext = extension_of(o.file);
  const bool raw = !is_nrrd(ext) && ext != ".vti";
  const std::pair<bool, const char*> raw_only[] = {{!o.dims.empty(), "--dims"},
                                                   {!o.type.empty(), "--type"},
                                                   {!o.spacing.empty(), "--spacing"},
                                                   {o.big_endian, "--big-endian"}};
  for (const auto& [given, name] : raw_only)
    if (given && !raw)
      throw Error("", name,
                  fmt::format("{} conflicts with the {} file '{}', whose header describes it", name,
                              ext, o.file),
                  fmt::format("drop {} (it is for raw files)", name));
  if (!o.array.empty() && ext != ".vti")
    throw Error("", "--array", fmt::format("--array conflicts with the file '{}'", o.file),
                "drop --array (it picks an array of a .vti file)");
}

ScalarVolume load_volume_file(const VolumeFileOptions& o) {
  check_volume_file_options(o);
  const std::string ext = extension_of(o.file);
  if (is_nrrd(ext)) return load_nrrd(o.file);
  if (ext == ".vti") return load_vti(o.file, o.array);
  if (o.dims.size() != 3)
    throw_invalid("masav volume", "--dims", fmt::format("{} values", o.dims.size()),
                  "three sizes X,Y,Z for a raw file");
  if (o.type.empty())
    throw_invalid("masav volume", "--type", "none",
                  "the sample type of a raw file (uint8, int16, float32, ...)");
  if (!o.spacing.empty() && o.spacing.size() != 3)
    throw_invalid("masav volume", "--spacing", fmt::format("{} values", o.spacing.size()),
                  "three voxel sizes X,Y,Z");
  Vec3f sp{1, 1, 1};
  if (o.spacing.size() == 3) sp = {o.spacing[0], o.spacing[1], o.spacing[2]};
  return load_raw(o.file, {o.dims[0], o.dims[1], o.dims[2]}, parse_sample_type(o.type),
                  o.big_endian, sp);
}

}  // namespace masav::volume
