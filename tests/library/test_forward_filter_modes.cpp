// Forward shaders may take the filter from the uniforms (PENUMBRA_FILTER_FROM_UNIFORMS) and
// never be rebuilt: through the filters, changed live with update_settings(), one such
// pipeline computes what a pipeline specialised with shader_specialization() computes, for
// the sun and a spot light (tests/library/shaders/forward_probe.comp). And HLSL shaders
// (penumbra/shadow.hlsl) compute what GLSL shaders compute (forward_probe.comp.hlsl).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <span>
#include <string>
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

// One shader of the probe: its SPIR-V, and whether its pipeline is specialised with
// ShadowSystem::shader_specialization() (else it reads the filter from the uniforms).
struct ProbeShader {
    std::span<const uint32_t> spirv;
    bool specialised;
};

// The probe's pipelines, one per shader, each with its own output.
class ForwardProbe {
public:
    ForwardProbe(const DeviceDesc& device, VkDescriptorSetLayout shadow_layout, size_t pixels,
                 std::vector<ProbeShader> shaders)
        : device_(device.device), pixels_(pixels), shaders_(std::move(shaders)) {
        const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                                   nullptr};
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = 1;
        set_info.pBindings = &binding;
        TEST_VK(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &output_layout_));
        const auto count = static_cast<uint32_t>(shaders_.size());
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, count};
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = count;
        pool_info.poolSizeCount = 1;
        pool_info.pPoolSizes = &size;
        TEST_VK(vkCreateDescriptorPool(device_, &pool_info, nullptr, &pool_));
        const std::array<VkDescriptorSetLayout, 2> layouts{shadow_layout, output_layout_};
        const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ProbeConstants)};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = static_cast<uint32_t>(layouts.size());
        layout_info.pSetLayouts = layouts.data();
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &range;
        TEST_VK(vkCreatePipelineLayout(device_, &layout_info, nullptr, &layout_));
        for (const ProbeShader& shader : shaders_) {
            outputs_.push_back(std::make_unique<HostBuffer>(device, VkDeviceSize{pixels} * sizeof(float) * 2,
                                                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
            output_sets_.push_back(output_set(*outputs_.back()));
            pipelines_.push_back(shader.specialised ? VK_NULL_HANDLE : create_pipeline(shader.spirv, nullptr));
        }
    }
    ~ForwardProbe() {
        for (const VkPipeline pipeline : pipelines_) vkDestroyPipeline(device_, pipeline, nullptr);
        vkDestroyPipelineLayout(device_, layout_, nullptr);
        vkDestroyDescriptorPool(device_, pool_, nullptr);
        vkDestroyDescriptorSetLayout(device_, output_layout_, nullptr);
    }
    ForwardProbe(const ForwardProbe&) = delete;
    ForwardProbe& operator=(const ForwardProbe&) = delete;

    // What the caller does when update_settings() says the specialization changed.
    void respecialise(const ShaderSpecialization& specialization) {
        const VkSpecializationInfo info = specialization.info();
        for (size_t i = 0; i < shaders_.size(); ++i) {
            if (!shaders_[i].specialised) continue;
            vkDestroyPipeline(device_, pipelines_[i], nullptr);
            pipelines_[i] = create_pipeline(shaders_[i].spirv, &info);
        }
    }

    void record(VkCommandBuffer cmd, VkDescriptorSet shadow_set, const ProbeConstants& constants) const {
        for (size_t i = 0; i < shaders_.size(); ++i) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[i]);
            const std::array<VkDescriptorSet, 2> sets{shadow_set, output_sets_[i]};
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 2, sets.data(), 0, nullptr);
            vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
            vkCmdDispatch(cmd, (constants.size + 7) / 8, (constants.size + 7) / 8, 1);
        }
        host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }

    // Shader `i`'s (sun, local light) visibility per pixel, interleaved.
    std::vector<float> output(size_t i) const {
        const auto* values = static_cast<const float*>(outputs_[i]->mapped);
        return {values, values + pixels_ * 2};
    }

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

    VkDevice device_;
    size_t pixels_;
    std::vector<ProbeShader> shaders_;
    std::vector<std::unique_ptr<HostBuffer>> outputs_;
    std::vector<VkDescriptorSet> output_sets_;
    std::vector<VkPipeline> pipelines_;
    VkDescriptorSetLayout output_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
};

// The largest difference between two probes' outputs, and how many pixels the first
// shadows for the sun and for the local light (so that a comparison is of shadowed images).
struct ProbeComparison {
    float largest = 0.0f;
    size_t sun_shadowed = 0;
    size_t local_shadowed = 0;
};

ProbeComparison compare_probes(const std::vector<float>& reference, const std::vector<float>& other) {
    ProbeComparison comparison;
    for (size_t i = 0; i < reference.size(); ++i) {
        comparison.largest = std::max(comparison.largest, std::abs(reference[i] - other[i]));
        (i % 2 == 0 ? comparison.sun_shadowed : comparison.local_shadowed) += reference[i] < 0.5f;
    }
    return comparison;
}

