#pragma once
// Parameter structs of the electron-cloud, nebula-lighting and volume kernels (backend.h, section
// "electron cloud, nebula lighting, volume"). Plain data read by every backend; the shared
// validators in engine/atom/atom_checks.h reject bad values before any dispatch. Lengths are in
// Bohr radii (a0) unless a name says otherwise.
#include <cstdint>

#include "engine/core/buffer.h"
#include "engine/core/kernel_params.h"
#include "engine/core/types.h"

namespace masav {

class DeviceApi;

// ---- orbital_sample ---------------------------------------------------------------------------
enum class OrbitalPlacement : uint32_t {
  exact = 0,   // inverse-CDF tables of the separable factors of |psi|^2 (engine/atom/orbital_tables.h)
  shells = 1,  // the thesis's shell placement (Algorithm 2.1): sites on shells, stratified jitter
};

// Cumulative tables live in one uint32 buffer: `exact` holds three CDFs scaled to 2^24 (radial
// over r in [0, radial_max_a0], polar over cos(theta) in [-1, 1], azimuthal over psi in [0, pi)),
// one after the other, each with bins + 1 entries; `shells` holds the cumulative particle count
// over sites (radial_bins * polar_bins * azimuth_bins sites, one table). Build them with
// make_orbital_tables(); the kernel only inverts them.
struct OrbitalSampleParams {
  uint32_t count = 0;  // particles drawn into positions[0..count)
  uint64_t seed = 0;   // Philox key; particle i uses block i of stream kOrbitalStream
  OrbitalPlacement placement = OrbitalPlacement::exact;
  uint32_t radial_bins = 0;
  uint32_t polar_bins = 0;
  uint32_t azimuth_bins = 0;     // exact: 0 = phi uniform (complex orbitals and m = 0)
  float radial_max_a0 = 0;       // outer edge of the radial table (or of the outermost shell)
  uint32_t azimuth_periods = 1;  // real orbitals: cos^2(|m| phi) has 2|m| periods in [0, 2 pi)
  float azimuth_offset = 0;      // pi/2 turns cos^2 into sin^2 (real orbitals with m < 0)
};
constexpr uint64_t kOrbitalStream = 0x0A70'0000'0000'0001ull;
constexpr uint32_t kCdfOne = 1u << 24;  // exact tables: CDF values are integers out of 2^24

// ---- cloud density ----------------------------------------------------------------------------
// density[c] = (cell_end[c] - cell_start[c]) / (particles * cell_size^3): probability per a0^3 of
// each hash-grid cell (points outside the grid are clamped into its boundary cells, so the
// densities sum to 1 / cell volume).
struct CloudDensityParams {
  GridParams grid;
  uint32_t particles = 0;
};

// ---- scatter_table ----------------------------------------------------------------------------
enum class ScatterStart : uint32_t {
  surface = 0,  // X0 = C - l * d0, heading along d0 (thesis §2.2.3)
  centre = 1,   // X0 = C
};

// Monte Carlo multiple scattering in a sphere of radius l (= 1: only tau = sigma * l matters).
// Row i holds tau = (first_row + i) * tau_step; each row is `photons_per_row` photons, one per
// invocation, each with at most `max_scatterings` scattering events. A photon that leaves the
// sphere adds its weight to the bin of cos(angle to d0) (bins uniform in [-1, 1]); one whose
// weight drops below `weight_threshold` after a scattering is dropped; one that would scatter a
// (max_scatterings + 1)-th time is cut and its weight is counted apart ("capped").
struct ScatterTableParams {
  uint32_t rows = 1000;
  uint32_t first_row = 0;
  uint32_t bins = 72;
  float tau_step = 0.01f;
  float g = 0.6f;       // Henyey-Greenstein anisotropy
  float albedo = 0.6f;  // weight factor per scattering
  float weight_threshold = 1e-4f;
  uint32_t photons_per_row = 4096;
  uint32_t max_scatterings = 1000;
  ScatterStart start = ScatterStart::surface;
  Vec3f direction{0, 0, 1};  // d0, unit length
  uint64_t seed = 1;
};
// Entries per table row: the bins, then the extras below. Table values are weight fractions of
// the row's photons; `hits` counts the photons per entry.
constexpr uint32_t kScatterCapped = 0;       // + bins: weight cut by max_scatterings
constexpr uint32_t kScatterThreshold = 1;    // + bins: weight dropped below weight_threshold
constexpr uint32_t kScatterUnscattered = 2;  // + bins: escaped with no scattering (also in a bin)
constexpr uint32_t kScatterExtras = 3;
constexpr uint64_t kScatterStream = 0x5CA7'0000'0000'0000ull;  // + row * photons_per_row + photon

// ---- nebula_illuminate, nebula_view -----------------------------------------------------------
enum class OpticalPath : uint32_t {
  exact = 0,     // voxel traversal: the exact integral of the piecewise-constant density grid
  midpoint = 1,  // fixed steps of step_a0, density at each step's midpoint (error O(step))
};

// Thesis Eq. 2.4-2.6 with the density grid of cloud_density: sigma_sct = kappa * density,
// extinction = sigma_sct / albedo (tau_opt = tau_sct / a), tau_sct of a cell = sigma_sct * l.
struct NebulaLightParams {
  GridParams grid;  // the density grid; grid.n = particles
  Vec3f nucleus{0, 0, 0};
  float source_power_lm = 250000.0f;  // Phi: light is linear in it
  float kappa_a2 = 1.0f;              // scattering cross-section per unit probability density
  float albedo = 0.6f;
  float core_radius_a0 = 0.05f;  // 1/r^2 is evaluated at max(r, core radius)
  Vec3f viewer{0, 0, 60};
  OpticalPath path = OpticalPath::exact;
  float step_a0 = 0.1f;  // midpoint path only
  // Geometry of the phase table (rows x bins, from make_phase_table() of a scatter_table).
  uint32_t table_rows = 1000;
  uint32_t table_bins = 72;
  float table_tau_step = 0.01f;
};
constexpr uint32_t kMaxPathSteps = 60000;  // lavapipe's loop limit, with margin

// ---- voxelize ---------------------------------------------------------------------------------
// Thesis §3.3.2 on an N^3 grid: p(i) = particles in cell i / particles (clamped into the grid, so
// sum p = 1), g(i) = mean over those particles of min(1, light * light_to_unit), and
// sample(i) = s * g(i) + t * p(i) / max_i p(i) (p normalised so that t weighs on [0, 1] too).
// Cells are the hash grid's (same fp32 rule); the outputs are stored x fastest, index
// (z * dims.y + y) * dims.x + x, like volume files, so raymarch reads them directly.
struct VoxelizeParams {
  GridParams grid;  // grid.n = particles
  float s = 0.7f;
  float t = 0.3f;
  float light_to_unit = 1.0f;
};

// ---- volume_bricks, raymarch ------------------------------------------------------------------
// A scalar volume: voxel (i, j, k) at index (k * dims.y + j) * dims.x + i (x fastest), its centre
// at box_min + (i + 0.5) * spacing, spacing = (box_max - box_min) / dims. Values map to the
// transfer function's [0, 1] by (v - value_min) / (value_max - value_min), clamped.
struct VolumeDesc {
  UVec3 dims{1, 1, 1};
  Vec3f box_min{0, 0, 0};
  Vec3f box_max{1, 1, 1};
  float value_min = 0.0f;
  float value_max = 1.0f;
};

// Empty-space skipping: per brick of brick^3 voxels (plus the one-voxel apron trilinear reads),
// the value range and the largest transfer-function alpha over it (0: the brick is empty).
struct VolumeBrickParams {
  VolumeDesc volume;
  uint32_t brick = 8;
  uint32_t tf_size = 256;
};

enum class Compositing : uint32_t {
  front_to_back = 0,  // emission-absorption, opacity corrected for the step, early termination
  lerp = 1,           // the thesis: acc = lerp(acc, (rgb, 1), alpha) from far to near, no correction
};

struct RaymarchParams {
  VolumeDesc volume;
  uint32_t width = 512;
  uint32_t height = 512;
  Vec3f eye{0, 0, 3};
  Vec3f target{0, 0, 0};
  Vec3f up{0, 1, 0};
  float fov_y_deg = 40.0f;
  float step = 0.01f;            // world units along the ray
  float reference_step = 0.01f;  // the step the transfer function's alpha is defined for
  float termination_alpha = 0.99f;  // early ray termination (front_to_back); 1 = never
  bool skip_empty = true;
  uint32_t brick = 8;
  uint32_t tf_size = 256;
  Compositing mode = Compositing::front_to_back;
};
constexpr uint32_t kMaxRaySteps = 60000;

// ---- checks Backend runs before any backend sees a call (engine/atom/atom_checks.cpp) --------
void validate(const DeviceApi& dev, const OrbitalSampleParams& p, const Buffer<uint32_t>& tables,
              const Buffer<Real4>& positions);
void validate(const DeviceApi& dev, const CloudDensityParams& p, const Buffer<uint32_t>& start,
              const Buffer<uint32_t>& end, const Buffer<Real>& density);
void validate(const DeviceApi& dev, const ScatterTableParams& p, const Buffer<Real>& table,
              const Buffer<uint32_t>& hits);
void validate(const DeviceApi& dev, const NebulaLightParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& density, const Buffer<Real>& illumination);
void validate(const DeviceApi& dev, const NebulaLightParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& density, const Buffer<Real>& table,
              const Buffer<Real>& illumination, const Buffer<Real>& light);
void validate(const DeviceApi& dev, const VoxelizeParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& light, const Buffer<Real>& probability,
              const Buffer<Real>& mean_light, const Buffer<Real>& sample);
void validate(const DeviceApi& dev, const VolumeBrickParams& p, const Buffer<Real>& volume,
              const Buffer<Real4>& tf, const Buffer<Real4>& bricks);
void validate(const DeviceApi& dev, const RaymarchParams& p, const Buffer<Real>& volume,
              const Buffer<Real4>& tf, const Buffer<Real4>& bricks, const Buffer<Real4>& image);
// Bricks of volume_bricks' output: its invocations.
uint64_t brick_count(const VolumeBrickParams& p);

}  // namespace masav
