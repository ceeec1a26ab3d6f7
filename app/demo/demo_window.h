#pragma once
// The demo's window (GLFW, no OpenGL context): the display check, the Vulkan instance
// extensions and presentation support GLFW reports, and the window surface.
#include <string>
#include <vector>

#include "compute/device/vk_context.h"

struct GLFWwindow;

namespace masav::app {

class DemoWindow {
 public:
  // Throws masav::Error when there is no display (naming `masav run` as the headless way).
  // A size of 0x0 fits the window to the primary monitor's work area (see fit_window).
  DemoWindow(uint32_t width, uint32_t height, const std::string& title);
  ~DemoWindow();
  DemoWindow(const DemoWindow&) = delete;
  DemoWindow& operator=(const DemoWindow&) = delete;

  GLFWwindow* handle() const { return window_; }
  // Render-context options with GLFW's surface extensions, the swapchain extension and
  // GLFW's presentation check.
  vk::ContextOptions graphics_options(const std::string& device) const;
  VkSurfaceKHR create_surface(const vk::Context& ctx) const;
  bool should_close() const;
  void set_title(const std::string& title);
  void framebuffer_size(uint32_t& width, uint32_t& height) const;
  // The primary monitor's work area (the screen less task bars) when the window was opened.
  uint32_t work_width() const { return work_w_; }
  uint32_t work_height() const { return work_h_; }
  // Files dropped on the window: GLFW's drop callback calls this, and so does the script's
  // `drop` (Xvfb cannot drop), so both take the same way in.
  void receive_drop(int count, const char* const* paths);
  // The files dropped on the window since the last call, oldest first.
  std::vector<std::string> take_dropped_files();

 private:
  GLFWwindow* window_ = nullptr;
  uint32_t work_w_ = 0, work_h_ = 0;
  std::vector<std::string> dropped_;
};

}  // namespace masav::app
