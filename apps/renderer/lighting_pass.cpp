#include "renderer/lighting_pass.hpp"

#include <array>
#include <vector>

#include "penumbra/gpu/barriers.hpp"
#include "renderer/draw_recording.hpp"
#include "renderer/shader_interface.hpp"
#include "renderer_shaders.hpp"

namespace penumbra::renderer {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kVisibilityFormat = VK_FORMAT_R16_UNORM;
constexpr VkFormat kCascadeFormat = VK_FORMAT_R8_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

gpu::Image create_target(const gpu::Device& device, VkFormat format, uint32_t width, uint32_t height,
                         VkImageUsageFlags usage, VkImageAspectFlags aspect) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = width;
    desc.height = height;
    desc.usage = usage;
    desc.aspect = aspect;
    return gpu::create_image(device, desc);
}

// The ShadowSystem's specialization constants (ids from 0: lighting.frag leaves
// PENUMBRA_SPEC_ID_BASE at its default).
std::vector<gpu::SpecializationValue> shadow_specialization(const ShadowSystem& shadows) {
    const ShaderSpecialization specialization = shadows.shader_specialization(0);
    std::vector<gpu::SpecializationValue> values;
    for (size_t i = 0; i < specialization.entries.size(); ++i) {
        values.push_back({specialization.entries[i].constantID, specialization.data[i]});
    }
    return values;
}

gpu::UniquePipeline create_lighting_pipeline(const gpu::Device& device, VkPipelineLayout layout,
                                             VkCullModeFlags cull_mode, const ShadowSystem& shadows) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::lighting_vert(), {}});
    desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, shaders::lighting_frag(), shadow_specialization(shadows)});
    desc.vertex_layout = scene_vertex_layout();
    desc.layout = layout;
    desc.color_formats = {kColorFormat, kVisibilityFormat, kCascadeFormat};
    desc.depth_format = kDepthFormat;
    desc.depth_compare = VK_COMPARE_OP_GREATER;  // reverse-Z
    desc.cull_mode = cull_mode;
    return gpu::create_graphics_pipeline(device, desc);
}

}  // namespace

LightingPass::LightingPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                           VkDescriptorSetLayout material_set_layout, const ShadowSystem& shadows, uint32_t width,
                           uint32_t height)
    : device_(device), width_(width), height_(height) {
    const VkImageUsageFlags color_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    targets_.color = create_target(device, kColorFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.visibility =
        create_target(device, kVisibilityFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.cascade = create_target(device, kCascadeFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.depth = create_target(device, kDepthFormat, width, height, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                   VK_IMAGE_ASPECT_DEPTH_BIT);
    const VkDescriptorSetLayout set_layouts[] = {frame_set_layout, material_set_layout,
                                                 shadows.descriptor_set_layout()};
    const VkPushConstantRange push_range = draw_push_constant_range();
    pipeline_layout_ = gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
    single_sided_ = create_lighting_pipeline(device, pipeline_layout_, VK_CULL_MODE_BACK_BIT, shadows);
    double_sided_ = create_lighting_pipeline(device, pipeline_layout_, VK_CULL_MODE_NONE, shadows);
}

void LightingPass::begin_rendering(VkCommandBuffer cmd) const {
    const std::array<VkRenderingAttachmentInfo, 3> colors{
        cleared_color_attachment(targets_.color.view, {{0.52f, 0.62f, 0.75f, 1.0f}}),    // sky (linear; stored as sRGB)
        cleared_color_attachment(targets_.visibility.view, {{1.0f, 0.0f, 0.0f, 0.0f}}),  // no geometry = fully lit
        cleared_color_attachment(targets_.cascade.view, VkClearColorValue{.uint32 = {RENDERER_NO_CASCADE, 0, 0, 0}}),
    };
    begin_camera_rendering(device_, cmd, colors, targets_.depth.view, width_, height_);
}

void LightingPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, VkDescriptorSet shadow_set,
                          const DrawData& data) const {
    for (const gpu::Image* target : {&targets_.color, &targets_.visibility, &targets_.cascade}) {
        gpu::transition(device_, cmd, *target, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    }
    gpu::transition(device_, cmd, targets_.depth, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);

    begin_rendering(cmd);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, RENDERER_SET_FRAME, 1,
                                     &frame_set, 0, nullptr);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, RENDERER_SET_SHADOWS, 1,
                                     &shadow_set, 0, nullptr);
    record_camera_draws(device_, cmd, pipeline_layout_, data, single_sided_, double_sided_);
    device_->vkCmdEndRendering(cmd);

    for (const gpu::Image* target : {&targets_.color, &targets_.visibility, &targets_.cascade}) {
        gpu::transition(device_, cmd, *target, gpu::ImageState::ColorAttachment, gpu::ImageState::TransferSrc);
    }
}

}  // namespace penumbra::renderer
