#pragma once
// ImGui controls generated from a scene table's schema: a checkbox for a flag, a slider (in
// steps, or logarithmic, when the schema says so) for numbers, a combo for choices. Every
// parameter a domain declares gets its control with no demo code of its own.
#include <string>

#include "engine/scene/param_schema.h"

namespace masav::app {

// Draws the control for `path`; on an edit stores the new value in `out` and returns true.
bool param_widget(const scene::ParamSpec& spec, const std::string& path,
                  const scene::ParamValue& current, scene::ParamValue& out);

}  // namespace masav::app
