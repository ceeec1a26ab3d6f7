#include "app/demo/volume_open.h"

#include <imgui.h>

#include <array>
#include <cstring>
#include <filesystem>

#include "app/demo/tooltip.h"
#include "engine/core/error.h"

namespace masav::app {
namespace {

// An ImGui text field over a std::string (the packaged Dear ImGui has no std::string overload).
bool text_field(const char* label, std::string& value, ImGuiInputTextFlags flags = 0) {
  std::array<char, 1024> buf{};
  std::strncpy(buf.data(), value.c_str(), buf.size() - 1);
  const bool entered = ImGui::InputText(label, buf.data(), buf.size(), flags);
  value = buf.data();
  return entered;
}

}  // namespace

scene::SceneFile volume_scene_file(const OpenFields& f) {
  scene::SceneFile s = scene::default_scene("volume");
  // Not a scene file (the panel offers none beside it): the file's name in brackets.
  s.source = "<" + std::filesystem::path(f.path).filename().string() + ">";
  s.params.set("source.path", f.path);
  s.params.set("source.dims", f.dims);
  s.params.set("source.type", f.type);
  s.params.set("source.spacing", f.spacing);
  s.params.set("source.big_endian", f.big_endian);
  s.params.set("source.array", f.array);
  return s;
}

OpenFields open_fields_from_words(const std::vector<std::string>& words, const std::string& where) {
  OpenFields f;
  if (words.empty()) throw_invalid(where, "open", "no path", "open PATH [dims=X,Y,Z] ...");
  f.path = words[0];
  for (size_t i = 1; i < words.size(); ++i) {
    const std::string& w = words[i];
    const size_t eq = w.find('=');
    const std::string key = w.substr(0, eq),
                      value = eq == std::string::npos ? "" : w.substr(eq + 1);
    if (key == "big_endian" && eq == std::string::npos)
      f.big_endian = true;
    else if (key == "dims" && eq != std::string::npos)
      f.dims = value;
    else if (key == "type" && eq != std::string::npos)
      f.type = value;
    else if (key == "spacing" && eq != std::string::npos)
      f.spacing = value;
    else if (key == "array" && eq != std::string::npos)
      f.array = value;
    else
      throw_invalid(where, "open", w,
                    "dims=X,Y,Z, type=T, spacing=X,Y,Z, big_endian or array=NAME");
  }
  return f;
}

void volume_open_controls(OpenFields& fields, bool& request) {
  if (!ImGui::CollapsingHeader("open a volume file")) return;
  const bool entered = text_field("path", fields.path, ImGuiInputTextFlags_EnterReturnsTrue);
  if (tooltip_due())
    ImGui::SetTooltip(
        ".nrrd/.nhdr, .vti, or raw (any other name: give dims and type); or drop "
        "a file on the window");
  text_field("dims (raw)", fields.dims);
  if (tooltip_due()) ImGui::SetTooltip("X,Y,Z, each in [2, 8192]");
  text_field("type (raw)", fields.type);
  if (tooltip_due())
    ImGui::SetTooltip("uint8, int8, uint16, int16, uint32, int32, float32, float64");
  text_field("spacing (raw)", fields.spacing);
  if (tooltip_due()) ImGui::SetTooltip("voxel size X,Y,Z (empty: 1,1,1)");
  ImGui::Checkbox("big-endian (raw)", &fields.big_endian);
  text_field("array (vti)", fields.array);
  if (tooltip_due()) ImGui::SetTooltip("the array of a .vti file to read (empty: the first)");
  if (ImGui::Button("Open") || entered) request = true;
}

}  // namespace masav::app
