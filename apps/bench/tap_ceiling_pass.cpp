#include "bench/tap_ceiling_pass.hpp"

#include <cstddef>

#include <glm/glm.hpp>

#include "bench_shaders.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "renderer/draw_recording.hpp"

namespace penumbra::bench {
namespace shader {

using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#include "bench_shared.h"
static_assert(offsetof(TapCeilingPushConstants, counts) == 16 && sizeof(TapCeilingPushConstants) == 32);

}  // namespace shader
namespace {

constexpr VkFormat kTargetFormat = VK_FORMAT_R8G8B8A8_UNORM;

gpu::Image create_shadow_map(const gpu::Device& device, const TapCeilingDesc& desc) {
    gpu::ImageDesc image;
    image.format = VK_FORMAT_D32_SFLOAT;  // the shadow pass's format
    image.width = desc.shadow_resolution;
    image.height = desc.shadow_resolution;
    image.layers = desc.shadow_layers;
    image.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    image.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    image.array_view = true;
    return gpu::create_image(device, image);
}

gpu::Image create_target(const gpu::Device& device, const TapCeilingDesc& desc) {
    gpu::ImageDesc image;
    image.format = kTargetFormat;
    image.width = desc.width;
    image.height = desc.height;
    image.usage =
        desc.units == TapCeilingUnits::Compute ? VK_IMAGE_USAGE_STORAGE_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    return gpu::create_image(device, image);
}

VkShaderStageFlags stage_of(TapCeilingUnits units) {
    return units == TapCeilingUnits::Compute ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
}

gpu::UniquePipeline create_pipeline(const gpu::Device& device, VkPipelineLayout layout, TapCeilingUnits units) {
    if (units == TapCeilingUnits::Compute) {
        return gpu::create_compute_pipeline(device, {VK_SHADER_STAGE_COMPUTE_BIT, shaders::tap_ceiling_comp(), {}},
                                            layout);
    }
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::fullscreen_vert(), {}});
    desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, shaders::tap_ceiling_frag(), {}});
    desc.layout = layout;
    desc.color_formats = {kTargetFormat};
    desc.cull_mode = VK_CULL_MODE_NONE;
    desc.depth_write = false;
    return gpu::create_graphics_pipeline(device, desc);
}

}  // namespace

TapCeilingPass::TapCeilingPass(const gpu::Device& device, const TapCeilingDesc& desc)
    : device_(device), desc_(desc), shadow_map_(create_shadow_map(device, desc)), target_(create_target(device, desc)) {
    // The shadow sampler of Penumbra's descriptor set: bilinear depth comparison.
    gpu::SamplerDesc sampler;
    sampler.filter = VK_FILTER_LINEAR;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler.compare = true;
    sampler.compare_op = VK_COMPARE_OP_GREATER_OR_EQUAL;
    sampler_ = gpu::create_sampler(device, sampler);

    const bool compute = desc.units == TapCeilingUnits::Compute;
    const VkShaderStageFlags stage = stage_of(desc.units);
    const VkDescriptorSetLayoutBinding bindings[] = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stage, nullptr},
                                                     {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr}};
    set_layout_ = gpu::create_descriptor_set_layout(device, {bindings, compute ? 2u : 1u});
    const VkDescriptorPoolSize pool_sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                               {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    descriptor_pool_ = gpu::create_descriptor_pool(device, 1, {pool_sizes, compute ? 2u : 1u});
    set_ = gpu::allocate_descriptor_set(device, descriptor_pool_, set_layout_);
    gpu::write_combined_image_sampler(device, set_, 0, shadow_map_.view, sampler_);
    if (compute) gpu::write_storage_image(device, set_, 1, target_.view);

    const VkDescriptorSetLayout set_layout = set_layout_;
    const VkPushConstantRange push{stage, 0, sizeof(shader::TapCeilingPushConstants)};
    pipeline_layout_ = gpu::create_pipeline_layout(device, {&set_layout, 1}, {&push, 1});
    pipeline_ = create_pipeline(device, pipeline_layout_, desc.units);
}

void TapCeilingPass::record_setup(VkCommandBuffer cmd) const {
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::Undefined, gpu::ImageState::TransferDst);
    // Half depth everywhere: the compare result is constant, the filtering work is not.
    const VkClearDepthStencilValue clear{0.5f, 0};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, desc_.shadow_layers};
    device_->vkCmdClearDepthStencilImage(cmd, shadow_map_.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1,
                                         &range);
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::TransferDst, gpu::ImageState::ShaderSampled);
}

void TapCeilingPass::record(VkCommandBuffer cmd) const {
    shader::TapCeilingPushConstants params{};
    params.target_and_texel = {1.0f / static_cast<float>(desc_.width), 1.0f / static_cast<float>(desc_.height),
                               1.0f / static_cast<float>(desc_.shadow_resolution), 0.0f};
    params.counts = {desc_.taps, desc_.shadow_layers, 0u, 0u};
    if (desc_.units == TapCeilingUnits::Compute) {
        record_compute(cmd, &params, sizeof(params));
    } else {
        record_fragment(cmd, &params, sizeof(params));
    }
}

void TapCeilingPass::record_compute(VkCommandBuffer cmd, const void* params, uint32_t size) const {
    // Every frame overwrites the whole target (the previous frame completed before this one).
    gpu::transition(device_, cmd, target_, gpu::ImageState::Undefined, gpu::ImageState::ComputeStorageWrite);
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout_, 0, 1, &set_, 0, nullptr);
    device_->vkCmdPushConstants(cmd, pipeline_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, size, params);
    constexpr uint32_t kGroupSize = 8;  // tap_ceiling.comp's local size
    device_->vkCmdDispatch(cmd, (desc_.width + kGroupSize - 1) / kGroupSize,
                           (desc_.height + kGroupSize - 1) / kGroupSize, 1);
}

void TapCeilingPass::record_fragment(VkCommandBuffer cmd, const void* params, uint32_t size) const {
    gpu::transition(device_, cmd, target_, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = target_.view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every pixel is written
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {desc_.width, desc_.height}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    device_->vkCmdBeginRendering(cmd, &info);
    renderer::set_viewport_and_scissor(device_, cmd, desc_.width, desc_.height);
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, 0, 1, &set_, 0, nullptr);
    device_->vkCmdPushConstants(cmd, pipeline_layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, size, params);
    device_->vkCmdDraw(cmd, 3, 1, 0, 0);
    device_->vkCmdEndRendering(cmd);
}

}  // namespace penumbra::bench
