#include "passes/virtual_shadow_pass.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>

#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

// virtual_cull.comp runs one workgroup per instance; Vulkan guarantees 65,535 workgroups in
// each dimension, and the second continues the first.
constexpr uint32_t kMaxWorkgroupsPerDimension = 65535;

void require_features(const gpu::Device& device, const VirtualPages& pages) {
    if (!device.features().virtual_pages) {
        throw DeviceError(
            "shadow technique virtual: the device was not created with the features virtual shadow maps need "
            "(VkPhysicalDeviceFeatures::multiDrawIndirect, drawIndirectFirstInstance and multiViewport, "
            "VkPhysicalDeviceVulkan12Features::drawIndirectCount, shaderOutputLayer and shaderOutputViewportIndex)");
    }
    const uint32_t pool_pages = pages.desc().pool_pages;
    const uint32_t layers = virtual_pool_layers(pool_pages);
    const VkPhysicalDeviceLimits& limits = device.properties().limits;
    const uint32_t layer_limit = std::min(limits.maxImageArrayLayers, limits.maxFramebufferLayers);
    if (layers > layer_limit) {
        throw DeviceError("shadow technique virtual: a pool of " + std::to_string(pool_pages) + " pages needs " +
                          std::to_string(layers) + " image layers; " + device.info().name + " allows " +
                          std::to_string(layer_limit) + " (maxImageArrayLayers, maxFramebufferLayers)");
    }
}

gpu::Image create_pool(const gpu::Device& device, uint32_t pool_pages) {
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_D32_SFLOAT;
    desc.width = kVirtualPoolLayerPages * kVirtualPageTexels;
    desc.height = desc.width;
    desc.layers = virtual_pool_layers(pool_pages);
    desc.array_view = true;
    desc.layer_views = false;  // drawn through gl_Layer, one rendering over every layer
    desc.usage =
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    return gpu::create_image(device, desc);
}

// One viewport and scissor per page of a pool layer, page i at (i % 4, i / 4).
void set_page_viewports(const gpu::Device& device, VkCommandBuffer cmd) {
    constexpr uint32_t count = kVirtualPagesPerPoolLayer;
    constexpr float side = static_cast<float>(kVirtualPageTexels);
    std::array<VkViewport, count> viewports{};
    std::array<VkRect2D, count> scissors{};
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t x = i % kVirtualPoolLayerPages * kVirtualPageTexels;
        const uint32_t y = i / kVirtualPoolLayerPages * kVirtualPageTexels;
        viewports[i] = {static_cast<float>(x), static_cast<float>(y), side, side, 0.0f, 1.0f};
        scissors[i] = {{static_cast<int32_t>(x), static_cast<int32_t>(y)}, {kVirtualPageTexels, kVirtualPageTexels}};
    }
    device->vkCmdSetViewport(cmd, 0, count, viewports.data());
    device->vkCmdSetScissor(cmd, 0, count, scissors.data());
}

// One workgroup per culled unit, the rows continuing the columns.
glm::uvec2 cull_grid(uint32_t units) {
    const uint32_t columns = std::clamp(units, 1u, kMaxWorkgroupsPerDimension);
    return {columns, (units + columns - 1) / columns};
}

CasterPipelineTemplate virtual_template(const gpu::Device& device, VkPipelineLayout layout) {
    CasterPipelineTemplate pipelines;
    pipelines.opaque_vertex = shaders::caster_virtual_vert();
    pipelines.masked_vertex = shaders::caster_virtual_masked_vert();
    pipelines.masked_fragment = shaders::caster_masked_frag();
    pipelines.layout = layout;
    pipelines.depth_bias = true;
    pipelines.depth_clamp = device.depth_clamp_supported();
    pipelines.viewport_count = kVirtualPagesPerPoolLayer;
    return pipelines;
}

}  // namespace

glm::uvec2 VirtualShadowPass::cull_workgroups(const CasterScene& scene) {
    return cull_grid(cull_unit_total(scene, CullUnit::Clusters));
}

