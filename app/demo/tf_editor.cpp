#include "app/demo/tf_editor.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cstring>

#include "app/demo/tooltip.h"
#include "engine/core/error.h"
#include "engine/volume/value_histogram.h"

namespace masav::app {
namespace {

constexpr uint32_t kHistogramBins = 128;
constexpr float kCanvasHeight = 120;
constexpr float kPickRadius = 7;  // px: a click this close to a point picks it

ImU32 colour_of(const TransferPoint& p, double alpha) {
  return ImGui::ColorConvertFloat4ToU32(
      ImVec4(float(p.r), float(p.g), float(p.b), float(std::clamp(alpha, 0.0, 1.0))));
}

void report(TfEditorState& e, std::string text, bool error) {
  e.message = std::move(text);
  e.message_is_error = error;
}

// Stores the edited points in the scene; a refusal stays in the editor's message.
void apply(render::ScenePlayer& player, TfEditorState& e, const std::string& table) {
  try {
    apply_tf_points(player.scene(), table, e.points);
    e.keys.clear();  // read back from the key: the editor shows what the scene renders
  } catch (const Error& err) {
    report(e, err.what(), true);
  }
}

// The histogram, recomputed only when the volume changed (a download of the whole volume).
void refresh_histogram(render::ScenePlayer& player, TfEditorState& e) {
  const uint64_t version = player.scene().volume_version();
  if (version == e.histogram_version) return;
  e.histogram_version = version;
  e.histogram = volume::log_heights(player.scene().value_histogram(kHistogramBins));
}

// The canvas: histogram, opacity curve and points; returns whether the points changed.
bool point_canvas(TfEditorState& e) {
  const float width = std::max(ImGui::GetContentRegionAvail().x, 64.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##tf canvas", ImVec2(width, kCanvasHeight),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 end(origin.x + width, origin.y + kCanvasHeight);
  draw->AddRectFilled(origin, end, IM_COL32(20, 20, 24, 255));
  const size_t bins = e.histogram.size();
  for (size_t i = 0; i < bins; ++i) {
    const float x0 = origin.x + width * float(i) / float(bins);
    const float x1 = origin.x + width * float(i + 1) / float(bins);
    draw->AddRectFilled(ImVec2(x0, end.y - kCanvasHeight * e.histogram[i]), ImVec2(x1, end.y),
                        IM_COL32(90, 90, 100, 255));
  }
  auto at = [&](const TransferPoint& p) {
    return ImVec2(origin.x + width * float(p.value), end.y - kCanvasHeight * float(p.a));
  };
  for (size_t i = 0; i + 1 < e.points.size(); ++i)
    draw->AddLine(at(e.points[i]), at(e.points[i + 1]), IM_COL32(230, 230, 230, 255), 1.5f);
  for (size_t i = 0; i < e.points.size(); ++i) {
    draw->AddCircleFilled(at(e.points[i]), 5, colour_of(e.points[i], 1.0));
    const bool selected = e.selected && *e.selected == i;
    draw->AddCircle(at(e.points[i]), selected ? 7.0f : 5.0f,
                    selected ? IM_COL32(255, 255, 0, 255) : IM_COL32(255, 255, 255, 255), 0,
                    selected ? 2.0f : 1.0f);
  }
  draw->AddRect(origin, end, IM_COL32(120, 120, 130, 255));

  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const double value = (mouse.x - origin.x) / width;
  const double opacity = (end.y - mouse.y) / kCanvasHeight;
  std::optional<size_t> under;
  for (size_t i = 0; i < e.points.size(); ++i) {
    const ImVec2 p = at(e.points[i]);
    const float dx = p.x - mouse.x, dy = p.y - mouse.y;
    if (dx * dx + dy * dy <= kPickRadius * kPickRadius) under = i;
  }
  bool changed = false;
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    if (!under) {
      under = add_tf_point(e.points, value);
      if (under) {
        move_tf_point(e.points, *under, e.points[*under].value, opacity);
        changed = true;
      }
    }
    e.selected = e.dragging = under;
  }
  if (e.dragging && ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
      (ImGui::GetIO().MouseDelta.x != 0 || ImGui::GetIO().MouseDelta.y != 0)) {
    move_tf_point(e.points, *e.dragging, value, opacity);
    changed = true;
  }
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) e.dragging.reset();
  if (hovered && under && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
    if (delete_tf_point(e.points, *under)) {
      e.selected.reset();
      changed = true;
    } else {
      report(e, fmt::format("a transfer function keeps at least {} points", kMinTfPoints), true);
    }
  }
  if (hovered && tooltip_due())
    ImGui::SetTooltip(
        "value %.3f, opacity %.3f\nclick: add a point, drag: move it, right click: "
        "delete it",
        std::clamp(value, 0.0, 1.0), std::clamp(opacity, 0.0, 1.0));
  return changed;
}

// The resampled function as the raymarch reads it: colour above, colour times opacity below.
void preview_strip(const std::vector<TransferPoint>& points) {
  const std::vector<Vec4d> tf = volume::resample_transfer(points);
  const float width = std::max(ImGui::GetContentRegionAvail().x, 64.0f);
  const float height = 24;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::Dummy(ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (size_t k = 0; k < tf.size(); ++k) {
    const float x0 = origin.x + width * float(k) / float(tf.size());
    const float x1 = origin.x + width * float(k + 1) / float(tf.size());
    const Vec4d& c = tf[k];
    draw->AddRectFilled(
        ImVec2(x0, origin.y), ImVec2(x1 + 1, origin.y + height / 2),
        ImGui::ColorConvertFloat4ToU32(ImVec4(float(c.x), float(c.y), float(c.z), 1.0f)));
    draw->AddRectFilled(ImVec2(x0, origin.y + height / 2), ImVec2(x1 + 1, origin.y + height),
                        ImGui::ColorConvertFloat4ToU32(
                            ImVec4(float(c.x * c.w), float(c.y * c.w), float(c.z * c.w), 1.0f)));
  }
}

bool path_field(std::string& value) {
  std::array<char, 1024> buf{};
  std::strncpy(buf.data(), value.c_str(), buf.size() - 1);
  const bool edited = ImGui::InputText("file##tf", buf.data(), buf.size());
  value = buf.data();
  return edited;
}

}  // namespace

void tf_editor(render::ScenePlayer& player, DemoState& st) {
  const std::optional<std::string> table = transfer_table(player.scene().params());
  if (!table) return;
  if (!ImGui::CollapsingHeader("transfer function", ImGuiTreeNodeFlags_DefaultOpen)) return;
  TfEditorState& e = st.tf;
  sync_tf_editor(e, player.scene().params(), *table);
  refresh_histogram(player, e);
  ImGui::PushID("tf editor");
  bool changed = point_canvas(e);
  preview_strip(e.points);
  if (e.selected && *e.selected < e.points.size()) {
    TransferPoint& p = e.points[*e.selected];
    float rgba[4] = {float(p.r), float(p.g), float(p.b), float(p.a)};
    ImGui::Text("point %zu of %zu, value %.3f", *e.selected + 1, e.points.size(), p.value);
    if (ImGui::ColorEdit4("colour, opacity##tf", rgba, ImGuiColorEditFlags_Float)) {
      set_tf_colour(e.points, *e.selected, rgba[0], rgba[1], rgba[2], rgba[3]);
      changed = true;
    }
    if (ImGui::Button("Delete point")) {
      if (delete_tf_point(e.points, *e.selected)) {
        e.selected.reset();
        changed = true;
      } else {
        report(e, fmt::format("a transfer function keeps at least {} points", kMinTfPoints), true);
      }
    }
  } else {
    ImGui::TextDisabled("click a point to edit its colour and opacity");
  }
  if (changed) apply(player, e, *table);
  path_field(e.path);
  if (ImGui::Button("Save TF...")) save_tf_file(e, e.path);
  ImGui::SameLine();
  if (ImGui::Button("Load TF...")) load_tf_file(e, player.scene(), *table, e.path);
  ImGui::SameLine();
  if (ImGui::Button("Reset TF")) {
    try {
      reset_tf_points(player.scene(), *table);
      e.keys.clear();
      e.selected.reset();
      report(e, "the default transfer function", false);
    } catch (const Error& err) {
      report(e, err.what(), true);
    }
  }
  if (!e.message.empty()) {
    if (e.message_is_error) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.4f, 0.3f, 1));
    ImGui::TextWrapped("%s", e.message.c_str());
    if (e.message_is_error) ImGui::PopStyleColor();
  }
  ImGui::PopID();
}

}  // namespace masav::app
