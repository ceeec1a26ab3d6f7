#include "render/ui_context.h"

#include <imgui.h>

#include <cstring>

namespace masav::render {

UiContext::UiContext(float scale) {
  ctx_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(ctx_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini written next to the user's files
  io.LogFilename = nullptr;
  io.FontGlobalScale = scale;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().ScaleAllSizes(scale);
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  atlas_w_ = uint32_t(w);
  atlas_h_ = uint32_t(h);
  atlas_.resize(size_t(w) * size_t(h));
  std::memcpy(atlas_.data(), pixels, atlas_.size() * 4);
  io.Fonts->SetTexID(ImTextureID(1));
}

UiContext::~UiContext() {
  ImGui::DestroyContext(ctx_);
}

void UiContext::make_current() const {
  ImGui::SetCurrentContext(ctx_);
}

}  // namespace masav::render
