#include "passes/casters.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>

#include "passes/shader_interface.hpp"
#include "penumbra/gpu/check.hpp"

namespace penumbra::passes {
namespace {

constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;

gpu::VertexLayout caster_vertex_layout(const VertexFormats& formats) {
    gpu::VertexLayout layout;
    layout.dynamic_strides = true;  // each mesh brings its own strides
    layout.bindings.push_back({0, 0, VK_VERTEX_INPUT_RATE_VERTEX});
    layout.attributes.push_back({PENUMBRA_LOCATION_POSITION, 0, formats.position, 0});
    if (formats.uv != VK_FORMAT_UNDEFINED) {
        layout.bindings.push_back({1, 0, VK_VERTEX_INPUT_RATE_VERTEX});
        layout.attributes.push_back({PENUMBRA_LOCATION_UV, 1, formats.uv, 0});
    }
    return layout;
}

VkCullModeFlags cull_mode(CasterCulling culling, bool double_sided) {
    if (double_sided) return VK_CULL_MODE_NONE;
    switch (culling) {
        case CasterCulling::BackFaces:
            return VK_CULL_MODE_BACK_BIT;
        case CasterCulling::FrontFaces:
            return VK_CULL_MODE_FRONT_BIT;
        case CasterCulling::None:
            break;
    }
    return VK_CULL_MODE_NONE;
}

VkFrontFace flipped(VkFrontFace face) {
    return face == VK_FRONT_FACE_COUNTER_CLOCKWISE ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
}

// Binds what changes from one draw to the next, skipping what the previous draw bound.
bool same_stream(const VertexStream& a, const VertexStream& b) {
    return a.buffer == b.buffer && a.offset == b.offset && a.stride == b.stride;
}

// What is bound in the command buffer, so that draws of meshes sharing buffers (an engine's
// one big vertex and index buffer) bind nothing between them.
struct BoundState {
    VkPipeline pipeline = VK_NULL_HANDLE;
    int64_t mesh = -1;
    std::optional<VertexStream> positions;
    std::optional<VertexStream> uvs;
    VkBuffer index_buffer = VK_NULL_HANDLE;
    VkIndexType index_type = VK_INDEX_TYPE_MAX_ENUM;
    VkDescriptorSet alpha_mask = VK_NULL_HANDLE;
    VkCullModeFlags cull = ~0u;
    VkFrontFace front_face = VK_FRONT_FACE_MAX_ENUM;
};

void bind_mesh(const gpu::Device& device, VkCommandBuffer cmd, const CasterMesh& mesh, bool masked, BoundState& bound) {
    const bool positions_bound = bound.positions && same_stream(*bound.positions, mesh.positions);
    const bool uvs_bound = !masked || (bound.uvs && same_stream(*bound.uvs, mesh.uvs));
    if (!positions_bound || !uvs_bound) {
        const std::array<VkBuffer, 2> buffers{mesh.positions.buffer, mesh.uvs.buffer};
        const std::array<VkDeviceSize, 2> offsets{mesh.positions.offset, mesh.uvs.offset};
        const std::array<VkDeviceSize, 2> strides{mesh.positions.stride, mesh.uvs.stride};
        device->vkCmdBindVertexBuffers2(cmd, 0, masked ? 2u : 1u, buffers.data(), offsets.data(), nullptr,
                                        strides.data());
        bound.positions = mesh.positions;
        bound.uvs = masked ? std::optional<VertexStream>(mesh.uvs) : std::nullopt;
    }
    // Bound at offset 0: each draw starts at its mesh's first index (index_offset / size).
    if (mesh.index_buffer != bound.index_buffer || mesh.index_type != bound.index_type) {
        device->vkCmdBindIndexBuffer(cmd, mesh.index_buffer, 0, mesh.index_type);
        bound.index_buffer = mesh.index_buffer;
        bound.index_type = mesh.index_type;
    }
}

uint32_t first_index(const CasterMesh& mesh) {
    const VkDeviceSize index_size = mesh.index_type == VK_INDEX_TYPE_UINT16 ? 2 : 4;
    return static_cast<uint32_t>(mesh.index_offset / index_size);
}

}  // namespace

VertexFormats vertex_formats(const CasterMesh& mesh, bool masked) {
    return {mesh.positions.format, masked ? mesh.uvs.format : VK_FORMAT_UNDEFINED};
}

CasterPipelines::CasterPipelines(const gpu::Device& device, CasterPipelineTemplate pipeline_template)
    : device_(device), template_(std::move(pipeline_template)) {}

void CasterPipelines::prepare(const VertexFormats& formats) {
    if (pipelines_.contains(formats)) return;
    const bool masked = formats.uv != VK_FORMAT_UNDEFINED;
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, masked ? template_.masked_vertex : template_.opaque_vertex, {}});
    const std::span<const uint32_t> fragment = masked ? template_.masked_fragment : template_.opaque_fragment;
    if (!fragment.empty()) {
        desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, fragment, template_.fragment_specialization});
    }
    desc.vertex_layout = caster_vertex_layout(formats);
    desc.layout = template_.layout;
    desc.color_formats = template_.color_formats;
    desc.depth_format = template_.depth_format;
    desc.depth_compare = VK_COMPARE_OP_GREATER;  // reverse-Z: the caster nearest the light wins
    desc.cull_mode = VK_CULL_MODE_NONE;          // set per draw (CasterFaceCulling)
    desc.dynamic_culling = true;
    desc.depth_bias = template_.depth_bias;
    desc.depth_clamp = template_.depth_clamp;
    desc.view_mask = template_.view_mask;
    desc.viewport_count = template_.viewport_count;
    pipelines_.emplace(formats, gpu::create_graphics_pipeline(device_, desc));
}

