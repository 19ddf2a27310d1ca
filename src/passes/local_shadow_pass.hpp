#pragma once
// Shadow-map depth pass of spot and point lights: renders the layers of one layered D32
// map (passes::create_depth_map) that holds every shadowed local light's layers (a spot:
// one; a point: six cube faces), each with its culled casters, reverse-Z, with the same
// slope-scaled depth bias as the sun's cascades. A light whose resolution is below the
// map's renders into the top-left resolution x resolution corner of its layers (the
// shader scales its UVs). The map belongs to the caller of the pass: it is resized as
// lights come and go, the pipelines stay.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "passes/caster_culling.hpp"
#include "passes/casters.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// One layer to render: its index, the texels per side it uses, the draws that may cast
// into it and the winding of faces toward the light in its projection. `keep`: the layer
// still holds what an earlier frame rendered for it (cached local shadows): not rendered.
// `gpu_culled`: the GPU culls its casters (layered strategy): `draws` is unused.
struct LocalShadowLayer {
    uint32_t layer = 0;
    uint32_t resolution = 0;
    DrawList draws;
    VkFrontFace facing_light = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool keep = false;
    bool gpu_culled = false;
};

class LocalShadowPass {
public:
    // Set 0 of its pipelines is `frame_set_layout` (PenumbraLocalShadows at binding
    // PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS), set 1 the alpha mask. `gpu_culling`: the
    // layered strategy's GPU-driven culling of the layers (throws DeviceError without its
    // features); `frames_in_flight` as ShadowPass's.
    LocalShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                    VkDescriptorSetLayout alpha_mask_set_layout, bool gpu_culling = false,
                    uint32_t frames_in_flight = 2);

    void prepare_pipelines(const VertexFormats& formats) { pipelines_.prepare(formats); }

    // Renders `layers` of `map` and leaves the map in ImageState::ShaderSampled. Without a
    // kept layer the map's earlier contents are discarded and the layers not listed are
    // cleared to "no caster"; with one, the map is loaded as the last frame left it
    // (ShaderSampled) and only the layers not kept are rendered (nothing at all when every
    // layer is kept). Layers marked gpu_culled are culled on the GPU first (every caster
    // into them when `cull` is off), then drawn from the culled commands.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                const std::vector<LocalShadowLayer>& layers, const gpu::Image& map, const BiasSettings& bias,
                CasterCulling culling, bool cull = true, uint64_t frame = 0);

    const GpuCasterCulling* gpu_culling() const { return gpu_culling_.get(); }

private:
    const gpu::Device& device_;
    std::unique_ptr<GpuCasterCulling> gpu_culling_;  // layered strategy only
    gpu::UniquePipelineLayout pipeline_layout_;
    CasterPipelines pipelines_;
};

}  // namespace penumbra::passes
