#pragma once
// Graphics pipelines for dynamic rendering, shader modules from embedded SPIR-V,
// descriptor-set layouts, pools and samplers.
#include <vulkan/vulkan.h>

#include <optional>

#include <cstdint>
#include <span>
#include <vector>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"

namespace penumbra::gpu {

UniqueShaderModule create_shader_module(const Device& device, std::span<const uint32_t> spirv);

struct SpecializationValue {
    uint32_t constant_id;
    uint32_t value;  // 32-bit int/uint/bool (VK_TRUE/VK_FALSE) or float bits
    bool operator==(const SpecializationValue&) const = default;
};

struct ShaderStage {
    VkShaderStageFlagBits stage;
    std::span<const uint32_t> spirv;
    std::vector<SpecializationValue> specialization;
};

struct VertexLayout {
    uint32_t stride = 0;  // of binding 0, when `bindings` is empty
    std::vector<VkVertexInputAttributeDescription> attributes;
    // Several bindings (e.g. positions and UVs in separate streams); their strides are
    // then set at draw time (vkCmdBindVertexBuffers2) when dynamic_strides is set.
    std::vector<VkVertexInputBindingDescription> bindings;
    bool dynamic_strides = false;
};

struct GraphicsPipelineDesc {
    std::vector<ShaderStage> stages;  // a depth-only pipeline has no fragment stage
    VertexLayout vertex_layout;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::vector<VkFormat> color_formats;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
    VkCompareOp depth_compare = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reverse-Z
    bool depth_write = true;
    VkCullModeFlags cull_mode = VK_CULL_MODE_BACK_BIT;
    bool depth_bias = false;       // dynamic depth bias (vkCmdSetDepthBias)
    bool depth_clamp = false;      // flatten geometry in front of the near plane onto it
    uint32_t view_mask = 0;        // multiview: one bit per rendered layer
    bool dynamic_culling = false;  // cull mode and front face set at draw time (vkCmdSetCullMode/FrontFace)
    uint32_t viewport_count = 1;   // viewports and scissors (set at draw time); more than one needs multiViewport
};

UniquePipeline create_graphics_pipeline(const Device& device, const GraphicsPipelineDesc& desc);

// A compute pipeline of `stage` (its stage must be VK_SHADER_STAGE_COMPUTE_BIT).
UniquePipeline create_compute_pipeline(const Device& device, const ShaderStage& stage, VkPipelineLayout layout);

UniquePipelineLayout create_pipeline_layout(const Device& device, std::span<const VkDescriptorSetLayout> set_layouts,
                                            std::span<const VkPushConstantRange> push_constants);

UniqueDescriptorSetLayout create_descriptor_set_layout(const Device& device,
                                                       std::span<const VkDescriptorSetLayoutBinding> bindings);

UniqueDescriptorPool create_descriptor_pool(const Device& device, uint32_t max_sets,
                                            std::span<const VkDescriptorPoolSize> sizes,
                                            VkDescriptorPoolCreateFlags flags = 0);

VkDescriptorSet allocate_descriptor_set(const Device& device, VkDescriptorPool pool, VkDescriptorSetLayout layout);

void write_uniform_buffer(const Device& device, VkDescriptorSet set, uint32_t binding, VkBuffer buffer,
                          VkDeviceSize size);
void write_storage_buffer(const Device& device, VkDescriptorSet set, uint32_t binding, VkBuffer buffer,
                          VkDeviceSize size);
void write_combined_image_sampler(const Device& device, VkDescriptorSet set, uint32_t binding, VkImageView view,
                                  VkSampler sampler, VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
// A storage image in VK_IMAGE_LAYOUT_GENERAL.
void write_storage_image(const Device& device, VkDescriptorSet set, uint32_t binding, VkImageView view);

struct SamplerDesc {
    VkFilter filter = VK_FILTER_LINEAR;
    VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_REPEAT;  // U, and V and W unless set below
    std::optional<VkSamplerAddressMode> address_v;
    bool compare = false;  // depth comparison sampler (sampler2DArrayShadow)
    VkCompareOp compare_op = VK_COMPARE_OP_GREATER_OR_EQUAL;
    VkBorderColor border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
};

UniqueSampler create_sampler(const Device& device, const SamplerDesc& desc);

}  // namespace penumbra::gpu
