#include "app/demo/demo_window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

#include "app/demo/demo_layout.h"
#include "app/host_environment.h"
#include "engine/core/error.h"
#include "render/render_device.h"

namespace masav::app {
namespace {

constexpr const char* kHeadless =
    "render headless instead: masav run scene.toml --out DIR (or start the demo under "
    "xvfb-run)";

std::string glfw_error() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text ? text : "no description";
}

}  // namespace

DemoWindow::DemoWindow(uint32_t width, uint32_t height, const std::string& title) {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!x11 || !*x11) && (!wayland || !*wayland))
    throw Error("demo", "", "no display: DISPLAY is not set (no X server or Wayland session)",
                kHeadless);
  if (!glfwInit())
    throw Error("demo", "", fmt::format("the window system could not be opened ({})", glfw_error()),
                kHeadless);
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw Error("demo", "", "GLFW finds no Vulkan loader with window-system support",
                "install libvulkan1 and mesa-vulkan-drivers, or render headless with masav run");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  int wx = 0, wy = 0, ww = 0, wh = 0;
  if (GLFWmonitor* monitor = glfwGetPrimaryMonitor())
    glfwGetMonitorWorkarea(monitor, &wx, &wy, &ww, &wh);
  work_w_ = uint32_t(std::max(ww, 0));
  work_h_ = uint32_t(std::max(wh, 0));
  if (width == 0 || height == 0) fit_window(work_w_, work_h_, width, height);
  window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string why = glfw_error();
    glfwTerminate();
    throw Error("demo", "", fmt::format("the window could not be created ({})", why), kHeadless);
  }
  // Room for the panel and a scene viewport beside it.
  glfwSetWindowSizeLimits(window_, 480, 320, GLFW_DONT_CARE, GLFW_DONT_CARE);
  // Files dropped on the window wait here until the demo's loop takes them.
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
    static_cast<DemoWindow*>(glfwGetWindowUserPointer(w))->receive_drop(count, paths);
  });
}

void DemoWindow::receive_drop(int count, const char* const* paths) {
  for (int i = 0; i < count; ++i) dropped_.emplace_back(paths[i]);
}

std::vector<std::string> DemoWindow::take_dropped_files() {
  std::vector<std::string> out = std::move(dropped_);
  dropped_.clear();
  return out;
}

DemoWindow::~DemoWindow() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

vk::ContextOptions DemoWindow::graphics_options(const std::string& device) const {
  vk::ContextOptions o = render::graphics_options(vulkan_options(host_environment()), device);
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names)
    throw Error("demo", "", "GLFW reports no Vulkan surface extensions for this display",
                kHeadless);
  for (uint32_t i = 0; i < count; ++i) o.instance_extensions.push_back(names[i]);
  o.device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  o.present_support = [](VkInstance instance, VkPhysicalDevice pd, uint32_t family) {
    return glfwGetPhysicalDevicePresentationSupport(instance, pd, family) == GLFW_TRUE;
  };
  return o;
}

VkSurfaceKHR DemoWindow::create_surface(const vk::Context& ctx) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  const VkResult r =
      glfwCreateWindowSurface(static_cast<VkInstance>(*ctx.instance()), window_, nullptr, &surface);
  if (r != VK_SUCCESS)
    throw Error("demo", "",
                fmt::format("the window surface could not be created (VkResult {})", int(r)),
                kHeadless);
  return surface;
}

bool DemoWindow::should_close() const {
  return glfwWindowShouldClose(window_);
}

void DemoWindow::set_title(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}

void DemoWindow::framebuffer_size(uint32_t& width, uint32_t& height) const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  width = uint32_t(std::max(w, 0));
  height = uint32_t(std::max(h, 0));
}

}  // namespace masav::app
