#include "passes/visibility_resolve_pass.hpp"

#include <array>
#include <utility>

#include "passes/shadow_filter_specialization.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

constexpr uint32_t kGroupSize = 8;  // local_size_x and _y of visibility_resolve.comp

gpu::UniqueDescriptorSetLayout create_screen_set_layout(const gpu::Device& device) {
    const std::array<VkDescriptorSetLayoutBinding, 4> bindings{{
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    }};
    return gpu::create_descriptor_set_layout(device, bindings);
}

}  // namespace

gpu::Image create_visibility_image(const gpu::Device& device, uint32_t width, uint32_t height, uint32_t layers) {
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = width;
    desc.height = height;
    desc.layers = layers;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.array_view = true;
    return gpu::create_image(device, desc);
}

VisibilityResolvePass::VisibilityResolvePass(const gpu::Device& device, VkDescriptorSetLayout shadow_set_layout,
                                             const FilterSettings& filter)
    : device_(device), screen_set_layout_(create_screen_set_layout(device)) {
    const std::array<VkDescriptorSetLayout, 2> sets{shadow_set_layout, screen_set_layout_};
    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(shader::ResolvePushConstants)};
    layout_ = gpu::create_pipeline_layout(device, sets, {&range, 1});
    pipeline_ = create_pipeline(filter);
    gpu::SamplerDesc sampler;
    sampler.filter = VK_FILTER_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    nearest_ = gpu::create_sampler(device, sampler);
}

gpu::UniquePipeline VisibilityResolvePass::create_pipeline(const FilterSettings& filter) const {
    return gpu::create_compute_pipeline(
        device_,
        {VK_SHADER_STAGE_COMPUTE_BIT, shaders::visibility_resolve_comp(), shadow_filter_specialization(filter)},
        layout_);
}

gpu::UniquePipeline VisibilityResolvePass::respecialize(const FilterSettings& filter) {
    gpu::UniquePipeline replaced = create_pipeline(filter);
    std::swap(replaced, pipeline_);
    return replaced;
}

void VisibilityResolvePass::write_screen_set(VkDescriptorSet set, const ScreenInputs& screen,
                                             VkImageView target) const {
    // An absent normal image is bound to the depth again: the shader does not read it.
    const auto write_or_depth = [&](uint32_t binding, VkImageView view, VkImageLayout layout) {
        if (view != VK_NULL_HANDLE) {
            gpu::write_combined_image_sampler(device_, set, binding, view, nearest_, layout);
        } else {
            gpu::write_combined_image_sampler(device_, set, binding, screen.depth, nearest_, screen.depth_layout);
        }
    };
    gpu::write_combined_image_sampler(device_, set, 0, screen.depth, nearest_, screen.depth_layout);
    write_or_depth(1, screen.normals, screen.normals_layout);
    gpu::write_storage_image(device_, set, 2, target);
    write_or_depth(3, screen.face_normals, screen.face_normals_layout);
}

void VisibilityResolvePass::record(VkCommandBuffer cmd, VkDescriptorSet shadow_set, VkDescriptorSet screen_set,
                                   const ResolveTarget& target, const shader::ResolvePushConstants& constants,
                                   ResolveQueue queue) const {
    const bool graphics = queue == ResolveQueue::Graphics;
    gpu::transition(device_, cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, target.layers,
                    graphics ? gpu::ImageState::DiscardAfterShaderReads : gpu::ImageState::DiscardAfterComputeReads,
                    gpu::ImageState::ComputeStorageWrite);
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    const std::array<VkDescriptorSet, 2> sets{shadow_set, screen_set};
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 2, sets.data(), 0, nullptr);
    device_->vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    device_->vkCmdDispatch(cmd, (constants.width + kGroupSize - 1) / kGroupSize,
                           (constants.height + kGroupSize - 1) / kGroupSize, 1);
    gpu::transition(device_, cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, target.layers,
                    gpu::ImageState::ComputeStorageWrite,
                    graphics ? gpu::ImageState::ShaderSampled : gpu::ImageState::ComputeSampled);
}

}  // namespace penumbra::passes
