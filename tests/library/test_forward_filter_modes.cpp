// Forward shaders may take the filter from the uniforms (PENUMBRA_FILTER_FROM_UNIFORMS) and
// never be rebuilt: through the filters, changed live with update_settings(), one such
// pipeline computes what a pipeline specialised with shader_specialization() computes, for
// the sun and a spot light (tests/library/shaders/forward_probe.comp).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "library_fixture.hpp"
#include "library_test_shaders.hpp"

namespace penumbra::library_tests {
namespace {

struct ProbeConstants {
    float half_extent;
    uint32_t size;
    uint32_t light;
};

// The probe's pipelines and the two outputs (specialised, from the uniforms).
class ForwardProbe {
public:
    ForwardProbe(const DeviceDesc& device, VkDescriptorSetLayout shadow_layout, size_t pixels)
        : device_(device.device),
          specialised_out_(device, VkDeviceSize{pixels} * sizeof(float) * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
          uniform_out_(device, VkDeviceSize{pixels} * sizeof(float) * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
        const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                                   nullptr};
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = 1;
        set_info.pBindings = &binding;
        TEST_VK(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &output_layout_));
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = 2;
        pool_info.poolSizeCount = 1;
        pool_info.pPoolSizes = &size;
        TEST_VK(vkCreateDescriptorPool(device_, &pool_info, nullptr, &pool_));
        specialised_set_ = output_set(specialised_out_);
        uniform_set_ = output_set(uniform_out_);
        const std::array<VkDescriptorSetLayout, 2> layouts{shadow_layout, output_layout_};
        const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ProbeConstants)};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = static_cast<uint32_t>(layouts.size());
        layout_info.pSetLayouts = layouts.data();
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &range;
        TEST_VK(vkCreatePipelineLayout(device_, &layout_info, nullptr, &layout_));
        uniform_pipeline_ = create_pipeline(shaders::forward_probe_uniform_filter_comp(), nullptr);
    }
    ~ForwardProbe() {
        vkDestroyPipeline(device_, specialised_pipeline_, nullptr);
        vkDestroyPipeline(device_, uniform_pipeline_, nullptr);
        vkDestroyPipelineLayout(device_, layout_, nullptr);
        vkDestroyDescriptorPool(device_, pool_, nullptr);
        vkDestroyDescriptorSetLayout(device_, output_layout_, nullptr);
    }
    ForwardProbe(const ForwardProbe&) = delete;
    ForwardProbe& operator=(const ForwardProbe&) = delete;

    // What the caller does when update_settings() says the specialization changed.
    void respecialise(const ShaderSpecialization& specialization) {
        vkDestroyPipeline(device_, specialised_pipeline_, nullptr);
        const VkSpecializationInfo info = specialization.info();
        specialised_pipeline_ = create_pipeline(shaders::forward_probe_comp(), &info);
    }

    void record(VkCommandBuffer cmd, VkDescriptorSet shadow_set, const ProbeConstants& constants) const {
        for (const auto& [pipeline, set] :
             {std::pair{specialised_pipeline_, specialised_set_}, std::pair{uniform_pipeline_, uniform_set_}}) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
            const std::array<VkDescriptorSet, 2> sets{shadow_set, set};
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 2, sets.data(), 0, nullptr);
            vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
            vkCmdDispatch(cmd, (constants.size + 7) / 8, (constants.size + 7) / 8, 1);
        }
        host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }

    std::vector<float> specialised(size_t pixels) const { return read(specialised_out_, pixels); }
    std::vector<float> from_uniforms(size_t pixels) const { return read(uniform_out_, pixels); }

