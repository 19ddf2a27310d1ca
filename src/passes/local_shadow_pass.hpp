#pragma once
// Shadow-map depth pass of spot and point lights. Owns one layered D32 map that holds
// every shadowed local light's layers (a spot: one; a point: six cube faces) and renders
// each layer with its culled casters, reverse-Z, with the same slope-scaled depth bias as
// the sun's cascades. A light whose resolution is below the map's renders into the
// top-left resolution x resolution corner of its layers (the shader scales its UVs).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "gpu/device.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "passes/draw_data.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// One layer to render: its index, the texels per side it uses and the draws that may cast into it.
struct LocalShadowLayer {
    uint32_t layer = 0;
    uint32_t resolution = 0;
    std::vector<uint32_t> draws;  // indices into DrawData::draws
};

class LocalShadowPass {
public:
    // A map of `layer_count` layers (at least 1) of `resolution` texels per side.
    LocalShadowPass(const gpu::Device& device, VkDescriptorSetLayout material_set_layout, uint32_t resolution,
                    uint32_t layer_count);

    // Set 0 of the pipelines: binding 0 = LocalLightUniforms (a storage buffer).
    VkDescriptorSetLayout set_layout() const { return set_layout_; }
    const gpu::Image& shadow_map() const { return shadow_map_; }

    // Renders `layers` (others are cleared to "no caster") and leaves the map ready for
    // fragment-shader sampling.
    void record(VkCommandBuffer cmd, VkDescriptorSet set, const DrawData& data,
                const std::vector<LocalShadowLayer>& layers, const BiasSettings& bias) const;

    // Without shadowed lights: only moves the map into the layout the lighting pass binds.
    void record_placeholder(VkCommandBuffer cmd) const;

private:
    const gpu::Device& device_;
    uint32_t resolution_;
    gpu::Image shadow_map_;
    gpu::UniqueDescriptorSetLayout set_layout_;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline opaque_;
    gpu::UniquePipeline masked_;
};

}  // namespace penumbra::passes
