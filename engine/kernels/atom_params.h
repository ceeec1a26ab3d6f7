// Parameters of the electron-cloud, nebula-lighting and volume kernels (orbital_sample,
// cloud_density, scatter_table, nebula_illuminate, nebula_view, voxelize, volume_bricks,
// raymarch) and of their passes. Shared by C++, CUDA and GLSL (engine/core/layout.h). Lengths
// are in Bohr radii (a0) unless a name says otherwise.
#ifndef MASAV_KERNELS_ATOM_PARAMS_H
#define MASAV_KERNELS_ATOM_PARAMS_H
#include "engine/core/layout.h"
#include "engine/kernels/grid_params.h"

MASAV_NAMESPACE_BEGIN

// ---- orbital_sample ---------------------------------------------------------------------------
MASAV_ENUM_BEGIN(OrbitalPlacement)
// inverse-CDF tables of the separable factors of |psi|^2 (engine/atom/orbital_tables.h)
MASAV_ENUMERATOR(OrbitalPlacement, exact, 0)
// the thesis's shell placement (Algorithm 2.1): sites on shells, stratified jitter
MASAV_ENUMERATOR(OrbitalPlacement, shells, 1)
MASAV_ENUM_END(OrbitalPlacement)

// Cumulative tables live in one uint32 buffer: `exact` holds three CDFs scaled to 2^24 (radial
// over r in [0, radial_max_a0], polar over cos(theta) in [-1, 1], azimuthal over psi in [0, pi)),
// one after the other, each with bins + 1 entries; `shells` holds the cumulative particle count
// over sites (radial_bins * polar_bins * azimuth_bins sites, one table). Build them with
// make_orbital_tables(); the kernel only inverts them.
MASAV_LAYOUT(OrbitalSampleParams) {
  uint count MASAV_INIT(0u);  // particles drawn into positions[0..count)
  MASAV_ENUM(OrbitalPlacement) placement MASAV_INIT(OrbitalPlacement::exact);
  MASAV_U64 seed MASAV_INIT(0);  // Philox key; particle i uses block i of stream kOrbitalStream
  uint radial_bins MASAV_INIT(0u);
  uint polar_bins MASAV_INIT(0u);
  uint azimuth_bins MASAV_INIT(0u);       // exact: 0 = phi uniform (complex orbitals and m = 0)
  uint azimuth_periods MASAV_INIT(1u);    // real orbitals: cos^2(|m| phi): 2|m| periods in 2 pi
  float radial_max_a0 MASAV_INIT(0.0f);   // outer edge of the radial table (or outermost shell)
  float azimuth_offset MASAV_INIT(0.0f);  // pi/2 turns cos^2 into sin^2 (real orbitals, m < 0)
};
MASAV_CONSTANT64(kOrbitalStream, 0x0A700000, 0x00000001)
MASAV_CONSTANT(kCdfOne, 16777216)  // exact tables: CDF values are integers out of 2^24

// ---- cloud density ----------------------------------------------------------------------------
// density[c] = (cell_end[c] - cell_start[c]) / (particles * cell_size^3): probability per a0^3 of
// each hash-grid cell (points outside the grid are clamped into its boundary cells, so the
// densities sum to 1 / cell volume).
MASAV_LAYOUT(CloudDensityParams) {
  GridParams grid;
  uint particles MASAV_INIT(0u);
};

// ---- scatter_table ----------------------------------------------------------------------------
MASAV_ENUM_BEGIN(ScatterStart)
MASAV_ENUMERATOR(ScatterStart, surface, 0)  // X0 = C - l * d0, heading along d0 (thesis §2.2.3)
MASAV_ENUMERATOR(ScatterStart, centre, 1)   // X0 = C
MASAV_ENUM_END(ScatterStart)