private:
    VkDescriptorSet output_set(const HostBuffer& buffer) {
        VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        info.descriptorPool = pool_;
        info.descriptorSetCount = 1;
        info.pSetLayouts = &output_layout_;
        VkDescriptorSet set = VK_NULL_HANDLE;
        TEST_VK(vkAllocateDescriptorSets(device_, &info, &set));
        const VkDescriptorBufferInfo buffer_info{buffer.buffer, 0, VK_WHOLE_SIZE};
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstSet = set;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        write.pBufferInfo = &buffer_info;
        vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
        return set;
    }

    VkPipeline create_pipeline(std::span<const uint32_t> spirv, const VkSpecializationInfo* specialization) const {
        VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        module_info.codeSize = spirv.size_bytes();
        module_info.pCode = spirv.data();
        VkShaderModule module = VK_NULL_HANDLE;
        TEST_VK(vkCreateShaderModule(device_, &module_info, nullptr, &module));
        VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        info.stage.module = module;
        info.stage.pName = "main";
        info.stage.pSpecializationInfo = specialization;
        info.layout = layout_;
        VkPipeline pipeline = VK_NULL_HANDLE;
        const VkResult result = vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
        vkDestroyShaderModule(device_, module, nullptr);
        TEST_VK(result);
        return pipeline;
    }

    static std::vector<float> read(const HostBuffer& buffer, size_t pixels) {
        const auto* values = static_cast<const float*>(buffer.mapped);
        return {values, values + pixels * 2};
    }

    VkDevice device_;
    HostBuffer specialised_out_;
    HostBuffer uniform_out_;
    VkDescriptorSetLayout output_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet specialised_set_ = VK_NULL_HANDLE;
    VkDescriptorSet uniform_set_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline specialised_pipeline_ = VK_NULL_HANDLE;
    VkPipeline uniform_pipeline_ = VK_NULL_HANDLE;
};

using ForwardFilterModes = LibraryTest;

TEST_F(ForwardFilterModes, FromUniformsEqualsSpecialisedAcrossALiveFilterChange) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    Settings settings = test_settings();
    settings.shadow.cascades.resolution = 512;  // quick on lavapipe
    ShadowSystem shadows(system_desc(settings));
    add_scene(shadows, box, ground);
    LightDesc spot;
    spot.type = LightType::Spot;
    spot.position = {-4.0f, 6.0f, 3.0f};
    spot.direction = {4.0f, -6.0f, -3.0f};
    spot.outer_angle_degrees = 40.0f;
    spot.inner_angle_degrees = 30.0f;
    const LightDesc lights[] = {{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}}, spot};
    shadows.set_lights(lights);

    constexpr uint32_t kProbeSize = 80;  // pixels per side over the top-down view's ground
    constexpr size_t kPixels = size_t{kProbeSize} * kProbeSize;
    ForwardProbe probe(device_, shadows.descriptor_set_layout(), kPixels);
    probe.respecialise(shadows.shader_specialization(0));
    const ProbeConstants constants{kCameraHeight * std::tan(glm::radians(30.0f)), kProbeSize, 1};
    ViewDesc view = top_down_view();
    view.sampling_frame = 0;
    // Two filters whose taps the specialization counts (the others cost lavapipe about a
    // minute each to compile at their first dispatch on CI's 2 cores).
    for (const ShadowFilter filter : {ShadowFilter::Poisson, ShadowFilter::Pcss}) {
        SCOPED_TRACE(choice_name(kShadowFilterChoices, filter));
        settings.shadow.filter.mode = filter;
        if (shadows.update_settings(settings).shader_specialization_changed) {
            probe.respecialise(shadows.shader_specialization(0));
        }
        const FrameInfo& frame = shadows.prepare(view);
        submit([&](VkCommandBuffer cmd) {
            shadows.record_shadow_maps(cmd);
            probe.record(cmd, frame.descriptor_set, constants);
        });
        const std::vector<float> specialised = probe.specialised(kPixels);
        const std::vector<float> from_uniforms = probe.from_uniforms(kPixels);
        float largest = 0.0f;
        size_t sun_shadowed = 0, spot_shadowed = 0;
        for (size_t i = 0; i < specialised.size(); ++i) {
            largest = std::max(largest, std::abs(specialised[i] - from_uniforms[i]));
            (i % 2 == 0 ? sun_shadowed : spot_shadowed) += specialised[i] < 0.5f;
        }
        EXPECT_LE(largest, 1e-5f);
        // Both lights' shadows are there: the comparison is of two shadowed images.
        EXPECT_GT(sun_shadowed, 120u);
        EXPECT_GT(spot_shadowed, 50u);
    }
}

}  // namespace
}  // namespace penumbra::library_tests
