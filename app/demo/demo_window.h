#pragma once
// The demo's window (GLFW, no OpenGL context): the display check, the Vulkan instance
// extensions and presentation support GLFW reports, and the window surface.
#include <string>

#include "compute/device/vk_context.h"

struct GLFWwindow;

namespace masav::app {

class DemoWindow {
 public:
  // Throws masav::Error when there is no display (naming `masav run` as the headless way).
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

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace masav::app
