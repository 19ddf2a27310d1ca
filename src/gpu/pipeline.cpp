#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/debug_names.hpp"

#include "penumbra/gpu/check.hpp"

namespace penumbra::gpu {

UniqueShaderModule create_shader_module(const Device& device, std::span<const uint32_t> spirv) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateShaderModule(device, &info, nullptr, &module));
    name_object(device, VK_OBJECT_TYPE_SHADER_MODULE, module, "shader module");
    return UniqueShaderModule(device, module);
}

namespace {

// Specialization data must outlive vkCreateGraphicsPipelines; one per stage.
struct StageSpecialization {
    std::vector<VkSpecializationMapEntry> entries;
    std::vector<uint32_t> values;
    VkSpecializationInfo info{};
};

void fill_specialization(const ShaderStage& stage, StageSpecialization& out) {
    for (const SpecializationValue& value : stage.specialization) {
        const auto offset = static_cast<uint32_t>(out.values.size() * sizeof(uint32_t));
        out.entries.push_back({value.constant_id, offset, sizeof(uint32_t)});
        out.values.push_back(value.value);
    }
    out.info.mapEntryCount = static_cast<uint32_t>(out.entries.size());
    out.info.pMapEntries = out.entries.data();
    out.info.dataSize = out.values.size() * sizeof(uint32_t);
    out.info.pData = out.values.data();
}

}  // namespace

UniquePipeline create_graphics_pipeline(const Device& device, const GraphicsPipelineDesc& desc) {
    std::vector<UniqueShaderModule> modules;
    std::vector<StageSpecialization> specializations(desc.stages.size());
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    for (size_t i = 0; i < desc.stages.size(); ++i) {
        modules.push_back(create_shader_module(device, desc.stages[i].spirv));
        fill_specialization(desc.stages[i], specializations[i]);
        VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        stage.stage = desc.stages[i].stage;
        stage.module = modules.back();
        stage.pName = "main";
        stage.pSpecializationInfo = specializations[i].entries.empty() ? nullptr : &specializations[i].info;
        stages.push_back(stage);
    }

    std::vector<VkVertexInputBindingDescription> bindings = desc.vertex_layout.bindings;
    // One binding of `stride` by default; none when the vertex shader has no inputs
    // (full-screen passes).
    if (bindings.empty() && !desc.vertex_layout.attributes.empty()) {
        bindings.push_back({0, desc.vertex_layout.stride, VK_VERTEX_INPUT_RATE_VERTEX});
    }
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(bindings.size());
    vertex_input.pVertexBindingDescriptions = bindings.data();
    vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(desc.vertex_layout.attributes.size());
    vertex_input.pVertexAttributeDescriptions = desc.vertex_layout.attributes.data();

    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = desc.viewport_count;
    viewport.scissorCount = desc.viewport_count;

    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.depthClampEnable = desc.depth_clamp ? VK_TRUE : VK_FALSE;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = desc.cull_mode;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.depthBiasEnable = desc.depth_bias ? VK_TRUE : VK_FALSE;
    raster.lineWidth = 1.0f;

    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = desc.depth_format != VK_FORMAT_UNDEFINED ? VK_TRUE : VK_FALSE;
    depth.depthWriteEnable = desc.depth_write ? VK_TRUE : VK_FALSE;
    depth.depthCompareOp = desc.depth_compare;

    std::vector<VkPipelineColorBlendAttachmentState> blend_attachments(desc.color_formats.size());
    for (auto& attachment : blend_attachments) {
        attachment.colorWriteMask =
            VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    }
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = static_cast<uint32_t>(blend_attachments.size());
    blend.pAttachments = blend_attachments.data();

    std::vector<VkDynamicState> dynamic_states = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    if (desc.depth_bias) dynamic_states.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
    if (desc.vertex_layout.dynamic_strides) dynamic_states.push_back(VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE);
    if (desc.dynamic_culling) {
        dynamic_states.push_back(VK_DYNAMIC_STATE_CULL_MODE);
        dynamic_states.push_back(VK_DYNAMIC_STATE_FRONT_FACE);
    }
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = static_cast<uint32_t>(dynamic_states.size());
    dynamic.pDynamicStates = dynamic_states.data();

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.viewMask = desc.view_mask;
    rendering.colorAttachmentCount = static_cast<uint32_t>(desc.color_formats.size());
    rendering.pColorAttachmentFormats = desc.color_formats.data();
    rendering.depthAttachmentFormat = desc.depth_format;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = static_cast<uint32_t>(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = desc.layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    name_object(device, VK_OBJECT_TYPE_PIPELINE, pipeline, "graphics pipeline");
    return UniquePipeline(device, pipeline);
}

UniquePipeline create_compute_pipeline(const Device& device, const ShaderStage& stage, VkPipelineLayout layout) {
    const UniqueShaderModule module = create_shader_module(device, stage.spirv);
    StageSpecialization specialization;
    fill_specialization(stage, specialization);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = specialization.entries.empty() ? nullptr : &specialization.info;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    name_object(device, VK_OBJECT_TYPE_PIPELINE, pipeline, "compute pipeline");
    return UniquePipeline(device, pipeline);
}

UniquePipelineLayout create_pipeline_layout(const Device& device, std::span<const VkDescriptorSetLayout> set_layouts,
                                            std::span<const VkPushConstantRange> push_constants) {
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = static_cast<uint32_t>(set_layouts.size());
    info.pSetLayouts = set_layouts.data();
    info.pushConstantRangeCount = static_cast<uint32_t>(push_constants.size());
    info.pPushConstantRanges = push_constants.data();
    VkPipelineLayout layout = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreatePipelineLayout(device, &info, nullptr, &layout));
    name_object(device, VK_OBJECT_TYPE_PIPELINE_LAYOUT, layout, "pipeline layout");
    return UniquePipelineLayout(device, layout);
}

