#pragma once
// Export of the electron-cloud scene: particles as VTK PolyData (.vtp: position, light,
// illumination, state), the voxel grid as VTK ImageData (.vti: p, g, sample), the scattering
// table as CSV, images as PNG. All written to a temporary name and renamed.
#include <string>
#include <vector>

#include "engine/atom/atom_scene.h"

namespace masav::atom {

void write_cloud_vtp(AtomScene& scene, const std::string& path);
void write_volume_vti(AtomScene& scene, const std::string& path);
// Any scalar volume on a backend (e.g. a loaded file) as .vti, the array named `name`.
void write_scalar_vti(const VolumeDesc& desc, const std::vector<double>& values,
                      const std::string& name, const std::string& path);
void write_image_png(const std::vector<Vec4d>& image, uint32_t width, uint32_t height,
                     const std::string& path);

}  // namespace masav::atom
