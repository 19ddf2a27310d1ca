#include "renderer/gpu_scene.hpp"

#include <array>
#include <cstddef>
#include <span>

#include "passes/shader_interface.hpp"

namespace penumbra::renderer {
namespace {

struct MeshRange {
    uint32_t first_index;
    uint32_t index_count;
    int32_t vertex_offset;
};

template <typename T>
std::span<const std::byte> as_bytes(const std::vector<T>& values) {
    return std::as_bytes(std::span<const T>(values));
}

}  // namespace

GpuScene::GpuScene(const gpu::Context& context, const Scene& scene) {
    upload_geometry(context, scene);
    create_materials(context, scene);
}

void GpuScene::upload_geometry(const gpu::Context& context, const Scene& scene) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<MeshRange> ranges;
    for (const Mesh& mesh : scene.meshes) {
        ranges.push_back({static_cast<uint32_t>(indices.size()), static_cast<uint32_t>(mesh.indices.size()),
                          static_cast<int32_t>(vertices.size())});
        vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
        indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    }
    vertices_ = gpu::create_buffer_with_data(context, as_bytes(vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    indices_ = gpu::create_buffer_with_data(context, as_bytes(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    draw_data_.vertex_buffer = vertices_.get();
    draw_data_.index_buffer = indices_.get();

    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes.at(instance.mesh);
        if (mesh.indices.empty()) continue;
        const MeshRange& range = ranges[instance.mesh];
        passes::Draw draw;
        draw.first_index = range.first_index;
        draw.index_count = range.index_count;
        draw.vertex_offset = range.vertex_offset;
        draw.material = mesh.material;
        draw.model = instance.world;
        draw.world_bounds = transform_aabb(mesh.bounds, instance.world);
        draw_data_.draws.push_back(draw);
    }
}

void GpuScene::create_materials(const gpu::Context& context, const Scene& scene) {
    for (const Texture& texture : scene.textures) {
        textures_.push_back(gpu::create_texture_rgba8(context, texture.width, texture.height, texture.rgba8));
    }
    const std::array<uint8_t, 4> white{255, 255, 255, 255};
    textures_.push_back(gpu::create_texture_rgba8(context, 1, 1, white));
    texture_sampler_ = gpu::create_sampler(context, {});

    const VkDescriptorSetLayoutBinding binding{PENUMBRA_BINDING_BASE_COLOR_TEXTURE,
                                               VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                               VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    material_set_layout_ = gpu::create_descriptor_set_layout(context, {&binding, 1});
    draw_data_.material_set_layout = material_set_layout_;

    std::vector<Material> materials = scene.materials;
    if (materials.empty()) materials.emplace_back();  // a scene may have meshes but no materials
    const auto count = static_cast<uint32_t>(materials.size());
    const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, count};
    descriptor_pool_ = gpu::create_descriptor_pool(context, count, {&pool_size, 1});

    for (const Material& material : materials) {
        passes::MaterialBinding binding_data;
        binding_data.descriptor_set = gpu::allocate_descriptor_set(context, descriptor_pool_, material_set_layout_);
        const bool has_texture = material.base_color_texture >= 0 &&
                                 material.base_color_texture < static_cast<int32_t>(scene.textures.size());
        const gpu::Image& texture = has_texture ? textures_[material.base_color_texture] : textures_.back();
        gpu::write_combined_image_sampler(context, binding_data.descriptor_set, PENUMBRA_BINDING_BASE_COLOR_TEXTURE,
                                          texture.view, texture_sampler_);
        binding_data.base_color = material.base_color;
        binding_data.has_texture = has_texture;
        // BLEND materials are drawn and cast alpha-tested at 0.5 (docs/techniques.md):
        // sorted transparency is out of scope and a shadow map stores one depth per texel.
        binding_data.alpha_masked = material.alpha_mode != AlphaMode::Opaque;
        binding_data.alpha_cutoff = material.alpha_mode == AlphaMode::Blend ? 0.5f : material.alpha_cutoff;
        binding_data.roughness = material.roughness;
        binding_data.metallic = material.metallic;
        binding_data.double_sided = material.double_sided;
        draw_data_.materials.push_back(binding_data);
    }
}

}  // namespace penumbra::renderer
