#include "present/window.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>

#include "penumbra/errors.hpp"
#include "penumbra/gpu/check.hpp"

namespace penumbra::present {
namespace {

// GLFW reports errors through a callback; keep the last one for a one-line message
// instead of letting GLFW print to stderr.
std::string& last_glfw_error() {
    static std::string message;
    return message;
}

void on_glfw_error(int /*code*/, const char* description) { last_glfw_error() = description ? description : ""; }

std::string glfw_failure(const std::string& what) {
    const std::string& detail = last_glfw_error();
    return what + (detail.empty() ? "" : " (" + detail + ")");
}

}  // namespace

Window::Window(const WindowOptions& options) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        throw DeviceError(glfw_failure("no window system available: glfwInit failed") +
                          "; run under X11 (set DISPLAY, e.g. with xvfb-run) or use `penumbra render`");
    }
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw DeviceError(glfw_failure("the Vulkan loader offers no window surface support"));
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window_ = glfwCreateWindow(static_cast<int>(options.width), static_cast<int>(options.height), options.title.c_str(),
                               nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw DeviceError(glfw_failure("cannot create a window"));
    }
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

void Window::add_presentation(VulkanContextOptions& options) const {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    for (uint32_t i = 0; i < count; ++i) options.presentation_extensions.emplace_back(names[i]);
    options.can_present = [](VkInstance instance, VkPhysicalDevice device, uint32_t family) {
        return glfwGetPhysicalDevicePresentationSupport(instance, device, family) == GLFW_TRUE;
    };
}

VkExtent2D Window::framebuffer_size() const {
    int width = 0;
    int height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) return {0, 0};
    return {static_cast<uint32_t>(std::max(width, 0)), static_cast<uint32_t>(std::max(height, 0))};
}

bool Window::should_close() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

void Window::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void Window::resize(uint32_t width, uint32_t height) {
    glfwSetWindowSize(window_, static_cast<int>(width), static_cast<int>(height));
}

void Window::poll_events() { glfwPollEvents(); }

void Window::wait_events() { glfwWaitEventsTimeout(0.1); }

Surface::Surface(const gpu::Device& context, const Window& window) : instance_(context.instance()) {
    PENUMBRA_VK_CHECK(glfwCreateWindowSurface(instance_, window.handle(), nullptr, &surface_));
}

Surface::~Surface() {
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
}

}  // namespace penumbra::present
