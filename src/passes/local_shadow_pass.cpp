#include "passes/local_shadow_pass.hpp"

#include <algorithm>

#include "embedded_shaders.hpp"
#include "gpu/barriers.hpp"
#include "passes/draw_recording.hpp"
#include "passes/shader_interface.hpp"

namespace penumbra::passes {
namespace {

constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;

gpu::UniquePipeline create_local_shadow_pipeline(const gpu::Device& device, VkPipelineLayout layout, bool masked) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::local_shadow_depth_vert(), {}});
    if (masked) desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, shaders::shadow_masked_frag(), {}});
    desc.vertex_layout = scene_vertex_layout(VertexAttributes::PositionUv);
    desc.layout = layout;
    desc.depth_format = kShadowFormat;
    desc.depth_compare = VK_COMPARE_OP_GREATER;  // reverse-Z
    desc.cull_mode = VK_CULL_MODE_NONE;          // thin casters must cast (as for the cascades)
    desc.depth_bias = true;
    // No depth clamp: the near plane is the nearest caster's distance, and a perspective
    // frustum must clip what lies behind the light.
    desc.depth_clamp = false;
    return gpu::create_graphics_pipeline(device, desc);
}

}  // namespace

LocalShadowPass::LocalShadowPass(const gpu::Device& device, VkDescriptorSetLayout material_set_layout,
                                 uint32_t resolution, uint32_t layer_count)
    : device_(device), resolution_(resolution) {
    gpu::ImageDesc desc;
    desc.format = kShadowFormat;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = std::max(layer_count, 1u);
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    desc.array_view = true;
    shadow_map_ = gpu::create_image(device, desc);

    const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT,
                                               nullptr};
    set_layout_ = gpu::create_descriptor_set_layout(device, {&binding, 1});
    const VkDescriptorSetLayout set_layouts[] = {set_layout_, material_set_layout};
    const VkPushConstantRange push_range = draw_push_constant_range();
    pipeline_layout_ = gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
    opaque_ = create_local_shadow_pipeline(device, pipeline_layout_, false);
    masked_ = create_local_shadow_pipeline(device, pipeline_layout_, true);
}

void LocalShadowPass::record(VkCommandBuffer cmd, VkDescriptorSet set, const DrawData& data,
                             const std::vector<LocalShadowLayer>& layers, const BiasSettings& bias) const {
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, 0, 1, &set, 0, nullptr);
    VkDeviceSize offset = 0;
    device_->vkCmdBindVertexBuffers(cmd, 0, 1, &data.vertex_buffer, &offset);
    device_->vkCmdBindIndexBuffer(cmd, data.index_buffer, 0, VK_INDEX_TYPE_UINT32);
    std::vector<bool> rendered(shadow_map_.desc.layers, false);
    std::vector<LocalShadowLayer> all_layers = layers;
    for (const LocalShadowLayer& layer : layers) rendered[layer.layer] = true;
    // Layers nobody renders are still cleared, so that sampling them is defined.
    for (uint32_t layer = 0; layer < shadow_map_.desc.layers; ++layer) {
        if (!rendered[layer]) all_layers.push_back({layer, resolution_, {}});
    }
    for (const LocalShadowLayer& layer : all_layers) {
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = shadow_map_.layer_views[layer.layer];
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: nothing casts
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {resolution_, resolution_}};
        info.layerCount = 1;
        info.pDepthAttachment = &depth;
        device_->vkCmdBeginRendering(cmd, &info);
        set_viewport_and_scissor(device_, cmd, layer.resolution, layer.resolution);
        const float clamp = device_.depth_bias_clamp_supported() ? -bias.clamp : 0.0f;
        device_->vkCmdSetDepthBias(cmd, -bias.constant, clamp, -bias.slope);
        for (const bool masked_pass : {false, true}) {
            device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, masked_pass ? masked_ : opaque_);
            for (uint32_t index : layer.draws) {
                const Draw& draw = data.draws[index];
                if (data.materials[draw.material].alpha_masked != masked_pass) continue;
                record_draw(device_, cmd, pipeline_layout_, data, draw, layer.layer);
            }
        }
        device_->vkCmdEndRendering(cmd);
    }
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::DepthAttachment, gpu::ImageState::FragmentSampled);
}

void LocalShadowPass::record_placeholder(VkCommandBuffer cmd) const {
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::Undefined, gpu::ImageState::FragmentSampled);
}

}  // namespace penumbra::passes