// Monte Carlo multiple scattering in a sphere of radius l (= 1: only tau = sigma * l matters).
// Row i holds tau = (first_row + i) * tau_step; each row is `photons_per_row` photons, one per
// invocation, each with at most `max_scatterings` scattering events. A photon that leaves the
// sphere adds its weight to the bin of cos(angle to d0) (bins uniform in [-1, 1]); one whose
// weight drops below `weight_threshold` after a scattering is dropped; one that would scatter a
// (max_scatterings + 1)-th time is cut and its weight is counted apart ("capped").
MASAV_LAYOUT(ScatterTableParams) {
  uint rows MASAV_INIT(1000u);
  uint first_row MASAV_INIT(0u);
  uint bins MASAV_INIT(72u);
  uint photons_per_row MASAV_INIT(4096u);
  MASAV_U64 seed MASAV_INIT(1);
  uint max_scatterings MASAV_INIT(1000u);
  MASAV_ENUM(ScatterStart) start MASAV_INIT(ScatterStart::surface);
  vec3 direction MASAV_INIT(vec3(0, 0, 1));  // d0, unit length
  float tau_step MASAV_INIT(0.01f);
  float g MASAV_INIT(0.6f);       // Henyey-Greenstein anisotropy
  float albedo MASAV_INIT(0.6f);  // weight factor per scattering
  float weight_threshold MASAV_INIT(1e-4f);
};
// Entries per table row: the bins, then the extras below. Table values are weight fractions of
// the row's photons; `hits` counts the photons per entry.
MASAV_CONSTANT(kScatterCapped, 0)       // + bins: weight cut by max_scatterings
MASAV_CONSTANT(kScatterThreshold, 1)    // + bins: weight dropped below weight_threshold
MASAV_CONSTANT(kScatterUnscattered, 2)  // + bins: escaped with no scattering (also in a bin)
MASAV_CONSTANT(kScatterExtras, 3)
// Photon ph of row r draws from stream kScatterStream + (first_row + r) * photons_per_row + ph.
MASAV_CONSTANT64(kScatterStream, 0x5CA70000, 0x00000000)

// scatter_table's last pass on the GPU backends: table[e] = fixed-point tally[e] * scale.
MASAV_LAYOUT(ScatterFinalizeParams) {
  uint entries;
  float scale;  // 1 / (2^kFixedShift * photons_per_row)
};

// ---- nebula_illuminate, nebula_view -----------------------------------------------------------
MASAV_ENUM_BEGIN(OpticalPath)
// voxel traversal: the exact integral of the piecewise-constant density grid
MASAV_ENUMERATOR(OpticalPath, exact, 0)
// fixed steps of step_a0, density at each step's midpoint (error O(step))
MASAV_ENUMERATOR(OpticalPath, midpoint, 1)
MASAV_ENUM_END(OpticalPath)

// Thesis Eq. 2.4-2.6 with the density grid of cloud_density: sigma_sct = kappa * density,
// extinction = sigma_sct / albedo (tau_opt = tau_sct / a), tau_sct of a cell = sigma_sct * l.
MASAV_LAYOUT(NebulaLightParams) {
  GridParams grid;  // the density grid; grid.n = particles
  vec3 nucleus MASAV_INIT(vec3(0, 0, 0));
  float source_power_lm MASAV_INIT(250000.0f);  // Phi: light is linear in it
  vec3 viewer MASAV_INIT(vec3(0, 0, 60));
  float kappa_a2 MASAV_INIT(1.0f);  // scattering cross-section per unit probability density
  float albedo MASAV_INIT(0.6f);
  float core_radius_a0 MASAV_INIT(0.05f);  // 1/r^2 is evaluated at max(r, core radius)
  float step_a0 MASAV_INIT(0.1f);          // midpoint path only
  MASAV_ENUM(OpticalPath) path MASAV_INIT(OpticalPath::exact);
  // Geometry of the phase table (rows x bins, from make_phase_table() of a scatter_table).
  uint table_rows MASAV_INIT(1000u);
  uint table_bins MASAV_INIT(72u);
  float table_tau_step MASAV_INIT(0.01f);
};
// The most steps a midpoint path takes: within the portable loop budget (kPortableLoopBudget),
// with room for the invocation's other loops.
MASAV_CONSTANT(kMaxPathSteps, 60000)

// ---- voxelize ---------------------------------------------------------------------------------
// Thesis §3.3.2 on an N^3 grid: p(i) = particles in cell i / particles (clamped into the grid, so
// sum p = 1), g(i) = mean over those particles of min(1, light * light_to_unit), and
// sample(i) = s * g(i) + t * p(i) / max_i p(i) (p normalised so that t weighs on [0, 1] too).
// Cells are the hash grid's (same fp32 rule); the outputs are stored x fastest, index
// (z * dims.y + y) * dims.x + x, like volume files, so raymarch reads them directly. The GPU
// backends run two passes on these parameters (accumulate per particle, finalize per cell).
MASAV_LAYOUT(VoxelizeParams) {
  GridParams grid;  // grid.n = particles
  float s MASAV_INIT(0.7f);
  float t MASAV_INIT(0.3f);
  float light_to_unit MASAV_INIT(1.0f);
};

