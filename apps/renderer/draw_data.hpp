#pragma once
// What the renderer's camera passes (lighting, geometry AOVs) draw: geometry buffers,
// materials (with their descriptor sets) and draws. Built by GpuScene from a Scene.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra::renderer {

struct MaterialBinding {
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;  // set RENDERER_SET_MATERIAL
    VkImageView texture_view = VK_NULL_HANDLE;        // the base colour texture (or a white texel)
    VkSampler texture_sampler = VK_NULL_HANDLE;       // with the texture's wrap modes and filter
    glm::vec4 base_color{1.0f};
    float alpha_cutoff = 0.5f;
    float roughness = 0.6f;
    float metallic = 0.0f;
    glm::vec3 emissive{0.0f};         // emitted radiance, times the emissive texture when it has one
    float occlusion_strength = 1.0f;  // how much the occlusion texture (white: none) darkens ambient light
    bool has_texture = false;
    bool has_emissive_texture = false;
    bool alpha_masked = false;  // MASK, or BLEND cast and shaded as MASK
    bool double_sided = false;
};

struct Draw {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    int32_t vertex_offset = 0;
    uint32_t material = 0;  // index into DrawData::materials
    glm::mat4 model{1.0f};
    bool receive_shadows = true;
    glm::vec3 centre{0.0f};  // world space: the centre of the mesh's bounds, for sorting
    uint32_t mesh = 0;       // Scene::meshes index
};

// Consecutive draws of the frame's order (GpuScene::order_draws_front_to_back) with the same mesh, material and shadow
// receiving, drawn as one instanced draw: instance slots [first_instance, first_instance + count) of the frame's
// instance list name their draws.
struct DrawBatch {
    uint32_t draw = 0;  // the first draw (mesh, material, flags)
    uint32_t first_instance = 0;
    uint32_t count = 0;
};

struct DrawData {
    VkBuffer vertex_buffer = VK_NULL_HANDLE;  // penumbra::Vertex
    VkBuffer index_buffer = VK_NULL_HANDLE;   // uint32
    std::vector<MaterialBinding> materials;
    std::vector<Draw> draws;
    // What the camera passes draw, in order: single-sided materials ([0]), then double-sided
    // ones ([1]), each nearest first (GpuScene::order_draws_front_to_back), so that the depth
    // test rejects what lies behind before it is shaded; every camera pass of a frame draws
    // the same batches.
    std::vector<DrawBatch> batches[2];
    VkBuffer draw_models = VK_NULL_HANDLE;     // mat4 per draw (RENDERER_BINDING_DRAW_MODELS)
    VkBuffer instance_draws = VK_NULL_HANDLE;  // uint per instance slot (RENDERER_BINDING_INSTANCE_DRAWS)
    VkDescriptorSetLayout material_set_layout = VK_NULL_HANDLE;
};

}  // namespace penumbra::renderer
