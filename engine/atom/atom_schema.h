#pragma once
// The parameters of the electron-cloud scenes (`atom` and `atom-volume`), declared once: the
// cloud [atom], its nebula lighting [nebula], the scattering table [scatter] and, for
// atom-volume, the voxelized volume and its raymarch [volume]. Defaults are the thesis's
// (§2.2-§2.5, §3.3) unless a comment says otherwise.
#include "engine/atom/atom_scene.h"
#include "engine/scene/param_schema.h"

namespace masav::atom {

const scene::TableSchema& atom_table();
const scene::TableSchema& nebula_table();
const scene::TableSchema& scatter_table_schema();
const scene::TableSchema& volume_table();

// The hydrogen state the parameters select: atom.state = state1 .. state10 (thesis Table 2.1)
// or custom (atom.n, atom.l, atom.m); atom.orbital = complex or real. Throws masav::Error naming
// atom.n / atom.l / atom.m when the custom state is not a valid one.
OrbitalState state_of(const scene::ParamSet& p);
ScatterTableParams scatter_params_of(const scene::ParamSet& p);
// The scattering table traces rows x photons paths of up to max_scatterings events each: the
// product is bounded (kMaxScatterPaths) before any work, the message naming `photons_field` and
// the most photons per row that fit with these rows.
inline constexpr uint64_t kMaxScatterPaths = uint64_t(1) << 30;
void check_scatter_cost(const ScatterTableParams& t, std::string_view photons_field);
// The options of the shared atom pipeline (atom_scene.h) at the reference power: the scene
// graph computes the light once at kReferencePowerLm and rescales it for atom.power_lm.
AtomSceneOptions scene_options_of(const scene::ParamSet& p);

}  // namespace masav::atom