// ---- volume_bricks, raymarch ------------------------------------------------------------------
// A scalar volume: voxel (i, j, k) at index (k * dims.y + j) * dims.x + i (x fastest), its centre
// at box_min + (i + 0.5) * spacing, spacing = (box_max - box_min) / dims. Values map to the
// transfer function's [0, 1] by (v - value_min) / (value_max - value_min), clamped.
MASAV_LAYOUT(VolumeDesc) {
  uvec3 dims MASAV_INIT(uvec3(1, 1, 1));
  float value_min MASAV_INIT(0.0f);
  vec3 box_min MASAV_INIT(vec3(0, 0, 0));
  float value_max MASAV_INIT(1.0f);
  vec3 box_max MASAV_INIT(vec3(1, 1, 1));
};

// Empty-space skipping: per brick of brick^3 voxels (plus the one-voxel apron trilinear reads),
// the value range and the largest transfer-function alpha over it (0: the brick is empty).
MASAV_LAYOUT(VolumeBrickParams) {
  VolumeDesc volume;
  uint brick MASAV_INIT(8u);
  uint tf_size MASAV_INIT(256u);
};

// The stride a ray crosses bricks in: per brick, the Chebyshev distance in bricks (at least 1) to
// the nearest brick of the other kind (occupied: alpha > 0; or empty), so that every brick within
// distance - 1 of it is of its kind and a ray crosses that cube of bricks with one lookup.
// Distances beyond `radius` read radius + 1. The max-norm distance transform is separable: pass
// (axis) 0 reads the bricks' alpha along x, 1 the first pass's distances along y, 2 the second's
// along z and writes the distance to bricks[].w (volume_bricks writes 1 there: one brick).
MASAV_LAYOUT(BrickSkipParams) {
  uvec3 bricks MASAV_INIT(uvec3(1, 1, 1));  // bricks per axis
  uint axis MASAV_INIT(0u);                 // the pass: 0, 1, 2
  uint radius MASAV_INIT(16u);              // the farthest distance looked for, 1 .. 255
};
MASAV_CONSTANT(kBrickSkipMaxRadius, 255)

MASAV_ENUM_BEGIN(Compositing)
// emission-absorption, opacity corrected for the step, early termination
MASAV_ENUMERATOR(Compositing, front_to_back, 0)
// the thesis: acc = lerp(acc, (rgb, 1), alpha) from far to near, no correction
MASAV_ENUMERATOR(Compositing, lerp, 1)
MASAV_ENUM_END(Compositing)

