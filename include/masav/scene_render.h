#pragma once
/// \file
/// Scene files rendered headless, frame by frame, as `masav run` renders them: the scene's
/// stages run on a compute backend (any: the CPU reference, Vulkan, CUDA) and are drawn
/// offscreen with Vulkan (a GPU, or lavapipe on the CPU). No window and no display are needed.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "masav/backends.h"
#include "masav/scene.h"

namespace masav {

/// One rendered frame: 8-bit RGBA, rows top first, as `masav run` writes its PNG frames.
struct Frame {
  uint32_t width = 0;         ///< pixels per row
  uint32_t height = 0;        ///< rows
  std::vector<uint8_t> rgba;  ///< width * height * 4 bytes
};

/// Writes `frame` as a PNG (to a temporary name, then renamed). Throws masav::Error naming the
/// path when it cannot be written, or the frame when its size and its bytes disagree.
void save_png(const std::string& path, const Frame& frame);

/// Where a SceneRenderer draws.
struct RenderOptions {
  /// The Vulkan device that draws when the compute backend is not Vulkan (the CPU reference,
  /// CUDA): an index or part of its name; empty: the best one. A Vulkan compute backend draws
  /// on its own device, so that its buffers are drawn where they lie.
  std::string device;
};

/// A scene played on a compute backend and drawn headless, frame by frame, as `masav run`
/// draws its frame_NNNNN.png: frame i shows the scene at run.start_time_s + i / run.fps, and
/// an SPH scene advances its simulation by one frame's steps each frame.
class SceneRenderer {
 public:
  /// Opens the compute backend `compute` and a Vulkan device to draw with, and builds the scene.
  /// Throws masav::Error when the backend cannot be opened, when no Vulkan device can draw (the
  /// message says what to install), or when the scene's render parameters contradict each other.
  explicit SceneRenderer(scene::SceneFile scene, const BackendOptions& compute = {},
                         const RenderOptions& render = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;             ///< one renderer per device context
  SceneRenderer& operator=(const SceneRenderer&) = delete;  ///< one renderer per device context

  /// Every kernel the scene runs, on its compute backend against the scene's verify.reference:
  /// the cross-check `masav run` runs before it renders.
  verify::CrossCheckReport verify();

  /// Brings the scene's stages up to date for the next frame, draws it and reads it back.
  Frame next_frame();
  /// How many frames next_frame() has drawn (the index of the next one).
  uint64_t frames_drawn() const;

  uint32_t width() const;                  ///< the frame width the scene asks for (render.width)
  uint32_t height() const;                 ///< the frame height (render.height)
  std::string backend_name() const;        ///< the compute backend: cpu, vulkan or cuda
  std::string compute_device_name() const; ///< the compute backend's device
  std::string render_device_name() const;  ///< the Vulkan device that draws
  /// True when the compute backend's buffers are drawn where they are (the same Vulkan device),
  /// false when each frame copies them to the render device.
  bool shares_device() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace masav