VkPipeline CasterPipelines::get(const VertexFormats& formats) const {
    const auto found = pipelines_.find(formats);
    if (found == pipelines_.end()) {
        throw VulkanError("caster pipeline for vertex formats " + gpu::format_name(formats.position) + "/" +
                              gpu::format_name(formats.uv) + " was not prepared",
                          VK_ERROR_UNKNOWN);
    }
    return found->second;
}

namespace {

// Binds what `draw` needs that `bound` does not hold: its pipeline, mesh streams, alpha mask,
// face culling and winding.
void bind_draw_state(const gpu::Device& device, VkCommandBuffer cmd, const CasterPipelines& pipelines,
                     const CasterScene& scene, const CasterDraw& draw, const CasterFaceCulling& culling,
                     BoundState& bound) {
    const CasterMesh& mesh = scene.meshes[draw.mesh];
    // The pipeline depends on the mesh's vertex formats only: looked up per mesh change,
    // not per draw (a forest's thousands of draws share a few meshes).
    if (static_cast<int64_t>(draw.mesh) != bound.mesh) {
        const VkPipeline pipeline = pipelines.get(vertex_formats(mesh, draw.masked));
        if (pipeline != bound.pipeline) {
            device->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
            bound.pipeline = pipeline;
        }
        bind_mesh(device, cmd, mesh, draw.masked, bound);
        bound.mesh = draw.mesh;
    }
    if (draw.masked && mesh.alpha_mask_set != bound.alpha_mask) {
        device->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.layout(),
                                        PENUMBRA_SET_ALPHA_MASK, 1, &mesh.alpha_mask_set, 0, nullptr);
        bound.alpha_mask = mesh.alpha_mask_set;
    }
    const VkCullModeFlags cull = cull_mode(culling.mode, draw.double_sided);
    if (cull != bound.cull) {
        device->vkCmdSetCullMode(cmd, cull);
        bound.cull = cull;
    }
    const VkFrontFace front_face = draw.mirrored ? flipped(culling.facing_light) : culling.facing_light;
    if (front_face != bound.front_face) {
        device->vkCmdSetFrontFace(cmd, front_face);
        bound.front_face = front_face;
    }
}

void push_caster_constants(const gpu::Device& device, VkCommandBuffer cmd, const CasterPipelines& pipelines,
                           const shader::CasterPushConstants& constants) {
    device->vkCmdPushConstants(cmd, pipelines.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(constants), &constants);
}

}  // namespace

