#include "passes/local_shadow_pass.hpp"

#include <algorithm>

#include "passes/shader_interface.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

CasterPipelineTemplate local_template(VkPipelineLayout layout, bool gpu_culling) {
    CasterPipelineTemplate pipelines;
    pipelines.opaque_vertex = gpu_culling ? shaders::caster_local_gpu_vert() : shaders::caster_local_vert();
    pipelines.masked_vertex =
        gpu_culling ? shaders::caster_local_gpu_masked_vert() : shaders::caster_local_masked_vert();
    pipelines.masked_fragment = shaders::caster_masked_frag();
    pipelines.layout = layout;
    pipelines.depth_bias = true;
    // No depth clamp: the near plane is the nearest caster's distance, and a perspective
    // frustum must clip what lies behind the light.
    pipelines.depth_clamp = false;
    return pipelines;
}

}  // namespace

LocalShadowPass::LocalShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                                 VkDescriptorSetLayout alpha_mask_set_layout, bool gpu_culling,
                                 uint32_t frames_in_flight)
    : device_(device),
      gpu_culling_(create_gpu_culling(device, gpu_culling, frame_set_layout, frames_in_flight)),
      pipeline_layout_(
          create_caster_pipeline_layout(device, frame_set_layout, alpha_mask_set_layout, gpu_culling_.get())),
      pipelines_(device, local_template(pipeline_layout_, gpu_culling)) {}

void LocalShadowPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                             const std::vector<LocalShadowLayer>& layers, const gpu::Image& map,
                             const BiasSettings& bias, CasterCulling culling, bool cull, uint64_t frame) {
    const uint32_t resolution = map.desc.width;
    const bool keep = std::any_of(layers.begin(), layers.end(), [](const LocalShadowLayer& l) { return l.keep; });
    std::vector<LocalShadowLayer> all_layers;
    for (const LocalShadowLayer& layer : layers) {
        if (!layer.keep) all_layers.push_back(layer);
    }
    if (!keep) {
        // Layers nobody renders are still cleared, so that sampling them is defined.
        std::vector<bool> rendered(map.desc.layers, false);
        for (const LocalShadowLayer& layer : layers) rendered[layer.layer] = true;
        for (uint32_t layer = 0; layer < map.desc.layers; ++layer) {
            if (!rendered[layer]) all_layers.push_back({layer, resolution, {}, VK_FRONT_FACE_COUNTER_CLOCKWISE});
        }
    }
    if (all_layers.empty()) return;  // every layer kept: the map stays ShaderSampled
    if (gpu_culling_) {
        std::vector<bool> culled(map.desc.layers, false);
        for (const LocalShadowLayer& layer : all_layers) culled[layer.layer] = layer.gpu_culled;
        gpu_culling_->record_cull(cmd, frame_set, scene, CullLayers::LocalLayers, culled, cull, frame);
    }
    gpu::transition(device_, cmd, map, keep ? gpu::ImageState::ShaderSampled : gpu::ImageState::DiscardAfterShaderReads,
                    gpu::ImageState::DepthAttachment);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, PENUMBRA_SET_CASTER_FRAME,
                                     1, &frame_set, 0, nullptr);
    for (const LocalShadowLayer& layer : all_layers) {
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = map.layer_views[layer.layer];
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: nothing casts
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {resolution, resolution}};
        info.layerCount = 1;
        info.pDepthAttachment = &depth;
        device_->vkCmdBeginRendering(cmd, &info);
        set_viewport_and_scissor(device_, cmd, layer.resolution, layer.resolution);
        set_shadow_depth_bias(device_, cmd, bias);
        const CasterFaceCulling faces{culling, layer.facing_light};
        if (layer.gpu_culled && gpu_culling_) {
            gpu_culling_->record_draws(cmd, pipelines_, scene, faces, layer.layer);
        } else {
            record_caster_draws(device_, cmd, pipelines_, scene, layer.draws, layer.layer, faces);
        }
        device_->vkCmdEndRendering(cmd);
    }
    gpu::transition(device_, cmd, map, gpu::ImageState::DepthAttachment, gpu::ImageState::ShaderSampled);
}

}  // namespace penumbra::passes
