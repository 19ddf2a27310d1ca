#pragma once
// The depth and normal pre-pass of `--resolve deferred` (shaders/screen_prepass.frag): the
// reverse-Z depth and the world-space shading and face normals of every pixel, which Penumbra's
// compute resolve (ShadowSystem::record_visibility) reads and the lighting pass then
// shades over with an equal depth test. It draws with the lighting pass's vertex shader,
// culling, draw order and alpha test, so that both passes keep the same fragments.
#include <vulkan/vulkan.h>

#include <cstdint>

#include <glm/glm.hpp>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/shadow_system.hpp"
#include "renderer/draw_data.hpp"

namespace penumbra::renderer {

struct ScreenPrepassTargets {
    // R16G16B16A16_SFLOAT, world space, octahedral (NormalEncoding::Octahedral): xy the
    // shading normal, zw the face normal (the triangle's plane).
    gpu::Image normals;
    gpu::Image depth;  // D32_SFLOAT, reverse-Z (0: no geometry)
};

class ScreenPrepass {
public:
    // Set 0 is the renderer's frame set (the vertex shader reads the camera), set 1 the materials.
    ScreenPrepass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                  VkDescriptorSetLayout material_set_layout, uint32_t width, uint32_t height);

    const ScreenPrepassTargets& targets() const { return targets_; }

    // Renders every draw; leaves the normals in gpu::ImageState::ShaderSampled and the depth
    // in gpu::ImageState::DepthReadOnly, both ready for the resolve and the lighting pass.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data) const;

    // The pre-pass's images as the resolve's inputs, for the camera's world -> clip.
    ScreenInputs screen_inputs(const glm::mat4& view_projection) const;

private:
    const gpu::Device& device_;
    uint32_t width_;
    uint32_t height_;
    ScreenPrepassTargets targets_;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline single_sided_;  // back faces culled, as in the lighting pass
    gpu::UniquePipeline double_sided_;
};

}  // namespace penumbra::renderer