// What raymarch reads: RaymarchParams with the camera as a ray basis (computed once, in fp32, by
// device_params): the ray through pixel (x, y) heads along forward + nx right + ny up, with
// nx, ny in [-1, 1] from left to right and bottom to top. Vulkan gives a push block 128 bytes, so
// small integers share words (volume::ray_width and its neighbours unpack them).
MASAV_LAYOUT(RaymarchLayout) {
  vec3 eye;
  float step;
  vec3 forward;
  float reference_step;
  vec3 right;  // scaled by tan(fov/2) * aspect
  float termination_alpha;
  vec3 up;  // scaled by tan(fov/2)
  float value_min;
  vec3 box_min;
  float value_scale;  // 1 / (value_max - value_min)
  vec3 box_max;
  float clip_position;  // the clipping plane's world coordinate on its axis (kRayClip)
  uvec3 dims;
  uint image_size;  // width | height << 16
  // kRay* flags | clip axis << kRayClipAxisShift | brick << kRayBrickShift
  // | tf_size << kRayTfSizeShift
  uint bits;
  uint shade_ambient_diffuse;  // ambient | diffuse << 16, each unorm16 (kRayShade)
  uint shade_specular;         // specular | shininess / kRayMaxShininess << 16, each unorm16
  uint shade_light;            // the direction towards a fixed light, octahedral snorm16 x 2
};
MASAV_CONSTANT(kRaySkipEmpty, 1)
// The segment's colour and opacity from the pre-integrated table (volume::segment_mean) rather
// than the transfer function at its midpoint.
MASAV_CONSTANT(kRayPreintegrate, 2)
// Compositing::lerp (else front_to_back).
MASAV_CONSTANT(kRayLerp, 4)
// Keep only the part of the volume on one side of an axis-aligned plane (volume::clip_span).
MASAV_CONSTANT(kRayClip, 8)
// The clip keeps coordinates at or above clip_position (else at or below).
MASAV_CONSTANT(kRayClipKeepAbove, 16)
// Blinn-Phong shading from the volume's gradient (volume::shade_at).
MASAV_CONSTANT(kRayShade, 32)
// The light sits at the camera (else it shines from shade_light).
MASAV_CONSTANT(kRayHeadlight, 64)
// The flags that choose a raymarch's code paths (the rest are values it reads).
MASAV_CONSTANT(kRayModeFlags, kRaySkipEmpty | kRayPreintegrate | kRayLerp | kRayClip | kRayShade)
MASAV_CONSTANT(kRayClipAxisShift, 8)  // 2 bits: 0 x, 1 y, 2 z
MASAV_CONSTANT(kRayBrickShift, 10)    // 5 bits: 2 .. 16
MASAV_CONSTANT(kRayTfSizeShift, 16)   // 13 bits: 2 .. 4096
MASAV_CONSTANT(kRayMaxShininess, 256)
// Which of volume::pow_step's forms the opacity correction's exponent step / reference_step takes
// (volume::pow_step_form): a Vulkan raymarch is specialised on it, so that lavapipe, which runs
// every branch of a sample, computes one form per sample instead of all five.
MASAV_CONSTANT(kRayPowGeneral, 0)  // pow(x, e)
MASAV_CONSTANT(kRayPowOne, 1)      // e = 1: x
MASAV_CONSTANT(kRayPowHalf, 2)     // e = 1/2: sqrt(x)
MASAV_CONSTANT(kRayPowQuarter, 3)  // e = 1/4: sqrt(sqrt(x))
MASAV_CONSTANT(kRayPowTwo, 4)      // e = 2: x * x
// The pre-integrated table holds this many Real4 per transfer-function entry
// (volume::segment_mean describes them).
MASAV_CONSTANT(kPreintegratedPerEntry, 3)
// The most loop iterations a ray may take (samples and skipped bricks), within the portable loop
// budget (kPortableLoopBudget).
MASAV_CONSTANT(kMaxRaySteps, 60000)

MASAV_NAMESPACE_END

#ifdef __cplusplus
#include "engine/core/buffer.h"