VirtualShadowPass::VirtualShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                                     VkDescriptorSetLayout alpha_mask_set_layout, const VirtualPages& pages,
                                     uint32_t frames_in_flight)
    : device_((require_features(device, pages), device)),
      culling_(device, frame_set_layout, frames_in_flight, CullUnit::Clusters),
      caster_layout_([&] {
          static_assert(PENUMBRA_SET_CASTER_FRAME == 0 && PENUMBRA_SET_ALPHA_MASK == 1 &&
                        PENUMBRA_SET_CASTER_DRAWS == 2 && PENUMBRA_SET_VIRTUAL_PAGES == 3);
          const std::array<VkDescriptorSetLayout, 4> sets{frame_set_layout, alpha_mask_set_layout,
                                                          culling_.draws_set_layout(), pages.pages_set_layout()};
          const VkPushConstantRange push_range = caster_push_constant_range();
          return gpu::create_pipeline_layout(device, sets, {&push_range, 1});
      }()),
      pipelines_(device, virtual_template(device, caster_layout_)),
      pool_(create_pool(device, pages.desc().pool_pages)) {
    const std::array<VkDescriptorSetLayout, 2> cull_sets{pages.pages_set_layout(), culling_.draws_set_layout()};
    const VkPushConstantRange cull_range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(shader::VirtualCullPushConstants)};
    cull_layout_ = gpu::create_pipeline_layout(device, cull_sets, {&cull_range, 1});
    cull_pipeline_ = gpu::create_compute_pipeline(
        device, {VK_SHADER_STAGE_COMPUTE_BIT, shaders::virtual_cull_comp(), {}}, cull_layout_);
    const VkDescriptorSetLayout pages_set = pages.pages_set_layout();
    clear_layout_ = gpu::create_pipeline_layout(device, {&pages_set, 1}, {});
    gpu::GraphicsPipelineDesc clear;
    clear.stages = {{VK_SHADER_STAGE_VERTEX_BIT, shaders::virtual_clear_vert(), {}}};
    clear.layout = clear_layout_;
    clear.depth_format = VK_FORMAT_D32_SFLOAT;
    clear.depth_compare = VK_COMPARE_OP_ALWAYS;
    clear.cull_mode = VK_CULL_MODE_NONE;
    clear.viewport_count = kVirtualPagesPerPoolLayer;
    clear_pipeline_ = gpu::create_graphics_pipeline(device, clear);
}

void VirtualShadowPass::record_cull(VkCommandBuffer cmd, const CasterScene& scene, VirtualPages& pages,
                                    uint64_t frame) {
    const uint32_t levels = pages.desc().level_count;
    if (!culling_.begin_commands(cmd, scene, levels)) {
        pages.copy_counters(cmd, frame);
        return;
    }
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cull_pipeline_);
    const std::array<VkDescriptorSet, 2> sets{pages.pages_set(frame), culling_.draws_set()};
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cull_layout_, 0, 2, sets.data(), 0, nullptr);
    shader::VirtualCullPushConstants constants{};
    constants.instance_count = culling_.draw_count();
    constants.bucket_count = static_cast<uint32_t>(culling_.buckets().size());
    constants.draw_capacity = pages.desc().max_page_draws;
    constants.level_count = levels;
    device_->vkCmdPushConstants(cmd, cull_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    // The allocation wrote cull_workgroups(scene) here, or no workgroup when no page is drawn.
    device_->vkCmdDispatchIndirect(cmd, pages.counters_buffer(), offsetof(shader::VirtualCounters, cull_groups));
    culling_.finish_commands(cmd, frame);
    // The culling's last count: the frame's counters, copied with the culling's statistics.
    pages.record_counters_copy(cmd, frame);
    gpu::transfer_to_host_barrier(device_, cmd);
}

void VirtualShadowPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                               VirtualPages& pages, uint64_t frame, const BiasSettings& bias,
                               const CasterFaceCulling& culling, gpu::GpuTimer* timer) {
    {
        gpu::TimedScope scope(device_, timer, cmd, "shadow_virtual_cull");
        record_cull(cmd, scene, pages, frame);
    }
    gpu::TimedScope scope(device_, timer, cmd, "shadow_virtual_raster");
    gpu::transition(device_, cmd, pool_, pool_state_, gpu::ImageState::DepthAttachment);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = pool_.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // cached pages keep their texels
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {pool_.desc.width, pool_.desc.height}};
    info.layerCount = pool_.desc.layers;
    info.pDepthAttachment = &depth;
    device_->vkCmdBeginRendering(cmd, &info);
    set_page_viewports(device_, cmd);
    const VkDescriptorSet pages_set = pages.pages_set(frame);
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, clear_pipeline_);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, clear_layout_, 0, 1, &pages_set, 0, nullptr);
    device_->vkCmdDrawIndirect(cmd, pages.counters_buffer(), offsetof(shader::VirtualCounters, level_clears),
                               pages.desc().level_count, sizeof(shader::VirtualClearDraw));
    if (culling_.draws_set() != VK_NULL_HANDLE && !culling_.buckets().empty()) {
        set_shadow_depth_bias(device_, cmd, bias);
        device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, caster_layout_,
                                         PENUMBRA_SET_CASTER_FRAME, 1, &frame_set, 0, nullptr);
        device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, caster_layout_,
                                         PENUMBRA_SET_VIRTUAL_PAGES, 1, &pages_set, 0, nullptr);
        culling_.record_draws_of_every_layer(cmd, pipelines_, scene, culling);
    }
    device_->vkCmdEndRendering(cmd);
    gpu::transition(device_, cmd, pool_, gpu::ImageState::DepthAttachment, gpu::ImageState::ShaderSampled);
    pool_state_ = gpu::ImageState::ShaderSampled;
}

}  // namespace penumbra::passes