UniqueDescriptorSetLayout create_descriptor_set_layout(const Device& device,
                                                       std::span<const VkDescriptorSetLayoutBinding> bindings) {
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = static_cast<uint32_t>(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateDescriptorSetLayout(device, &info, nullptr, &layout));
    name_object(device, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, layout, "descriptor set layout");
    return UniqueDescriptorSetLayout(device, layout);
}

UniqueDescriptorPool create_descriptor_pool(const Device& device, uint32_t max_sets,
                                            std::span<const VkDescriptorPoolSize> sizes,
                                            VkDescriptorPoolCreateFlags flags) {
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.flags = flags;
    info.maxSets = max_sets;
    info.poolSizeCount = static_cast<uint32_t>(sizes.size());
    info.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateDescriptorPool(device, &info, nullptr, &pool));
    name_object(device, VK_OBJECT_TYPE_DESCRIPTOR_POOL, pool, "descriptor pool");
    return UniqueDescriptorPool(device, pool);
}

VkDescriptorSet allocate_descriptor_set(const Device& device, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = pool;
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkAllocateDescriptorSets(device, &info, &set));
    name_object(device, VK_OBJECT_TYPE_DESCRIPTOR_SET, set, "descriptor set");
    return set;
}

namespace {

void write_buffer(const Device& device, VkDescriptorSet set, uint32_t binding, VkBuffer buffer, VkDeviceSize size,
                  VkDescriptorType type) {
    const VkDescriptorBufferInfo buffer_info{buffer, 0, size};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pBufferInfo = &buffer_info;
    device->vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}

}  // namespace

void write_uniform_buffer(const Device& device, VkDescriptorSet set, uint32_t binding, VkBuffer buffer,
                          VkDeviceSize size) {
    write_buffer(device, set, binding, buffer, size, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
}

void write_storage_buffer(const Device& device, VkDescriptorSet set, uint32_t binding, VkBuffer buffer,
                          VkDeviceSize size) {
    write_buffer(device, set, binding, buffer, size, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

namespace {

void write_image(const Device& device, VkDescriptorSet set, uint32_t binding, const VkDescriptorImageInfo& image,
                 VkDescriptorType type) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pImageInfo = &image;
    device->vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}

}  // namespace

void write_combined_image_sampler(const Device& device, VkDescriptorSet set, uint32_t binding, VkImageView view,
                                  VkSampler sampler, VkImageLayout layout) {
    write_image(device, set, binding, {sampler, view, layout}, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
}

void write_storage_image(const Device& device, VkDescriptorSet set, uint32_t binding, VkImageView view) {
    write_image(device, set, binding, {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL},
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
}

UniqueSampler create_sampler(const Device& device, const SamplerDesc& desc) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = desc.filter;
    info.minFilter = desc.filter;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = desc.address;
    info.addressModeV = desc.address_v.value_or(desc.address);
    info.addressModeW = desc.address;
    info.compareEnable = desc.compare ? VK_TRUE : VK_FALSE;
    info.compareOp = desc.compare_op;
    info.borderColor = desc.border;
    info.maxLod = 0.0f;
    VkSampler sampler = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateSampler(device, &info, nullptr, &sampler));
    name_object(device, VK_OBJECT_TYPE_SAMPLER, sampler, "sampler");
    return UniqueSampler(device, sampler);
}

}  // namespace penumbra::gpu
