#include "renderer/gpu_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <span>
#include <string>
#include <tuple>

#include "penumbra/errors.hpp"
#include "renderer/math_conversions.hpp"
#include "renderer/shader_interface.hpp"

namespace penumbra::renderer {
namespace {

template <typename T>
std::span<const std::byte> as_bytes(const std::vector<T>& values) {
    return std::as_bytes(std::span<const T>(values));
}

}  // namespace

GpuScene::GpuScene(const AppContext& context, const Scene& scene, ShadowSystem& shadows) {
    const std::vector<MeshRange> ranges = upload_geometry(context, scene);
    create_materials(context, scene);
    add_draws(context, scene, ranges);
    add_shadow_casters(scene, ranges, shadows);
}

std::vector<GpuScene::MeshRange> GpuScene::upload_geometry(const AppContext& context, const Scene& scene) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<MeshRange> ranges;
    for (const Mesh& mesh : scene.meshes) {
        MeshRange range{static_cast<uint32_t>(indices.size()),
                        static_cast<uint32_t>(mesh.indices.size()),
                        static_cast<int32_t>(vertices.size()),
                        {}};
        vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
        indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
        // The mesh's triangles in clusters (reordered in place: every pass draws the same
        // triangles, and the depth test keeps the same nearest surface).
        std::vector<Vec3> positions(mesh.vertices.size());
        for (size_t v = 0; v < positions.size(); ++v) positions[v] = to_vec3(mesh.vertices[v].position);
        range.clusters =
            build_mesh_clusters(positions, std::span<uint32_t>(indices).subspan(range.first_index, range.index_count));
        ranges.push_back(std::move(range));
    }
    vertices_ = gpu::create_buffer_with_data(context.one_time(), as_bytes(vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    indices_ = gpu::create_buffer_with_data(context.one_time(), as_bytes(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    draw_data_.vertex_buffer = vertices_.get();
    draw_data_.index_buffer = indices_.get();
    return ranges;
}

// Front to back by distance bands (each twice as far as the one before, from 1 m), and by
// material within a band: the depth test still rejects most hidden fragments (within
// 0.1-0.3 ms of an exact-distance order on an H100, docs/PERFORMANCE.md), and consecutive
// draws mostly keep their material, so recording rebinds it rarely (an exact-distance order
// alternates the forest's trunk and crown materials at every draw).
void GpuScene::order_draws_front_to_back(const glm::vec3& eye) {
    struct Key {
        int band;
        uint32_t material;
        float distance_squared;
        uint32_t index;
        bool operator<(const Key& other) const {
            return std::tie(band, material, distance_squared, index) <
                   std::tie(other.band, other.material, other.distance_squared, other.index);
        }
    };
    std::vector<Key> keys;
    keys.reserve(draw_data_.draws.size());
    for (uint32_t i = 0; i < draw_data_.draws.size(); ++i) {
        const Draw& draw = draw_data_.draws[i];
        const glm::vec3 to_draw = draw.centre - eye;
        const float distance_squared = glm::dot(to_draw, to_draw);
        const int band = static_cast<int>(std::floor(0.5f * std::log2(std::max(distance_squared, 1.0f))));
        keys.push_back({band, draw.material, distance_squared, i});
    }
    std::sort(keys.begin(), keys.end());
    std::vector<uint32_t> order;
    order.reserve(keys.size());
    for (const Key& key : keys) order.push_back(key.index);
    build_batches(order);
}

// Runs of the order that share mesh, material and shadow receiving become one instanced
// draw: the forest's 30,001 draws are a few hundred batches, so recording a camera pass
// costs the CPU little (issue 14's CPU goal) while the order stays front to back.
void GpuScene::build_batches(const std::vector<uint32_t>& order) {
    auto* slots = static_cast<uint32_t*>(instance_slots_.mapped);
    uint32_t slot = 0;
    for (const bool double_sided : {false, true}) {
        std::vector<DrawBatch>& batches = draw_data_.batches[double_sided ? 1 : 0];
        batches.clear();
        const Draw* previous = nullptr;
        for (const uint32_t index : order) {
            const Draw& draw = draw_data_.draws[index];
            if (draw_data_.materials[draw.material].double_sided != double_sided) continue;
            const bool same_batch = previous && previous->mesh == draw.mesh && previous->material == draw.material &&
                                    previous->receive_shadows == draw.receive_shadows;
            if (same_batch) {
                ++batches.back().count;
            } else {
                batches.push_back({index, slot, 1});
            }
            slots[slot++] = index;
            previous = &draw;
        }
    }
}

void GpuScene::write_draw_model(uint32_t draw) {
    std::memcpy(static_cast<std::byte*>(draw_models_.mapped) + size_t{draw} * sizeof(glm::mat4),
                &draw_data_.draws[draw].model, sizeof(glm::mat4));
}

void GpuScene::add_draws(const AppContext& context, const Scene& scene, const std::vector<MeshRange>& ranges) {
    for (const Mesh& mesh : scene.meshes) mesh_centres_.push_back(0.5f * (mesh.bounds.min + mesh.bounds.max));
    instance_draws_.assign(scene.instances.size(), std::nullopt);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const MeshRange& range = ranges.at(instance.mesh);
        if (range.index_count == 0) continue;
        instance_draws_[i] = static_cast<uint32_t>(draw_data_.draws.size());
        Draw draw;
        draw.first_index = range.first_index;
        draw.index_count = range.index_count;
        draw.vertex_offset = range.vertex_offset;
        draw.material = scene.meshes[instance.mesh].material;
        draw.model = instance.world;
        draw.receive_shadows = instance.receive_shadows;
        draw.centre = glm::vec3(instance.world * glm::vec4(mesh_centres_[instance.mesh], 1.0f));
        draw.mesh = instance.mesh;
        draw_data_.draws.push_back(draw);
    }
    const size_t draws = std::max<size_t>(draw_data_.draws.size(), 1);
    draw_models_ = gpu::create_buffer(context, draws * sizeof(glm::mat4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                      gpu::MemoryKind::HostUpload);
    instance_slots_ = gpu::create_buffer(context, draws * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         gpu::MemoryKind::HostUpload);
    draw_data_.draw_models = draw_models_.get();
    draw_data_.instance_draws = instance_slots_.get();
    std::vector<uint32_t> order;  // the scene's, until the first order_draws_front_to_back()
    for (uint32_t d = 0; d < draw_data_.draws.size(); ++d) {
        write_draw_model(d);
        order.push_back(d);
    }
    build_batches(order);
}

void GpuScene::move_instance(size_t instance, const glm::mat4& world, ShadowSystem& shadows) {
    if (instance >= instance_draws_.size()) {
        throw InputError("move_instance: instance " + std::to_string(instance) + " is not in the scene (" +
                         std::to_string(instance_draws_.size()) + " instances)");
    }
    if (instance_draws_[instance]) {
        Draw& draw = draw_data_.draws[*instance_draws_[instance]];
        draw.model = world;
        draw.centre = glm::vec3(world * glm::vec4(mesh_centres_[draw.mesh], 1.0f));
        write_draw_model(*instance_draws_[instance]);
    }
    if (instance_casters_[instance]) shadows.set_instance_transform(*instance_casters_[instance], to_mat4(world));
}

namespace {

VkSamplerAddressMode address_mode(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case TextureWrap::MirroredRepeat:
            return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        case TextureWrap::Repeat:
            break;
    }
    return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

// The texture's own sampler (glTF wrapS/wrapT and filter): the lighting pass, the shadow
// passes and the ray-traced reference all read the alpha the same way.
gpu::SamplerDesc sampler_desc(const Texture& texture) {
    gpu::SamplerDesc desc;
    desc.filter = texture.nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
    desc.address = address_mode(texture.wrap_u);
    desc.address_v = address_mode(texture.wrap_v);
    return desc;
}

// The loader bounds a texture's pixels (LoadBudget), not its sides: one wider or taller
// than the device's maxImageDimension2D (4096 on some devices, 16384 on most) would be
// invalid usage of vkCreateImage. It is refused, not downscaled: the user decides how to
// shrink it.
void check_texture_fits_device(const Texture& texture, size_t index, uint32_t max_dimension) {
    if (texture.width <= max_dimension && texture.height <= max_dimension) return;
    const std::string name = texture.origin.empty() ? "scene texture " + std::to_string(index) : texture.origin;
    throw InputError(name + ": " + std::to_string(texture.width) + " x " + std::to_string(texture.height) +
                     " texels exceed this device's maxImageDimension2D of " + std::to_string(max_dimension) +
                     " (refused, not downscaled)");
}

}  // namespace

void GpuScene::create_materials(const AppContext& context, const Scene& scene) {
    for (const Texture& texture : scene.textures) {
        check_texture_fits_device(texture, textures_.size(), context.properties().limits.maxImageDimension2D);
        textures_.push_back(
            gpu::create_texture_rgba8(context.one_time(), texture.width, texture.height, texture.rgba8));
        texture_samplers_.push_back(gpu::create_sampler(context, sampler_desc(texture)));
    }
    const std::array<uint8_t, 4> white{255, 255, 255, 255};
    textures_.push_back(gpu::create_texture_rgba8(context.one_time(), 1, 1, white));
    texture_samplers_.push_back(gpu::create_sampler(context, {}));

    const VkDescriptorSetLayoutBinding bindings[] = {
        {RENDERER_BINDING_BASE_COLOR_TEXTURE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
         VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {RENDERER_BINDING_EMISSIVE_TEXTURE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
         nullptr},
        {RENDERER_BINDING_METALLIC_ROUGHNESS_TEXTURE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
         VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {RENDERER_BINDING_OCCLUSION_TEXTURE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
         nullptr}};
    material_set_layout_ = gpu::create_descriptor_set_layout(context, bindings);
    draw_data_.material_set_layout = material_set_layout_;

    std::vector<Material> materials = scene.materials;
    if (materials.empty()) materials.emplace_back();  // a scene may have meshes but no materials
    const auto count = static_cast<uint32_t>(materials.size());
    const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                         static_cast<uint32_t>(std::size(bindings)) * count};
    descriptor_pool_ = gpu::create_descriptor_pool(context, count, {&pool_size, 1});

    for (const Material& material : materials) {
        MaterialBinding binding_data;
        binding_data.descriptor_set = gpu::allocate_descriptor_set(context, descriptor_pool_, material_set_layout_);
        const size_t texture_index = texture_slot(material.base_color_texture);
        const gpu::Image& texture = textures_[texture_index];
        const VkSampler sampler = texture_samplers_[texture_index];
        gpu::write_combined_image_sampler(context, binding_data.descriptor_set, RENDERER_BINDING_BASE_COLOR_TEXTURE,
                                          texture.view, sampler);
        const size_t emissive_index = texture_slot(material.emissive_texture);
        // Textures a material lacks read the white texel: factors times 1.
        const auto write_texture = [&](uint32_t binding, size_t slot) {
            gpu::write_combined_image_sampler(context, binding_data.descriptor_set, binding, textures_[slot].view,
                                              texture_samplers_[slot]);
        };
        write_texture(RENDERER_BINDING_EMISSIVE_TEXTURE, emissive_index);
        write_texture(RENDERER_BINDING_METALLIC_ROUGHNESS_TEXTURE, texture_slot(material.metallic_roughness_texture));
        write_texture(RENDERER_BINDING_OCCLUSION_TEXTURE, texture_slot(material.occlusion_texture));
        binding_data.texture_view = texture.view;
        binding_data.texture_sampler = sampler;
        binding_data.base_color = material.base_color;
        binding_data.has_texture = texture_index != white_texture_slot();
        binding_data.emissive = material.emissive;
        binding_data.has_emissive_texture = emissive_index != white_texture_slot();
        binding_data.occlusion_strength = material.occlusion_strength;
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

// Each mesh is the range of the shared buffers that the camera passes draw, positions and
// UVs read in place from the interleaved vertices; a masked material's texture is its alpha
// mask. A masked material without a texture has one alpha everywhere: it casts entirely or
// not at all, as the lighting pass shows it entirely or not at all.
void GpuScene::add_shadow_casters(const Scene& scene, const std::vector<MeshRange>& ranges, ShadowSystem& shadows) {
    std::vector<MeshId> ids(scene.meshes.size());
    std::vector<bool> casts(scene.meshes.size(), true);
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const MeshRange& range = ranges[m];
        if (range.index_count == 0) continue;
        const MaterialBinding& material = draw_data_.materials.at(scene.meshes[m].material);
        MeshDesc desc;
        desc.positions = {vertices_.get(), offsetof(Vertex, position), sizeof(Vertex), VK_FORMAT_R32G32B32_SFLOAT};
        desc.index_buffer = indices_.get();
        desc.index_offset = VkDeviceSize{range.first_index} * sizeof(uint32_t);
        desc.index_count = range.index_count;
        desc.vertex_offset = range.vertex_offset;
        desc.bounds = {to_vec3(scene.meshes[m].bounds.min), to_vec3(scene.meshes[m].bounds.max)};
        desc.clusters = range.clusters;
        if (material.alpha_masked && material.has_texture) {
            desc.uvs = VertexStream{vertices_.get(), offsetof(Vertex, uv), sizeof(Vertex), VK_FORMAT_R32G32_SFLOAT};
            desc.alpha_mask = AlphaMaskDesc{material.texture_view, material.texture_sampler, material.alpha_cutoff,
                                            std::clamp(material.base_color.a, 0.0f, 1.0f)};
        }
        casts[m] = !material.alpha_masked || material.has_texture || material.base_color.a >= material.alpha_cutoff;
        ids[m] = shadows.add_mesh(desc);
    }
    instance_casters_.assign(scene.instances.size(), std::nullopt);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        if (ranges.at(instance.mesh).index_count == 0) continue;
        const MaterialBinding& material = draw_data_.materials.at(scene.meshes[instance.mesh].material);
        uint32_t flags = kInstanceAlphaMasked;
        if (casts[instance.mesh] && instance.cast_shadows) flags |= kInstanceCastsShadows;
        if (material.double_sided) flags |= kInstanceDoubleSided;
        if (instance.dynamic) flags |= kInstanceDynamic;
        instance_casters_[i] = shadows.add_instance({ids[instance.mesh], to_mat4(instance.world), flags});
    }
}

}  // namespace penumbra::renderer
