#include "ui_overlay.hpp"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <array>

#include "penumbra/gpu/check.hpp"

namespace penumbra::view {
namespace {

void check_imgui_result(VkResult result) {
    if (result < 0) ::penumbra::gpu::throw_vk_failure("an ImGui Vulkan backend call", result, __FILE__, __LINE__);
}

gpu::UniqueRenderPass create_render_pass(const gpu::Device& device, VkFormat format) {
    VkAttachmentDescription attachment{};
    attachment.format = format;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the scene is already there
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    // Explicit external dependencies that match the surrounding gpu::transition barriers
    // (which do the actual synchronisation), instead of the implicit ones.
    std::array<VkSubpassDependency, 2> dependencies{};
    dependencies[0] = {VK_SUBPASS_EXTERNAL,
                       0,
                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                       0};
    dependencies[1] = {0,
                       VK_SUBPASS_EXTERNAL,
                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                       0};
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &attachment;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = static_cast<uint32_t>(dependencies.size());
    info.pDependencies = dependencies.data();
    VkRenderPass render_pass = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateRenderPass(device, &info, nullptr, &render_pass));
    return {device, render_pass};
}

gpu::UniqueDescriptorPool create_font_pool(const gpu::Device& device) {
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    info.maxSets = 1;
    info.poolSizeCount = 1;
    info.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateDescriptorPool(device, &info, nullptr, &pool));
    return {device, pool};
}

}  // namespace

UiOverlay::UiOverlay(const renderer::AppContext& context, const present::Window& window,
                     const present::Presenter& presenter)
    : context_(context), presenter_(presenter), format_(presenter.swapchain().format()) {
    pool_ = create_font_pool(context);
    render_pass_ = create_render_pass(context, format_);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini left in the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window.handle(), true);

    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context.instance();
    info.PhysicalDevice = context.physical_device();
    info.Device = context.device();
    info.QueueFamily = context.queue_family();
    info.Queue = context.queue();
    info.DescriptorPool = pool_;
    info.MinImageCount = 2;
    info.ImageCount = 2;  // vertex buffers per frame; one frame is ever in flight
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = check_imgui_result;
    ImGui_ImplVulkan_Init(&info, render_pass_);
    context.submit_and_wait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

UiOverlay::~UiOverlay() {
    vkDeviceWaitIdle(context_.device());
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void UiOverlay::begin_frame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void UiOverlay::end_frame() { ImGui::Render(); }

void UiOverlay::rebuild_framebuffers() {
    const present::Swapchain& swapchain = presenter_.swapchain();
    if (swapchain.format() != format_) {
        throw VulkanError("the recreated swapchain changed its format", VK_ERROR_FORMAT_NOT_SUPPORTED);
    }
    framebuffers_.clear();
    for (const gpu::UniqueImageView& view : swapchain.views()) {
        const VkImageView attachment = view.get();
        VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        info.renderPass = render_pass_;
        info.attachmentCount = 1;
        info.pAttachments = &attachment;
        info.width = swapchain.extent().width;
        info.height = swapchain.extent().height;
        info.layers = 1;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        PENUMBRA_VK_CHECK(vkCreateFramebuffer(context_.device(), &info, nullptr, &framebuffer));
        framebuffers_.emplace_back(context_, framebuffer);
    }
    framebuffer_generation_ = presenter_.generation();
}

void UiOverlay::record(VkCommandBuffer cmd, const present::Frame& frame) {
    if (framebuffers_.empty() || framebuffer_generation_ != presenter_.generation()) rebuild_framebuffers();
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = render_pass_;
    begin.framebuffer = framebuffers_[frame.image_index];
    begin.renderArea.extent = frame.extent;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

}  // namespace penumbra::view
