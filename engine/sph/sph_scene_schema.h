#pragma once
// The [sph] table of a scene file (scene type `sph`) and its translation into an SphScene.
// The preset (thesis Figures 4.10-4.13, the dam break) fixes the geometry and the thesis's fluid
// constants; the table scales or overrides them. Everything but the colouring and the substeps
// per frame changes the simulation itself, so changing it restarts the simulation from the
// preset's initial state (the help of each key says so).
#include <string>
#include <string_view>

#include "engine/scene/param_schema.h"
#include "engine/sph/sph_params.h"

namespace masav::sph {

const scene::TableSchema& sph_table();

// The preset of a scene-file choice ("dambreak" -> make_preset's "dam-break").
std::string preset_name(std::string_view choice);

// The SphScene the parameters describe (validated; throws masav::Error naming the sph.* key).
SphScene scene_from_params(const scene::ParamSet& p);

// Keys whose change restarts the simulation (every [sph] key but these two).
bool restarts_simulation(std::string_view key);

}  // namespace masav::sph