void record_caster_draws(const gpu::Device& device, VkCommandBuffer cmd, const CasterPipelines& pipelines,
                         const CasterScene& scene, const DrawList& list, uint32_t layer,
                         const CasterFaceCulling& culling, uint32_t tile) {
    BoundState bound;
    // Opaque casters first, then masked ones, so that each pipeline is bound about once.
    for (const bool masked_pass : {false, true}) {
        bound.mesh = -1;  // a masked draw binds the mesh's UVs too
        for (const uint32_t index : list) {
            const CasterDraw& draw = scene.draws[index];
            if (draw.masked != masked_pass) continue;
            bind_draw_state(device, cmd, pipelines, scene, draw, culling, bound);
            const CasterMesh& mesh = scene.meshes[draw.mesh];
            push_caster_constants(device, cmd, pipelines,
                                  {draw.model, layer, mesh.alpha_cutoff, mesh.alpha_scale, tile});
            device->vkCmdDrawIndexed(cmd, mesh.index_count, 1, first_index(mesh), mesh.vertex_offset, 0);
        }
    }
}

void record_indirect_caster_draws(const gpu::Device& device, VkCommandBuffer cmd, const CasterPipelines& pipelines,
                                  const CasterScene& scene, std::span<const CasterBucket> buckets, VkBuffer commands,
                                  uint32_t first_command, VkBuffer counts, uint32_t first_count,
                                  const CasterFaceCulling& culling, uint32_t layers_per_bucket) {
    constexpr VkDeviceSize kCommandSize = sizeof(VkDrawIndexedIndirectCommand);
    BoundState bound;
    for (size_t b = 0; b < buckets.size(); ++b) {
        const CasterBucket& bucket = buckets[b];
        const CasterDraw& draw = scene.draws[bucket.draw];
        bound.mesh = -1;  // a bucket's meshes share streams, but not necessarily the mesh
        bind_draw_state(device, cmd, pipelines, scene, draw, culling, bound);
        const CasterMesh& mesh = scene.meshes[draw.mesh];
        // The vertex shader reads the transform and layer per command (CullRecord).
        push_caster_constants(device, cmd, pipelines, {glm::mat4(1.0f), 0, mesh.alpha_cutoff, mesh.alpha_scale, 0});
        const VkDeviceSize first = first_command + VkDeviceSize{bucket.first_command} * layers_per_bucket;
        device->vkCmdDrawIndexedIndirectCount(cmd, commands, first * kCommandSize, counts,
                                              (first_count + b) * sizeof(uint32_t), bucket.capacity * layers_per_bucket,
                                              kCommandSize);
    }
}

gpu::Image create_depth_map(const gpu::Device& device, uint32_t resolution, uint32_t layers,
                            VkImageUsageFlags extra_usage) {
    gpu::ImageDesc desc;
    desc.format = kShadowFormat;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = std::max(layers, 1u);
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT | extra_usage;
    desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    desc.array_view = true;
    return gpu::create_image(device, desc);
}

CasterDepthBias caster_depth_bias(const gpu::Device& device, const BiasSettings& bias) {
    const bool clamped = device.depth_bias_clamp_supported() && bias.clamp > 0.0f;
    return {bias.slope, clamped ? bias.clamp : std::numeric_limits<float>::max()};
}

void set_shadow_depth_bias(const gpu::Device& device, VkCommandBuffer cmd, const BiasSettings& bias) {
    // Reverse-Z: pushing a caster away from the light lowers its depth, so every bias term
    // is negative (a negative clamp bounds the bias from below). Without the depthBiasClamp
    // feature the bias is unclamped.
    const float clamp = device.depth_bias_clamp_supported() ? -bias.clamp : 0.0f;
    device->vkCmdSetDepthBias(cmd, -bias.constant, clamp, -bias.slope);
}

void set_viewport_and_scissor(const gpu::Device& device, VkCommandBuffer cmd, uint32_t width, uint32_t height) {
    const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {width, height}};
    device->vkCmdSetViewport(cmd, 0, 1, &viewport);
    device->vkCmdSetScissor(cmd, 0, 1, &scissor);
}

gpu::UniqueDescriptorSetLayout create_alpha_mask_set_layout(const gpu::Device& device) {
    const VkDescriptorSetLayoutBinding binding{PENUMBRA_BINDING_ALPHA_MASK, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                               1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    return gpu::create_descriptor_set_layout(device, {&binding, 1});
}

VkPushConstantRange caster_push_constant_range() {
    return {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(shader::CasterPushConstants)};
}

}  // namespace penumbra::passes
