#pragma once
// What passes draw: geometry buffers, materials (with their descriptor sets) and
// draws with world bounds for culling. Built by the renderer from a penumbra::Scene;
// passes only read it.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "core/bounds.hpp"
#include "core/glm_config.hpp"

namespace penumbra::passes {

struct MaterialBinding {
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;  // set PENUMBRA_SET_MATERIAL
    glm::vec4 base_color{1.0f};
    float alpha_cutoff = 0.5f;
    float roughness = 0.6f;
    float metallic = 0.0f;
    bool has_texture = false;
    bool alpha_masked = false;  // MASK, or BLEND cast and shaded as MASK
    bool double_sided = false;
};

struct Draw {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    int32_t vertex_offset = 0;
    uint32_t material = 0;  // index into DrawData::materials
    glm::mat4 model{1.0f};
    Aabb world_bounds;
};

struct DrawData {
    VkBuffer vertex_buffer = VK_NULL_HANDLE;  // penumbra::Vertex
    VkBuffer index_buffer = VK_NULL_HANDLE;   // uint32
    std::vector<MaterialBinding> materials;
    std::vector<Draw> draws;
    VkDescriptorSetLayout material_set_layout = VK_NULL_HANDLE;
};

}  // namespace penumbra::passes
