#pragma once
// The tables every scene file has besides its domain's: [scene], [render], [camera], [run],
// [verify].
#include "engine/scene/param_schema.h"

namespace masav::scene {

const TableSchema& scene_table();
const TableSchema& render_table();
const TableSchema& camera_table();
const TableSchema& run_table();
const TableSchema& verify_table();
std::vector<const TableSchema*> common_tables();

}  // namespace masav::scene
