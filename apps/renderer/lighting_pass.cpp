#include "renderer/lighting_pass.hpp"

#include <array>
#include <stdexcept>
#include <utility>
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

std::span<const uint32_t> lighting_fragment_shader(bool deferred, bool contact) {
    if (deferred) return contact ? shaders::lighting_deferred_contact_frag() : shaders::lighting_deferred_frag();
    return contact ? shaders::lighting_contact_frag() : shaders::lighting_frag();
}

gpu::UniquePipeline create_lighting_pipeline(const gpu::Device& device, VkPipelineLayout layout,
                                             VkCullModeFlags cull_mode, const ShadowSystem& shadows,
                                             ShadowResolve resolve, bool contact) {
    const bool deferred = resolve == ShadowResolve::Deferred;
    const bool over_prepass = deferred || contact;
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::lighting_color_vert(), {}});
    desc.stages.push_back(
        {VK_SHADER_STAGE_FRAGMENT_BIT, lighting_fragment_shader(deferred, contact), shadow_specialization(shadows)});
    desc.vertex_layout = scene_vertex_layout(VertexColors::Read);
    desc.layout = layout;
    desc.color_formats = {kColorFormat, kVisibilityFormat, kCascadeFormat};
    desc.depth_format = kDepthFormat;
    // Over the pre-pass: only the surface it kept at each pixel is shaded, once.
    desc.depth_compare = over_prepass ? VK_COMPARE_OP_EQUAL : VK_COMPARE_OP_GREATER;  // reverse-Z
    desc.depth_write = !over_prepass;
    desc.cull_mode = cull_mode;
    return gpu::create_graphics_pipeline(device, desc);
}

// Set 3: the resolve's visibility image (deferred) and the pre-pass's depth (contact).
gpu::UniqueDescriptorSetLayout create_screen_set_layout(const gpu::Device& device, bool deferred, bool contact) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (const auto& [used, binding] : {std::pair{deferred, uint32_t{RENDERER_BINDING_SHADOW_VISIBILITY}},
                                        std::pair{contact, uint32_t{RENDERER_BINDING_CONTACT_DEPTH}}}) {
        if (used) {
            bindings.push_back(
                {binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
        }
    }
    return gpu::create_descriptor_set_layout(device, bindings);
}

}  // namespace

LightingPass::LightingPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                           VkDescriptorSetLayout material_set_layout, const ShadowSystem& shadows, uint32_t width,
                           uint32_t height, ShadowResolve resolve, bool contact_shadows,
                           const gpu::Image* prepass_depth)
    : device_(device), width_(width), height_(height), resolve_(resolve) {
    const bool deferred = resolve == ShadowResolve::Deferred;
    const bool over_prepass = deferred || contact_shadows;
    prepass_depth_ = over_prepass ? prepass_depth : nullptr;
    if (over_prepass && prepass_depth == nullptr) {
        throw std::invalid_argument("LightingPass: the deferred resolve and contact shadows need the pre-pass's depth");
    }
    const VkImageUsageFlags color_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    targets_.color = create_camera_target(device, kColorFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.visibility =
        create_camera_target(device, kVisibilityFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.cascade =
        create_camera_target(device, kCascadeFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    std::vector<VkDescriptorSetLayout> set_layouts{frame_set_layout, material_set_layout,
                                                   shadows.descriptor_set_layout()};
    if (over_prepass) {
        screen_set_layout_ = create_screen_set_layout(device, deferred, contact_shadows);
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2};
        screen_pool_ = gpu::create_descriptor_pool(device, 1, {&size, 1});
        screen_set_ = gpu::allocate_descriptor_set(device, screen_pool_, screen_set_layout_);
        gpu::SamplerDesc sampler;
        sampler.filter = VK_FILTER_NEAREST;
        sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        nearest_ = gpu::create_sampler(device, sampler);
        set_layouts.push_back(screen_set_layout_);
    }
    if (contact_shadows) {
        // Read-only depth attachment and sampled at once (ScreenPrepass leaves it so).
        gpu::write_combined_image_sampler(device, screen_set_, RENDERER_BINDING_CONTACT_DEPTH, prepass_depth->view,
                                          nearest_, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    }
    if (prepass_depth_ == nullptr) {
        targets_.depth = create_camera_target(device, kDepthFormat, width, height,
                                              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    }
    const VkPushConstantRange push_range = draw_push_constant_range();
    pipeline_layout_ = gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
    contact_shadows_ = contact_shadows;
    respecialize(shadows);
}

void LightingPass::respecialize(const ShadowSystem& shadows) {
    single_sided_ =
        create_lighting_pipeline(device_, pipeline_layout_, VK_CULL_MODE_BACK_BIT, shadows, resolve_, contact_shadows_);
    double_sided_ =
        create_lighting_pipeline(device_, pipeline_layout_, VK_CULL_MODE_NONE, shadows, resolve_, contact_shadows_);
}

void LightingPass::use_visibility_image(const VisibilityImage& visibility) {
    if (resolve_ != ShadowResolve::Deferred || visibility.view == visibility_view_) return;
    gpu::write_combined_image_sampler(device_, screen_set_, RENDERER_BINDING_SHADOW_VISIBILITY, visibility.view,
                                      nearest_);
    visibility_view_ = visibility.view;
}

void LightingPass::begin_rendering(VkCommandBuffer cmd) const {
    const std::array<VkRenderingAttachmentInfo, 3> colors{
        cleared_color_attachment(targets_.color.view, {{0.52f, 0.62f, 0.75f, 1.0f}}),    // sky (linear; stored as sRGB)
        cleared_color_attachment(targets_.visibility.view, {{1.0f, 0.0f, 0.0f, 0.0f}}),  // no geometry = fully lit
        cleared_color_attachment(targets_.cascade.view, VkClearColorValue{.uint32 = {RENDERER_NO_CASCADE, 0, 0, 0}}),
    };
    const VkRenderingAttachmentInfo depth =
        prepass_depth_ == nullptr ? cleared_depth_attachment(targets_.depth.view, VK_ATTACHMENT_STORE_OP_DONT_CARE)
                                  : read_only_depth_attachment(prepass_depth_->view);
    begin_camera_rendering(device_, cmd, colors, depth, width_, height_);
}

void LightingPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, VkDescriptorSet shadow_set,
                          const DrawData& data) const {
    for (const gpu::Image* target : {&targets_.color, &targets_.visibility, &targets_.cascade}) {
        gpu::transition(device_, cmd, *target, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    }
    if (prepass_depth_ == nullptr) {
        gpu::transition(device_, cmd, targets_.depth, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);
    }

    begin_rendering(cmd);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, RENDERER_SET_FRAME, 1,
                                     &frame_set, 0, nullptr);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, RENDERER_SET_SHADOWS, 1,
                                     &shadow_set, 0, nullptr);
    if (screen_set_ != VK_NULL_HANDLE) {
        device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, RENDERER_SET_SCREEN, 1,
                                         &screen_set_, 0, nullptr);
    }
    record_camera_draws(device_, cmd, pipeline_layout_, data, single_sided_, double_sided_);
    device_->vkCmdEndRendering(cmd);

    for (const gpu::Image* target : {&targets_.color, &targets_.visibility, &targets_.cascade}) {
        gpu::transition(device_, cmd, *target, gpu::ImageState::ColorAttachment, gpu::ImageState::TransferSrc);
    }
}

}  // namespace penumbra::renderer
