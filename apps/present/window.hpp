#pragma once
// A desktop window for Vulkan presentation (GLFW on X11), as a move-less RAII owner, and
// the window surface. The window is created before the device because the instance needs
// the window system's surface extensions (add_presentation()).
//
//   present::Window window({"penumbra", 1280, 720});
//   VulkanContextOptions options;
//   window.add_presentation(options);
//   renderer::AppContext context(options);
//   present::Surface surface(context, window);
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

#include "penumbra/device.hpp"
#include "penumbra/gpu/device.hpp"

struct GLFWwindow;

namespace penumbra::present {

struct WindowOptions {
    std::string title = "penumbra";
    uint32_t width = 1280;  // framebuffer size asked for; the window system may differ
    uint32_t height = 720;
};

class Window {
public:
    // Throws penumbra::DeviceError (one line) when no window system is available (e.g.
    // DISPLAY unset) or the Vulkan loader offers no surface support.
    explicit Window(const WindowOptions& options);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return window_; }
    // Adds the instance extensions for surfaces and a queue-family presentation check.
    void add_presentation(VulkanContextOptions& options) const;

    VkExtent2D framebuffer_size() const;  // {0, 0} while minimised
    bool should_close() const;
    void request_close();
    void resize(uint32_t width, uint32_t height);
    void poll_events();
    void wait_events();  // blocks until an event arrives (used while minimised)

private:
    GLFWwindow* window_ = nullptr;
};

class Surface {
public:
    Surface(const gpu::Device& context, const Window& window);
    ~Surface();
    Surface(const Surface&) = delete;
    Surface& operator=(const Surface&) = delete;
    VkSurfaceKHR get() const { return surface_; }

private:
    VkInstance instance_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

}  // namespace penumbra::present