LightDesc probe_spot() {
    LightDesc spot;
    spot.type = LightType::Spot;
    spot.position = {-4.0f, 6.0f, 3.0f};
    spot.direction = {4.0f, -6.0f, -3.0f};
    spot.outer_angle_degrees = 40.0f;
    spot.inner_angle_degrees = 30.0f;
    return spot;
}

constexpr uint32_t kProbeSize = 80;  // pixels per side over the top-down view's ground
constexpr size_t kPixels = size_t{kProbeSize} * kProbeSize;

// The probe over what the top-down view from `camera_height` sees (60 degrees).
ProbeConstants probe_constants(float camera_height) {
    return {camera_height * std::tan(glm::radians(30.0f)), kProbeSize, 1};
}

using ForwardFilterModes = LibraryTest;

TEST_F(ForwardFilterModes, FromUniformsEqualsSpecialisedAcrossALiveFilterChange) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    Settings settings = test_settings();
    settings.shadow.cascades.resolution = 512;  // quick on lavapipe
    ShadowSystem shadows(system_desc(settings));
    add_scene(shadows, box, ground);
    const LightDesc lights[] = {{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                                probe_spot()};
    shadows.set_lights(lights);

    ForwardProbe probe(device_, shadows.descriptor_set_layout(), kPixels,
                       {{shaders::forward_probe_comp(), true}, {shaders::forward_probe_uniform_filter_comp(), false}});
    probe.respecialise(shadows.shader_specialization(0));
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
            probe.record(cmd, frame.descriptor_set, probe_constants(kCameraHeight));
        });
        const ProbeComparison comparison = compare_probes(probe.output(0), probe.output(1));
        EXPECT_LE(comparison.largest, 1e-5f);
        // Both lights' shadows are there: the comparison is of two shadowed images.
        EXPECT_GT(comparison.sun_shadowed, 120u);
        EXPECT_GT(comparison.local_shadowed, 50u);
    }
}

// penumbra/shadow.hlsl is penumbra/shadow.glsl's source through glslang's HLSL front end: the
// HLSL probe, specialised and reading the filter from the uniforms, gives the GLSL probe's
// visibility for the sun and a spot light, through the cascades and through the virtual
// shadow map (whose texels are read through the page table and the pool), with the
// filters whose paths differ most: pcf's weighted grid, PCSS's blocker search over the raw
// depth and its four-texel comparison at the receiver (a gather in GLSL, four texel reads
// in HLSL), and the moments of msm.
TEST_F(ForwardFilterModes, TheHlslLibraryGivesTheGlslLibrarysVisibility) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    const LightDesc lights[] = {{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                                probe_spot()};
    Settings settings = test_settings();
    settings.shadow.cascades.resolution = 512;  // quick on lavapipe
    settings.shadow.virtual_maps.pool_mib = 16;
    ShadowSystem shadows(system_desc(settings));
    add_scene(shadows, box, ground);
    shadows.set_lights(lights);
    ForwardProbe probe(device_, shadows.descriptor_set_layout(), kPixels,
                       {{shaders::forward_probe_comp(), true},
                        {shaders::forward_probe_comp_hlsl(), true},
                        {shaders::forward_probe_uniform_filter_comp_hlsl(), false}});
    ViewDesc view = top_down_view();
    view.sampling_frame = 0;
    struct Case {
        ShadowTechnique technique;
        ShadowFilter filter;
    };
    for (const Case& test_case :
         {Case{ShadowTechnique::Cascades, ShadowFilter::Pcf}, Case{ShadowTechnique::Cascades, ShadowFilter::Msm},
          Case{ShadowTechnique::Virtual, ShadowFilter::Pcss}}) {
        SCOPED_TRACE(std::string(choice_name(kShadowTechniqueChoices, test_case.technique)) + " " +
                     std::string(choice_name(kShadowFilterChoices, test_case.filter)));
        settings.shadow.technique = test_case.technique;
        settings.shadow.filter.mode = test_case.filter;
        shadows.update_settings(settings);
        probe.respecialise(shadows.shader_specialization(0));
        const FrameInfo& frame = shadows.prepare(view);
        submit([&](VkCommandBuffer cmd) {
            if (test_case.technique == ShadowTechnique::Virtual) {
                shadows.record_page_marking(
                    cmd, record_ground_depth(cmd, view, nullptr, NormalEncoding::SignedFloat, nullptr));
            }
            shadows.record_shadow_maps(cmd);
            probe.record(cmd, frame.descriptor_set, probe_constants(kCameraHeight));
        });
        for (const size_t hlsl : {1u, 2u}) {
            SCOPED_TRACE(hlsl == 1 ? "specialised" : "filter from the uniforms");
            // The front ends order some float operations differently (glslang's HLSL matrix
            // products are vector-times-transposed-matrix): a few ulps in the projected
            // coordinates, 3.6e-5 at most in visibility on lavapipe; a wrong read or texel is
            // 1/16 of a tap and more.
            const ProbeComparison comparison = compare_probes(probe.output(0), probe.output(hlsl));
            EXPECT_LE(comparison.largest, 1e-4f);
            EXPECT_GT(comparison.sun_shadowed, 120u);
            EXPECT_GT(comparison.local_shadowed, 50u);
        }
    }
}

}  // namespace
}  // namespace penumbra::library_tests
