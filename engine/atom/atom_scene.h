#pragma once
// The electron-cloud scene as stages, independent of any command line (the rendering issue
// drives them from scene files): cloud -> density grid -> scattering table (disk cache) ->
// illumination -> view -> voxelize -> raymarch. Each stage reads the buffers of the ones before
// it and can be rerun alone: a new viewpoint reruns view() (and the volume and raymarch), a new
// source power only rescales (light is linear in Phi).
#include <functional>
#include <string>
#include <vector>

#include "engine/atom/orbital_tables.h"
#include "engine/atom/scatter_cache.h"
#include "engine/kernels/backend.h"

namespace masav::atom {

// The source power the light is computed at when a caller rescales it (the thesis's middle
// setting): light is linear in Phi.
constexpr float kReferencePowerLm = 250000.0f;

// Where the light that fixes a state's colour scale is seen from: in front, 1.9 box
// half-diagonals away (`masav atom --view front`, the view the scene files' exposures came from).
Vec3f full_colour_viewer(double box_half_width);

enum class ViewPreset { top, left, front };
ViewPreset parse_view(const std::string& name);  // top, left, front
// Eye at `distance` from the nucleus on the preset's axis, and the matching up vector.
Vec3f view_eye(ViewPreset v, float distance);
Vec3f view_up(ViewPreset v);

struct AtomSceneOptions {
  OrbitalState state;
  OrbitalPlacement placement = OrbitalPlacement::exact;
  uint32_t particles = 200000;
  uint64_t seed = 1;
  TableOptions tables;
  uint32_t density_dims = 60;      // density grid cells per axis (the thesis's cube of size l)
  double box_probability = 0.999;  // the grid's cube holds at least this much of |psi|^2
  ScatterTableParams scatter;      // defaults: thesis §2.2.3 (1000 x 72, g = a = 0.6)
  std::string cache_dir;           // the table's cache (engine/util/cache_dir.h); "" = none
  bool use_cache = true;
  float source_power_lm = 250000.0f;
  Vec3f viewer{0, 0, 0};  // (0, 0, 0) = in front, at 2.5 box half-widths
  float tau_peak = 0.5f;  // scattering depth of one cell at the state's peak density
  OpticalPath path = OpticalPath::exact;
  float step_a0 = 0.0f;       // midpoint path step; 0 = half a cell
  uint32_t volume_dims = 60;  // voxelize: N^3
  float s = 0.6f, t = 0.4f;   // sample = s g + t p (the thesis: s > t)
  float exposure = 0.0f;      // light -> [0, 1] green; 0 = 1 / full_colour_light()
};

struct StageTimes {
  double cloud_ms = 0, density_ms = 0, table_ms = 0, illuminate_ms = 0, view_ms = 0,
         voxelize_ms = 0;
  bool table_from_cache = false;
};

class AtomScene {
 public:
  AtomScene(Backend& b, AtomSceneOptions o);
  // New options for the stages that run next (validated; the derived grids, box and kappa
  // follow). Buffers are kept: a scene graph reruns only the stages whose inputs changed.
  void reconfigure(AtomSceneOptions o);
  // Moves the viewer of view() (the scene graph's camera).
  void set_viewer(Vec3f viewer) { o_.viewer = viewer; }

  void build_cloud();
  void build_density();
  void build_table();
  void illuminate();
  void view();
  // The state's own scale, in cd/a0^2 at the reference power: the 90th percentile of the light
  // seen from full_colour_viewer() (one more view pass where the viewer is elsewhere), kept
  // until the light field changes. It follows the state and its lighting, never the current
  // view; backends differ only by their rounding of the light.
  double full_colour_light();
  void voxelize();
  // Voxelizes with light * light_to_unit as the light (the scene graph folds the source power
  // into it: light is linear in Phi).
  void voxelize(float light_to_unit);
  void run_all();

  Backend& backend() { return b_; }
  const AtomSceneOptions& options() const { return o_; }
  const StageTimes& times() const { return times_; }
  double box_half_width() const { return half_; }
  const GridParams& density_grid() const { return density_grid_; }
  const GridParams& volume_grid() const { return volume_grid_; }
  NebulaLightParams light_params() const;
  // light -> [0, 1]: options().exposure, or 1 / full_colour_light() where that is 0.
  float exposure();
  const ScatterTable& table() const { return table_; }
  // The voxelized volume's description: the box, N^3, values (sample) in [0, 1].
  VolumeDesc volume() const;

  Buffer<Real4> positions;
  Buffer<Real> density, phase, illumination, light;
  Buffer<Real> probability, mean_light, sample;

 private:
  double timed(const std::function<void()>& work);

  Backend& b_;
  AtomSceneOptions o_;
  double half_ = 1;
  GridParams density_grid_, volume_grid_;
  OrbitalTables tables_;
  ScatterTable table_;
  float kappa_ = 1;
  double full_colour_ = 0;  // full_colour_light(); 0 = not measured for this light field
  StageTimes times_;
};

// What raymarch reads besides the volume, on one backend: the transfer function (RGBA entries),
// its bricks, its pre-integrated table (when rp.preintegrate), and the image it writes.
struct RaymarchBuffers {
  Buffer<Real4> tf, bricks, tf_integral, image;
};
RaymarchBuffers prepare_raymarch(Backend& b, const Buffer<Real>& volume,
                                 const std::vector<Vec4d>& tf, const RaymarchParams& rp);
// One frame into r.image.
void raymarch_frame(Backend& b, const RaymarchParams& rp, const Buffer<Real>& volume,
                    RaymarchBuffers& r);

// Raymarches `volume` (on the scene's backend) with the transfer function `tf` (RGBA entries),
// returns the float RGBA image (premultiplied, top row first).
std::vector<Vec4d> render_volume(Backend& b, const VolumeDesc& desc, const Buffer<Real>& volume,
                                 const std::vector<Vec4d>& tf, RaymarchParams rp);
// A camera for `desc`: eye from the preset at 1.9 half-diagonals, step half a voxel.
RaymarchParams default_raymarch(const VolumeDesc& desc, ViewPreset view, uint32_t width,
                                uint32_t height);

}  // namespace masav::atom
