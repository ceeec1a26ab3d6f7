#pragma once
// A Dear ImGui context for one renderer: the demo's panel and the text overlay (which headless
// frames draw too) both go through it. ImGui's own font (ProggyClean) is built in, so nothing is
// loaded from disk.
#include <cstdint>
#include <vector>

struct ImGuiContext;

namespace masav::render {

class UiContext {
 public:
  explicit UiContext(float scale = 1.0f);
  ~UiContext();
  UiContext(const UiContext&) = delete;
  UiContext& operator=(const UiContext&) = delete;

  // Makes this context current (ImGui has one current context per thread).
  void make_current() const;
  uint32_t atlas_width() const { return atlas_w_; }
  uint32_t atlas_height() const { return atlas_h_; }
  const std::vector<uint32_t>& atlas() const { return atlas_; }  // RGBA8 texels

 private:
  ImGuiContext* ctx_ = nullptr;
  std::vector<uint32_t> atlas_;
  uint32_t atlas_w_ = 0, atlas_h_ = 0;
};

}  // namespace masav::render
