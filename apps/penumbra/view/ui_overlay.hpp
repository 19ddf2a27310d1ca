#pragma once
// Dear ImGui on the viewer's window: the GLFW platform backend and the Vulkan renderer
// backend (Debian's libimgui-dev 1.86). That backend draws inside a VkRenderPass (it
// predates dynamic rendering), so the overlay owns a one-subpass render pass that loads
// the swapchain image in COLOR_ATTACHMENT_OPTIMAL and keeps it there (the barriers
// around it are gpu::transition's), and one framebuffer per swapchain image.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "penumbra/gpu/handle.hpp"
#include "present/presenter.hpp"
#include "present/window.hpp"
#include "renderer/app_context.hpp"

namespace penumbra::view {

class UiOverlay {
public:
    UiOverlay(const renderer::AppContext& context, const present::Window& window, const present::Presenter& presenter);
    ~UiOverlay();
    UiOverlay(const UiOverlay&) = delete;
    UiOverlay& operator=(const UiOverlay&) = delete;

    void begin_frame();  // starts an ImGui frame (after the window's events were polled)
    void end_frame();    // finishes it (ImGui::Render); call once per begin_frame()
    // Draws the finished frame over `frame.image`, which must be in ImageState::ColorAttachment.
    void record(VkCommandBuffer cmd, const present::Frame& frame);

private:
    void rebuild_framebuffers();

    const renderer::AppContext& context_;
    const present::Presenter& presenter_;
    gpu::UniqueDescriptorPool pool_;
    gpu::UniqueRenderPass render_pass_;
    std::vector<gpu::UniqueFramebuffer> framebuffers_;
    uint64_t framebuffer_generation_ = 0;
    VkFormat format_;
};

}  // namespace penumbra::view
