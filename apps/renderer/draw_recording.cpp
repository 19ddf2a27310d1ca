#include "renderer/draw_recording.hpp"

#include <cstddef>
#include <cstdint>

#include "penumbra/scene/scene.hpp"

namespace penumbra::renderer {

gpu::Image create_camera_target(const gpu::Device& device, VkFormat format, uint32_t width, uint32_t height,
                                VkImageUsageFlags usage, VkImageAspectFlags aspect) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = width;
    desc.height = height;
    desc.usage = usage;
    desc.aspect = aspect;
    return gpu::create_image(device, desc);
}

gpu::VertexLayout scene_vertex_layout(VertexColors colors) {
    gpu::VertexLayout layout;
    layout.stride = sizeof(Vertex);
    layout.attributes.push_back({0, 0, VK_FORMAT_R32G32B32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, position))});
    layout.attributes.push_back({1, 0, VK_FORMAT_R32G32B32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, normal))});
    layout.attributes.push_back({2, 0, VK_FORMAT_R32G32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, uv))});
    if (colors == VertexColors::Read) {
        layout.attributes.push_back({3, 0, VK_FORMAT_R8G8B8A8_UNORM, static_cast<uint32_t>(offsetof(Vertex, color))});
    }
    return layout;
}

shader::DrawPushConstants draw_push_constants(const Draw& draw, const MaterialBinding& material) {
    shader::DrawPushConstants constants{};
    constants.base_color = material.base_color;
    constants.material = {material.alpha_cutoff, material.roughness, material.metallic, 0.0f};
    constants.emissive = glm::vec4(material.emissive, material.occlusion_strength);
    constants.flags = {material.has_emissive_texture ? 1u : 0u, material.has_texture ? 1u : 0u,
                       material.alpha_masked ? RENDERER_ALPHA_MASK : RENDERER_ALPHA_OPAQUE,
                       draw.receive_shadows ? 1u : 0u};
    return constants;
}

void set_viewport_and_scissor(const gpu::Device& device, VkCommandBuffer cmd, uint32_t width, uint32_t height) {
    const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {width, height}};
    device->vkCmdSetViewport(cmd, 0, 1, &viewport);
    device->vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void record_batch(const gpu::Device& device, VkCommandBuffer cmd, VkPipelineLayout layout, const DrawData& data,
                  const DrawBatch& batch, bool bind_material) {
    const Draw& draw = data.draws[batch.draw];
    const MaterialBinding& material = data.materials[draw.material];
    if (bind_material) {
        device->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, RENDERER_SET_MATERIAL, 1,
                                        &material.descriptor_set, 0, nullptr);
    }
    const shader::DrawPushConstants constants = draw_push_constants(draw, material);
    device->vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(constants), &constants);
    device->vkCmdDrawIndexed(cmd, draw.index_count, batch.count, draw.first_index, draw.vertex_offset,
                             batch.first_instance);
}

VkRenderingAttachmentInfo cleared_color_attachment(VkImageView view, VkClearColorValue clear) {
    VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    attachment.imageView = view;
    attachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.clearValue.color = clear;
    return attachment;
}

VkRenderingAttachmentInfo cleared_depth_attachment(VkImageView view, VkAttachmentStoreOp store) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = store;
    depth.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: the far plane
    return depth;
}

VkRenderingAttachmentInfo read_only_depth_attachment(VkImageView view) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_NONE;  // nothing written, nothing to store
    return depth;
}

void begin_camera_rendering(const gpu::Device& device, VkCommandBuffer cmd,
                            std::span<const VkRenderingAttachmentInfo> colors, const VkRenderingAttachmentInfo& depth,
                            uint32_t width, uint32_t height) {
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {width, height}};
    info.layerCount = 1;
    info.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    info.pColorAttachments = colors.data();
    info.pDepthAttachment = &depth;
    device->vkCmdBeginRendering(cmd, &info);
    set_viewport_and_scissor(device, cmd, width, height);
}

void record_camera_draws(const gpu::Device& device, VkCommandBuffer cmd, VkPipelineLayout layout, const DrawData& data,
                         VkPipeline single_sided, VkPipeline double_sided) {
    VkDeviceSize offset = 0;
    device->vkCmdBindVertexBuffers(cmd, 0, 1, &data.vertex_buffer, &offset);
    device->vkCmdBindIndexBuffer(cmd, data.index_buffer, 0, VK_INDEX_TYPE_UINT32);
    for (const bool double_sided_pass : {false, true}) {
        device->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                  double_sided_pass ? double_sided : single_sided);
        uint32_t bound_material = UINT32_MAX;  // a pipeline change keeps the set (same layout)
        for (const DrawBatch& batch : data.batches[double_sided_pass ? 1 : 0]) {
            const uint32_t material = data.draws[batch.draw].material;
            record_batch(device, cmd, layout, data, batch, material != bound_material);
            bound_material = material;
        }
    }
}

VkPushConstantRange draw_push_constant_range() {
    return {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(shader::DrawPushConstants)};
}

}  // namespace penumbra::renderer