namespace masav {

MASAV_LAYOUT_CHECK(OrbitalSampleParams, 48, (count, 0), (placement, 4), (seed, 8),
                   (radial_bins, 16), (polar_bins, 20), (azimuth_bins, 24), (azimuth_periods, 28),
                   (radial_max_a0, 32), (azimuth_offset, 36))
MASAV_LAYOUT_CHECK(CloudDensityParams, 64, (grid, 0), (particles, 48))
MASAV_LAYOUT_CHECK(ScatterTableParams, 64, (rows, 0), (first_row, 4), (bins, 8),
                   (photons_per_row, 12), (seed, 16), (max_scatterings, 24), (start, 28),
                   (direction, 32), (tau_step, 44), (g, 48), (albedo, 52), (weight_threshold, 56))
MASAV_LAYOUT_CHECK(ScatterFinalizeParams, 16, (entries, 0), (scale, 4))
MASAV_LAYOUT_CHECK(NebulaLightParams, 112, (grid, 0), (nucleus, 48), (source_power_lm, 60),
                   (viewer, 64), (kappa_a2, 76), (albedo, 80), (core_radius_a0, 84), (step_a0, 88),
                   (path, 92), (table_rows, 96), (table_bins, 100), (table_tau_step, 104))
MASAV_LAYOUT_CHECK(VoxelizeParams, 64, (grid, 0), (s, 48), (t, 52), (light_to_unit, 56))
MASAV_LAYOUT_CHECK(VolumeDesc, 48, (dims, 0), (value_min, 12), (box_min, 16), (value_max, 28),
                   (box_max, 32))
MASAV_LAYOUT_CHECK(VolumeBrickParams, 64, (volume, 0), (brick, 48), (tf_size, 52))
MASAV_LAYOUT_CHECK(BrickSkipParams, 32, (bricks, 0), (axis, 12), (radius, 16))
MASAV_LAYOUT_CHECK(RaymarchLayout, 128, (eye, 0), (step, 12), (forward, 16), (reference_step, 28),
                   (right, 32), (termination_alpha, 44), (up, 48), (value_min, 60), (box_min, 64),
                   (value_scale, 76), (box_max, 80), (clip_position, 92), (dims, 96),
                   (image_size, 108), (bits, 112), (shade_ambient_diffuse, 116),
                   (shade_specular, 120), (shade_light, 124))

// A volume's description in the order one says it: dims, box, value range.
inline VolumeDesc make_volume_desc(UVec3 dims, Vec3f box_min, Vec3f box_max, float value_min = 0,
                                   float value_max = 1) {
  VolumeDesc d;
  d.dims = dims;
  d.box_min = box_min;
  d.box_max = box_max;
  d.value_min = value_min;
  d.value_max = value_max;
  return d;
}

// A view of a volume: the camera, the image and the ray-casting knobs.
struct RaymarchParams {
  VolumeDesc volume;
  uint32_t width = 512;
  uint32_t height = 512;
  Vec3f eye{0, 0, 3};
  Vec3f target{0, 0, 0};
  Vec3f up{0, 1, 0};
  float fov_y_deg = 40.0f;
  float step = 0.01f;               // world units along the ray
  float reference_step = 0.01f;     // the step the transfer function's alpha is defined for
  float termination_alpha = 0.99f;  // early ray termination (front_to_back); 1 = never
  bool skip_empty = true;
  // Each segment's colour and opacity integrated over the scalar's linear change along it, from
  // the table of volume::segment_mean (the raymarch's tf_integral, front_to_back only): a larger
  // step keeps its accuracy.
  bool preintegrate = false;
  uint32_t brick = 2;  // voxels per empty-space brick: fine bricks skip the most samples
  uint32_t tf_size = 256;
  Compositing mode = Compositing::front_to_back;
  // An axis-aligned plane through the volume; samples on the removed side contribute nothing.
  struct Clip {
    bool enabled = false;
    uint32_t axis = 0;      // 0 x, 1 y, 2 z
    float position = 0.5f;  // fraction of the box's extent on that axis, [0, 1]
    bool keep_above = true;
  } clip;
  // Blinn-Phong shading with the normal from the volume's gradient (central differences of the
  // trilinear field): colour * (ambient + diffuse |n.l|) + specular (n.h)^shininess. Stored as
  // 16-bit fractions (ambient, diffuse, specular in [0, 1], shininess in [1, kRayMaxShininess]).
  struct Shading {
    bool enabled = false;
    bool headlight = true;     // the light at the camera; else from light_dir
    Vec3f light_dir{1, 1, 1};  // towards the light (normalised on upload)
    float ambient = 0.3f;
    float diffuse = 0.7f;
    float specular = 0.3f;
    float shininess = 24.0f;
  } shading;
};

// The ray basis and derived constants every backend's raymarch reads (fp32, computed once;
// engine/kernels/atom_checks.cpp).
RaymarchLayout raymarch_layout(const RaymarchParams& p);
template <class F, class... Buffers>
RaymarchLayout device_params(const RaymarchParams& p, const Buffers&...) {
  return raymarch_layout(p);
}

class DeviceApi;
// ---- checks Backend runs before any backend sees a call (engine/kernels/atom_checks.cpp) --------
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
void validate(const DeviceApi& dev, const BrickSkipParams& p, const Buffer<Real4>& bricks,
              const Buffer<uint32_t>& distances);
void validate(const DeviceApi& dev, const RaymarchParams& p, const Buffer<Real>& volume,
              const Buffer<Real4>& tf, const Buffer<Real4>& bricks, const Buffer<Real4>& image,
              const Buffer<Real4>* tf_integral);
// Bricks of volume_bricks' output: its invocations.
uint64_t brick_count(const VolumeBrickParams& p);
// Bricks of volume_brick_skip's grid: its invocations.
uint64_t brick_count(const BrickSkipParams& p);
// The raymarch's invocations: the image padded to whole 8x8 tiles (volume::tile_pixel).
uint64_t raymarch_invocations(const RaymarchParams& p);

}  // namespace masav
#endif
#endif
