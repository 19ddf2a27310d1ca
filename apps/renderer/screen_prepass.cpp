#include "renderer/screen_prepass.hpp"

#include "penumbra/gpu/barriers.hpp"
#include "renderer/draw_recording.hpp"
#include "renderer/math_conversions.hpp"
#include "renderer/shader_interface.hpp"
#include "renderer_shaders.hpp"

namespace penumbra::renderer {
namespace {

constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

gpu::UniquePipeline create_pipeline(const gpu::Device& device, VkPipelineLayout layout, VkCullModeFlags cull_mode) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::lighting_vert(), {}});
    desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, shaders::screen_prepass_frag(), {}});
    desc.vertex_layout = scene_vertex_layout(VertexColors::Skipped);
    desc.layout = layout;
    desc.color_formats = {kNormalFormat};
    desc.depth_format = kDepthFormat;
    desc.depth_compare = VK_COMPARE_OP_GREATER;  // reverse-Z, as the forward lighting pass
    desc.cull_mode = cull_mode;
    return gpu::create_graphics_pipeline(device, desc);
}

}  // namespace

ScreenPrepass::ScreenPrepass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                             VkDescriptorSetLayout material_set_layout, uint32_t width, uint32_t height)
    : device_(device), width_(width), height_(height) {
    targets_.normals = create_camera_target(device, kNormalFormat, width, height,
                                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                            VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.depth = create_camera_target(device, kDepthFormat, width, height,
                                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                          VK_IMAGE_ASPECT_DEPTH_BIT);
    const VkDescriptorSetLayout set_layouts[] = {frame_set_layout, material_set_layout};
    const VkPushConstantRange push_range = draw_push_constant_range();
    pipeline_layout_ = gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
    single_sided_ = create_pipeline(device, pipeline_layout_, VK_CULL_MODE_BACK_BIT);
    double_sided_ = create_pipeline(device, pipeline_layout_, VK_CULL_MODE_NONE);
}

void ScreenPrepass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data) const {
    // The previous frame's reads (resolve and lighting) finished before this submission:
    // render() waits for every frame.
    gpu::transition(device_, cmd, targets_.normals, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    gpu::transition(device_, cmd, targets_.depth, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);

    // Pixels without geometry keep the clear value: the resolve does not read them.
    const VkRenderingAttachmentInfo normals =
        cleared_color_attachment(targets_.normals.view, {{0.0f, 0.0f, 0.0f, 0.0f}});
    // Stored: the resolve reads it and the lighting pass tests against it.
    begin_camera_rendering(device_, cmd, {&normals, 1},
                           cleared_depth_attachment(targets_.depth.view, VK_ATTACHMENT_STORE_OP_STORE), width_,
                           height_);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, RENDERER_SET_FRAME, 1,
                                     &frame_set, 0, nullptr);
    record_camera_draws(device_, cmd, pipeline_layout_, data, single_sided_, double_sided_);
    device_->vkCmdEndRendering(cmd);

    gpu::transition(device_, cmd, targets_.normals, gpu::ImageState::ColorAttachment, gpu::ImageState::ShaderSampled);
    gpu::transition(device_, cmd, targets_.depth, gpu::ImageState::DepthAttachment, gpu::ImageState::DepthReadOnly);
}

ScreenInputs ScreenPrepass::screen_inputs(const glm::mat4& view_projection) const {
    ScreenInputs screen;
    screen.depth = targets_.depth.view;
    screen.depth_layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    screen.normals = targets_.normals.view;
    screen.normals_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    screen.normal_encoding = NormalEncoding::Octahedral;
    screen.face_normals = targets_.normals.view;  // its zw
    screen.face_normals_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    screen.width = width_;
    screen.height = height_;
    screen.view_projection = to_mat4(view_projection);
    screen.background_depth = 0.0f;  // reverse-Z far
    return screen;
}

}  // namespace penumbra::renderer
