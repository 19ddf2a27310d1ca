#include "penumbra/scene/loader.hpp"

#include <fnmatch.h>
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include <map>
#include <optional>
#include <regex>
#include <set>
#include <tuple>

#include <glm/gtc/quaternion.hpp>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"
#include "scene/mesh_tools.hpp"

namespace penumbra {
namespace {

// Finite, and within what the float math downstream carries (kMaxNumberMagnitude).
bool all_finite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), within_float_math);
}

// exclude_casters: a shell-style pattern ('*', '?', '[...]') against a node or mesh name;
// unnamed nodes and meshes match nothing.
bool name_matches(const std::string& pattern, const std::string& name) {
    return !name.empty() && ::fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}

// exclude_casters: "nodes[3]" or "meshes[0]" names an element by its index: the name
// Penumbra gives an unnamed node (Instance::name, the sky-box warning), taken as printed
// (as a shell pattern, "[3]" would be a character class).
struct IndexReference {
    bool node = false;  // else a mesh
    size_t index = 0;
};

std::optional<IndexReference> index_reference(const std::string& entry) {
    static const std::regex form(R"((nodes|meshes)\[([0-9]{1,9})\])");
    std::smatch match;
    if (!std::regex_match(entry, match, form)) return std::nullopt;
    return IndexReference{match[1] == "nodes", std::stoul(match[2].str())};
}

// A node that places a mesh, with its model-space transform.
struct PlacedMesh {
    int mesh = -1;
    int node = -1;
    glm::mat4 transform{1.0f};
};

// Turns the node tree into instances: one per (mesh primitive, node, placement).
class GltfImporter {
public:
    GltfImporter(Scene& scene, const GltfSource& source) : scene_(scene), source_(source) {}

    void place_model(const std::vector<glm::mat4>& placements, const GltfImportOptions& options, const GltfCost& held) {
        collect_nodes(checked_root_nodes(source_));
        refuse_too_many_instances(placements.size());
        refuse_over_budget(placements, held, options.budget);
        check_exclusion_patterns(options.exclude_casters);
        const size_t model_first = scene_.instances.size();
        for (size_t p = 0; p < placements.size(); ++p) {
            const size_t first = scene_.instances.size();
            for (const PlacedMesh& placed : placed_meshes_) place_mesh(placed, placements[p] * placed.transform);
            for (size_t i = first; i < scene_.instances.size(); ++i) {
                Instance& instance = scene_.instances[i];
                instance.cast_shadows = instance.cast_shadows &&
                                        (options.placement_casts.empty() || options.placement_casts.at(p)) &&
                                        !excluded_[i - model_first];
                instance.receive_shadows = options.placement_receives.empty() || options.placement_receives.at(p);
                instance.dynamic = !options.placement_dynamic.empty() && options.placement_dynamic.at(p);
                instance.origin.placement = static_cast<int32_t>(p);
            }
        }
        if (options.import_lights) append_gltf_lights(source_, placed_lights_, placements, scene_.lights);
    }

private:
    const tinygltf::Model& model() const { return source_.model; }

    // Every node under the roots with its model-space transform, depth first, without
    // recursion (a chain of nodes can be as deep as the file is long). The hierarchy was
    // checked to be a forest, so each node is reached once.
    void collect_nodes(const std::vector<int>& roots) {
        std::vector<std::pair<int, glm::mat4>> pending;
        for (auto root = roots.rbegin(); root != roots.rend(); ++root) pending.emplace_back(*root, glm::mat4{1.0f});
        while (!pending.empty()) {
            const auto [index, parent_transform] = pending.back();
            pending.pop_back();
            const tinygltf::Node& node = model().nodes[static_cast<size_t>(index)];
            const glm::mat4 transform =
                parent_transform * local_transform(node, "nodes[" + std::to_string(index) + "]");
            if (node.mesh >= 0) placed_meshes_.push_back({node.mesh, index, transform});
            if (const std::optional<int> light = punctual_light_of(source_, node, index)) {
                placed_lights_.push_back({*light, index, transform});
            }
            for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
                pending.emplace_back(*child, transform);
            }
        }
    }

    // Placements times the primitives the nodes place, before any is converted.
    void refuse_too_many_instances(size_t placement_count) const {
        size_t primitives = 0;
        for (const PlacedMesh& placed : placed_meshes_) {
            if (placed.mesh >= 0 && static_cast<size_t>(placed.mesh) < model().meshes.size()) {
                primitives += model().meshes[static_cast<size_t>(placed.mesh)].primitives.size();
            }
        }
        if (primitives > 0 && placement_count > kMaxGltfInstances / primitives) {
            source_.fail("nodes", std::to_string(placement_count) + " placement(s) of " + std::to_string(primitives) +
                                      " placed primitive(s) exceed " + std::to_string(kMaxGltfInstances) +
                                      " instances");
        }
    }

    // What placing the model will add to the scene, counted as place_mesh and convert_mesh
    // will convert it (a primitive once per mirroring and morph pose, drawn once per
    // placement) but from accessor counts only: placements times placed primitives is
    // bounded by kMaxGltfInstances, so this costs no more than the instances themselves.
    void refuse_over_budget(const std::vector<glm::mat4>& placements, const GltfCost& held,
                            const LoadBudget& budget) const {
        GltfCost added;
        for (const tinygltf::Image& image : model().images) {
            const uint64_t pixels = uint64_t(std::max(image.width, 0)) * uint64_t(std::max(image.height, 0));
            added.bytes = saturating_add(added.bytes, saturating_multiply(pixels, 4));
        }
        std::set<std::tuple<int, int, bool, std::vector<double>>> converted;
        for (const glm::mat4& placement : placements) {
            for (const PlacedMesh& placed : placed_meshes_) {
                if (placed.mesh < 0 || static_cast<size_t>(placed.mesh) >= model().meshes.size()) continue;
                const tinygltf::Mesh& mesh = model().meshes[static_cast<size_t>(placed.mesh)];
                const tinygltf::Node& node = model().nodes[static_cast<size_t>(placed.node)];
                const bool mirrored = glm::determinant(glm::mat3{placement * placed.transform}) < 0.0f;
                for (size_t p = 0; p < mesh.primitives.size(); ++p) {
                    const GltfCost cost = primitive_cost(model(), mesh.primitives[p]);
                    added.triangles = saturating_add(added.triangles, cost.triangles);
                    const std::vector<double> pose = mesh.primitives[p].targets.empty() ? std::vector<double>{}
                                                     : node.weights.empty()             ? mesh.weights
                                                                                        : node.weights;
                    if (cost.bytes > 0 && converted.emplace(placed.mesh, static_cast<int>(p), mirrored, pose).second) {
                        added.bytes = saturating_add(added.bytes, cost.bytes);
                    }
                }
            }
        }
        check_load_budget(source_, held, added, budget);
    }

    // glTF: a column-major matrix, or translation * rotation * scale.
    glm::mat4 local_transform(const tinygltf::Node& node, const std::string& where) const {
        if (!all_finite(node.matrix) || !all_finite(node.translation) || !all_finite(node.rotation) ||
            !all_finite(node.scale)) {
            source_.fail(where, "transform holds a number that is not finite or beyond 1e9 in magnitude");
        }
        if (node.matrix.size() == 16) {
            glm::mat4 matrix{1.0f};
            for (int i = 0; i < 16; ++i) matrix[i / 4][i % 4] = static_cast<float>(node.matrix[static_cast<size_t>(i)]);
            return matrix;
        }
        if (!node.matrix.empty() || (node.translation.size() != 0 && node.translation.size() != 3) ||
            (node.rotation.size() != 0 && node.rotation.size() != 4) ||
            (node.scale.size() != 0 && node.scale.size() != 3)) {
            source_.fail(where, "matrix, translation, rotation or scale has the wrong number of elements");
        }
        glm::mat4 transform{1.0f};
        if (!node.translation.empty()) {
            transform =
                glm::translate(transform, glm::vec3{node.translation[0], node.translation[1], node.translation[2]});
        }
        if (!node.rotation.empty()) {
            // glTF stores quaternions as (x, y, z, w); glm's constructor takes w first.
            const glm::quat rotation{static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                     static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2])};
            if (glm::length(rotation) > 0.0f) transform *= glm::mat4_cast(glm::normalize(rotation));
        }
        if (!node.scale.empty())
            transform = glm::scale(transform, glm::vec3{node.scale[0], node.scale[1], node.scale[2]});
        return transform;
    }

    void place_mesh(const PlacedMesh& placed, const glm::mat4& world) {
        const int mesh = placed.mesh;
        if (mesh < 0 || static_cast<size_t>(mesh) >= model().meshes.size()) {
            source_.fail("meshes[" + std::to_string(mesh) + "]",
                         "mesh does not exist (the file has " + std::to_string(model().meshes.size()) + " meshes)");
        }
        // A mirroring transform turns counter-clockwise triangles clockwise; such placements
        // get a copy of the mesh with reversed winding so front faces stay CCW in the world.
        const bool mirrored = glm::determinant(glm::mat3{world}) < 0.0f;
        const tinygltf::Mesh& gltf_mesh = model().meshes[static_cast<size_t>(mesh)];
        // glTF 2.0, 3.7.2.2: the node's weights, else the mesh's, pose the morph targets.
        const tinygltf::Node& node = model().nodes[static_cast<size_t>(placed.node)];
        const std::vector<double>& weights = node.weights.empty() ? gltf_mesh.weights : node.weights;
        if (!all_finite(weights)) {
            source_.fail("nodes[" + std::to_string(placed.node) + "]",
                         "morph target weights hold a number that is not finite or beyond 1e9 in magnitude");
        }
        for (size_t primitive = 0; primitive < gltf_mesh.primitives.size(); ++primitive) {
            const std::optional<uint32_t> scene_mesh =
                convert_mesh(mesh, static_cast<int>(primitive), mirrored, weights);
            if (!scene_mesh) continue;
            Instance instance{*scene_mesh, world};
            instance.name = node.name.empty() ? "nodes[" + std::to_string(placed.node) + "]" : node.name;
            instance.origin.type = "gltf";
            instance.origin.node = placed.node;
            instance.origin.mesh = mesh;
            instance.origin.primitive = static_cast<int32_t>(primitive);
            instance.origin.node_name = node.name;
            instance.origin.mesh_name = gltf_mesh.name;
            instance.cast_shadows = !unlit(gltf_mesh.primitives[primitive].material);
            scene_.instances.push_back(instance);
            excluded_.push_back(excludes(placed.node, mesh));
        }
    }

    std::optional<uint32_t> convert_mesh(int mesh, int primitive_index, bool mirrored,
                                         const std::vector<double>& weights) {
        const tinygltf::Primitive& primitive =
            model().meshes[static_cast<size_t>(mesh)].primitives[static_cast<size_t>(primitive_index)];
        // Nodes with different weights share a mesh without morph targets.
        const std::vector<double> pose = primitive.targets.empty() ? std::vector<double>{} : weights;
        const auto key = std::make_tuple(mesh, primitive_index, mirrored, pose);
        if (const auto found = converted_meshes_.find(key); found != converted_meshes_.end()) return found->second;
        const std::string where =
            "meshes[" + std::to_string(mesh) + "].primitives[" + std::to_string(primitive_index) + "]";
        GltfPrimitiveOptions options;
        options.morph_weights = pose;
        read_uv_mapping(primitive.material, options);
        std::optional<Mesh> converted = convert_gltf_primitive(source_, primitive, options, where);
        std::optional<uint32_t> scene_index;
        if (converted) {
            if (mirrored) reverse_winding(converted->indices);
            converted->material = convert_material(primitive.material, where + ".material");
            scene_index = static_cast<uint32_t>(scene_.meshes.size());
            scene_.meshes.push_back(std::move(*converted));
        }
        converted_meshes_.emplace(key, scene_index);
        return scene_index;
    }

    // KHR_materials_unlit: skies and backdrops, which a user does not expect to cast.
    bool unlit(int material) const {
        return material >= 0 && static_cast<size_t>(material) < model().materials.size() &&
               model().materials[static_cast<size_t>(material)].extensions.count("KHR_materials_unlit") > 0;
    }

    // Whether an exclude_casters entry names node `node` or mesh `mesh` (indices of the model).
    bool excludes(int node, int mesh) const {
        const std::string& node_name = model().nodes[static_cast<size_t>(node)].name;
        const std::string& mesh_name = model().meshes[static_cast<size_t>(mesh)].name;
        return std::any_of(exclusions_.begin(), exclusions_.end(), [&](const Exclusion& entry) {
            if (entry.reference)
                return entry.reference->index == static_cast<size_t>(entry.reference->node ? node : mesh);
            return name_matches(entry.pattern, node_name) || name_matches(entry.pattern, mesh_name);
        });
    }

    // Every entry must name something: a typo would otherwise leave the sky box casting.
    // Index references are parsed here, once, not per placed instance.
    void check_exclusion_patterns(const std::vector<std::string>& patterns) {
        exclusions_.clear();
        for (size_t i = 0; i < patterns.size(); ++i) {
            const std::string where = "exclude_casters[" + std::to_string(i) + "]";
            const std::optional<IndexReference> reference = index_reference(patterns[i]);
            exclusions_.push_back({patterns[i], reference});
            if (reference) {
                const size_t count = reference->node ? model().nodes.size() : model().meshes.size();
                if (reference->index >= count) {
                    source_.fail(where, "\"" + patterns[i] + "\" names no " + (reference->node ? "node" : "mesh") +
                                            " (the model has " + std::to_string(count) + ")");
                }
                continue;
            }
            const auto matches = [&](const std::string& name) { return name_matches(patterns[i], name); };
            const bool found = std::any_of(model().nodes.begin(), model().nodes.end(),
                                           [&](const tinygltf::Node& node) { return matches(node.name); }) ||
                               std::any_of(model().meshes.begin(), model().meshes.end(),
                                           [&](const tinygltf::Mesh& mesh) { return matches(mesh.name); });
            if (!found) {
                source_.fail(where, "\"" + patterns[i] + "\" matches no node or mesh name of the model");
            }
        }
    }

    // Where the material's base colour (alpha) texture is read: its textureInfo.texCoord
    // and KHR_texture_transform. Penumbra keeps one UV set per vertex, used by that texture
    // alone, so the transform is applied to the UVs at load.
    void read_uv_mapping(int material, GltfPrimitiveOptions& options) const {
        if (material < 0 || static_cast<size_t>(material) >= model().materials.size()) return;
        const BaseColorSource color = base_color_source(material);
        if (color.texture < 0) return;
        options.uv_set = color.tex_coord;
        if (color.transform == nullptr) return;
        options.uv_transform = read_texture_transform(
            source_, *color.transform, color.where + ".extensions.KHR_texture_transform", options.uv_set);
    }

    // Where a material's base colour (its alpha) comes from: pbrMetallicRoughness, or the
    // diffuse of KHR_materials_pbrSpecularGlossiness when the material has it (the
    // extension's rule: a client that reads it uses it).
    struct BaseColorSource {
        glm::vec4 factor{1.0f};
        int texture = -1;
        int tex_coord = 0;
        const tinygltf::Value* transform = nullptr;  // KHR_texture_transform of the texture
        std::string where;                           // the textureInfo's JSON path
    };

    BaseColorSource base_color_source(int index) const {
        const tinygltf::Material& gltf = model().materials[static_cast<size_t>(index)];
        const std::string material_where = "materials[" + std::to_string(index) + "]";
        BaseColorSource color;
        const auto spec_gloss = gltf.extensions.find("KHR_materials_pbrSpecularGlossiness");
        if (spec_gloss != gltf.extensions.end()) {
            read_diffuse(spec_gloss->second, material_where + ".extensions.KHR_materials_pbrSpecularGlossiness", color);
            return color;
        }
        const tinygltf::PbrMetallicRoughness& pbr = gltf.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() != 4 || !all_finite(pbr.baseColorFactor)) {
            source_.fail(material_where + ".pbrMetallicRoughness.baseColorFactor", "expected 4 finite numbers");
        }
        color.factor = {pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]};
        color.texture = pbr.baseColorTexture.index;
        color.tex_coord = std::max(pbr.baseColorTexture.texCoord, 0);
        const auto transform = pbr.baseColorTexture.extensions.find("KHR_texture_transform");
        if (transform != pbr.baseColorTexture.extensions.end()) color.transform = &transform->second;
        color.where = material_where + ".pbrMetallicRoughness.baseColorTexture";
        return color;
    }

    // diffuseFactor (default 1) and diffuseTexture {index, texCoord, extensions}.
    void read_diffuse(const tinygltf::Value& extension, const std::string& where, BaseColorSource& color) const {
        if (!extension.IsObject()) source_.fail(where, "expected an object");
        if (extension.Has("diffuseFactor")) {
            const tinygltf::Value& factor = extension.Get("diffuseFactor");
            const bool valid = factor.IsArray() && factor.ArrayLen() == 4 && [&] {
                for (int i = 0; i < 4; ++i) {
                    if (!factor.Get(i).IsNumber() || !within_float_math(factor.Get(i).GetNumberAsDouble()))
                        return false;
                }
                return true;
            }();
            if (!valid) source_.fail(where + ".diffuseFactor", "expected 4 finite numbers");
            for (int i = 0; i < 4; ++i) color.factor[i] = static_cast<float>(factor.Get(i).GetNumberAsDouble());
        }
        if (!extension.Has("diffuseTexture")) return;
        color.where = where + ".diffuseTexture";
        const tinygltf::Value& texture = extension.Get("diffuseTexture");
        if (!texture.IsObject() || !texture.Has("index") || !texture.Get("index").IsInt() ||
            texture.Get("index").GetNumberAsInt() < 0) {
            source_.fail(color.where, "expected a textureInfo with an index");
        }
        color.texture = texture.Get("index").GetNumberAsInt();
        if (texture.Has("texCoord")) {
            if (!texture.Get("texCoord").IsInt() || texture.Get("texCoord").GetNumberAsInt() < 0) {
                source_.fail(color.where + ".texCoord", "expected an index >= 0");
            }
            color.tex_coord = texture.Get("texCoord").GetNumberAsInt();
        }
        if (texture.Has("extensions") && texture.Get("extensions").Has("KHR_texture_transform")) {
            color.transform = &texture.Get("extensions").Get("KHR_texture_transform");
        }
    }

    uint32_t convert_material(int index, const std::string& where) {
        if (const auto found = converted_materials_.find(index); found != converted_materials_.end())
            return found->second;
        Material material;  // glTF's default material for primitives without one
        if (index >= 0) material = read_material(index, where);
        const auto scene_index = static_cast<uint32_t>(scene_.materials.size());
        scene_.materials.push_back(material);
        converted_materials_.emplace(index, scene_index);
        return scene_index;
    }

    Material read_material(int index, const std::string& where) {
        if (static_cast<size_t>(index) >= model().materials.size()) {
            source_.fail(where, "material " + std::to_string(index) + " does not exist");
        }
        const tinygltf::Material& gltf = model().materials[static_cast<size_t>(index)];
        const std::string material_where = "materials[" + std::to_string(index) + "]";
        const BaseColorSource color = base_color_source(index);
        Material material;
        material.base_color = color.factor;
        if (color.texture >= 0) material.base_color_texture = convert_texture(color.texture, color.where);
        material.alpha_mode = read_alpha_mode(gltf.alphaMode, material_where + ".alphaMode");
        material.alpha_cutoff = static_cast<float>(gltf.alphaCutoff);
        material.double_sided = gltf.doubleSided;
        read_shading(index, material);
        return material;
    }

    // Penumbra keeps one UV set per vertex, mapped for the base colour texture: another
    // texture read with other UVs cannot be shown, so it is left out with a warning (its
    // factors are kept).
    int32_t read_shading_texture(int material, const GltfTextureReference& reference) {
        if (reference.texture < 0) return -1;
        GltfPrimitiveOptions mesh_uvs;
        read_uv_mapping(material, mesh_uvs);
        if (reference.uv_set == mesh_uvs.uv_set && reference.uv_transform == mesh_uvs.uv_transform) {
            return convert_texture(reference.texture, reference.where);
        }
        scene_.warnings.push_back(source_.origin + ": " + reference.where +
                                  ": ignored (read with other texture coordinates or another "
                                  "KHR_texture_transform than the base colour texture)");
        return -1;
    }

    // The preview's shading inputs: metallic and roughness (pbrMetallicRoughness, or
    // KHR_materials_pbrSpecularGlossiness read as a dielectric of roughness 1 - glossiness),
    // occlusion and emission.
    void read_shading(int index, Material& material) {
        const tinygltf::Material& gltf = model().materials[static_cast<size_t>(index)];
        const std::string where = "materials[" + std::to_string(index) + "]";
        const auto spec_gloss = gltf.extensions.find("KHR_materials_pbrSpecularGlossiness");
        if (spec_gloss != gltf.extensions.end()) {
            material.metallic = 0.0f;
            material.roughness = 1.0f - glossiness(spec_gloss->second);
        } else {
            const tinygltf::PbrMetallicRoughness& pbr = gltf.pbrMetallicRoughness;
            material.roughness = std::clamp(static_cast<float>(pbr.roughnessFactor), 0.0f, 1.0f);
            material.metallic = std::clamp(static_cast<float>(pbr.metallicFactor), 0.0f, 1.0f);
            const tinygltf::TextureInfo& texture = pbr.metallicRoughnessTexture;
            material.metallic_roughness_texture = read_shading_texture(
                index, read_texture_reference(source_, texture.index, texture.texCoord, texture.extensions,
                                              where + ".pbrMetallicRoughness.metallicRoughnessTexture"));
        }
        const tinygltf::OcclusionTextureInfo& occlusion = gltf.occlusionTexture;
        material.occlusion_strength = std::clamp(static_cast<float>(occlusion.strength), 0.0f, 1.0f);
        material.occlusion_texture =
            read_shading_texture(index, read_texture_reference(source_, occlusion.index, occlusion.texCoord,
                                                               occlusion.extensions, where + ".occlusionTexture"));
        const GltfEmissive emissive = read_gltf_emissive(source_, index);
        material.emissive = emissive.factor;
        material.emissive_texture = read_shading_texture(index, emissive.texture);
    }

    // KHR_materials_pbrSpecularGlossiness' glossinessFactor (default 1), clamped to [0, 1].
    float glossiness(const tinygltf::Value& extension) const {
        if (!extension.IsObject() || !extension.Has("glossinessFactor")) return 1.0f;
        const tinygltf::Value& factor = extension.Get("glossinessFactor");
        return factor.IsNumber() ? std::clamp(static_cast<float>(factor.GetNumberAsDouble()), 0.0f, 1.0f) : 1.0f;
    }

    AlphaMode read_alpha_mode(const std::string& mode, const std::string& where) const {
        if (mode.empty() || mode == "OPAQUE") return AlphaMode::Opaque;
        if (mode == "MASK") return AlphaMode::Mask;
        if (mode == "BLEND") return AlphaMode::Blend;
        source_.fail(where, "unknown alphaMode \"" + mode + "\" (expected OPAQUE, MASK or BLEND)");
    }

    int32_t convert_texture(int texture, const std::string& where) {
        if (static_cast<size_t>(texture) >= model().textures.size()) {
            source_.fail(where, "texture " + std::to_string(texture) + " does not exist");
        }
        const int image = model().textures[static_cast<size_t>(texture)].source;
        if (image < 0 || static_cast<size_t>(image) >= model().images.size()) {
            source_.fail(where, "texture " + std::to_string(texture) + " has no PNG or JPEG image (source " +
                                    std::to_string(image) + ")");
        }
        const TextureSampling sampling = read_sampler(model().textures[static_cast<size_t>(texture)].sampler,
                                                      "textures[" + std::to_string(texture) + "].sampler");
        const auto key = std::make_tuple(image, sampling.wrap_u, sampling.wrap_v, sampling.nearest);
        if (const auto found = converted_images_.find(key); found != converted_images_.end()) return found->second;
        const auto scene_index = static_cast<int32_t>(scene_.textures.size());
        Texture converted = convert_gltf_image(source_, model().images[static_cast<size_t>(image)], image);
        converted.wrap_u = sampling.wrap_u;
        converted.wrap_v = sampling.wrap_v;
        converted.nearest = sampling.nearest;
        converted.origin = source_.origin + ": images[" + std::to_string(image) + "]";
        scene_.textures.push_back(std::move(converted));
        converted_images_.emplace(key, scene_index);
        return scene_index;
    }

    struct TextureSampling {
        TextureWrap wrap_u = TextureWrap::Repeat;
        TextureWrap wrap_v = TextureWrap::Repeat;
        bool nearest = false;
    };

    // glTF 2.0, 5.26: no sampler means repeat and a filter of the implementation's choice
    // (bilinear here).
    TextureSampling read_sampler(int index, const std::string& where) const {
        TextureSampling sampling;
        if (index < 0) return sampling;
        if (static_cast<size_t>(index) >= model().samplers.size()) {
            source_.fail(where, "sampler " + std::to_string(index) + " does not exist (the file has " +
                                    std::to_string(model().samplers.size()) + " samplers)");
        }
        const tinygltf::Sampler& sampler = model().samplers[static_cast<size_t>(index)];
        const std::string at = "samplers[" + std::to_string(index) + "]";
        sampling.wrap_u = read_wrap(sampler.wrapS, at + ".wrapS");
        sampling.wrap_v = read_wrap(sampler.wrapT, at + ".wrapT");
        const int filter = sampler.magFilter >= 0 ? sampler.magFilter : sampler.minFilter;
        sampling.nearest = filter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
                           filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                           filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
        return sampling;
    }

    TextureWrap read_wrap(int wrap, const std::string& where) const {
        switch (wrap) {
            case TINYGLTF_TEXTURE_WRAP_REPEAT:
                return TextureWrap::Repeat;
            case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
                return TextureWrap::ClampToEdge;
            case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
                return TextureWrap::MirroredRepeat;
            default:
                source_.fail(where, "unknown wrap mode " + std::to_string(wrap) +
                                        " (expected 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT or 10497 REPEAT)");
        }
    }

    Scene& scene_;
    const GltfSource& source_;
    std::vector<PlacedMesh> placed_meshes_;
    struct Exclusion {
        std::string pattern;
        std::optional<IndexReference> reference;  // set for "nodes[i]" / "meshes[j]"
    };
    std::vector<Exclusion> exclusions_;  // exclude_casters entries
    std::vector<bool> excluded_;         // per instance placed: its node or mesh matches a pattern
    std::vector<GltfPlacedLight> placed_lights_;
    // (mesh, primitive, mirrored, morph weights) -> scene mesh
    std::map<std::tuple<int, int, bool, std::vector<double>>, std::optional<uint32_t>> converted_meshes_;
    std::map<int, uint32_t> converted_materials_;
    std::map<std::tuple<int, TextureWrap, TextureWrap, bool>, int32_t> converted_images_;  // (image, sampling)
};

// The extensions the file lists (used or required) that Penumbra does not read, comma
// separated; KHR_lights_punctual counts as read only when its lights are imported.
std::string ignored_extensions(const tinygltf::Model& model, const GltfImportOptions& options) {
    static const char* const kRead[] = {"KHR_mesh_quantization",
                                        "KHR_texture_transform",
                                        "KHR_materials_unlit",
                                        "KHR_materials_pbrSpecularGlossiness",
                                        "KHR_materials_emissive_strength",
                                        "KHR_draco_mesh_compression",
                                        "EXT_meshopt_compression"};
    std::vector<std::string> listed = model.extensionsUsed;
    listed.insert(listed.end(), model.extensionsRequired.begin(), model.extensionsRequired.end());
    std::sort(listed.begin(), listed.end());
    listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
    std::string ignored;
    for (const std::string& name : listed) {
        const bool read = std::find(std::begin(kRead), std::end(kRead), name) != std::end(kRead) ||
                          (name == "KHR_lights_punctual" && options.import_lights);
        if (read) continue;
        ignored += (ignored.empty() ? "" : ", ") + name;
        if (name == "KHR_lights_punctual") ignored += " (import_lights = true reads its lights)";
    }
    return ignored;
}

}  // namespace

void append_gltf(Scene& scene, const std::filesystem::path& file, const std::vector<glm::mat4>& placements,
                 const GltfImportOptions& options) {
    const std::string origin = file.string();
    const GltfCost held = scene_cost(scene);
    const LoadBudget& budget = options.budget;
    const GltfImageAllowance images{budget.max_bytes > held.bytes ? budget.max_bytes - held.bytes : 0, budget.max_bytes,
                                    budget.max_bytes_name};
    tinygltf::Model model = read_gltf_model(file, origin, images);
    GltfDecodeAllowance decoded{images.bytes, images.max_bytes, images.budget_name};
    decode_compressed_geometry(model, origin, decoded);
    const GltfSource source{model, origin};
    // On error, leave the scene as it was rather than half-appended.
    const size_t texture_count = scene.textures.size();
    const size_t material_count = scene.materials.size();
    const size_t mesh_count = scene.meshes.size();
    const size_t instance_count = scene.instances.size();
    const size_t light_count = scene.lights.size();
    try {
        GltfImporter(scene, source).place_model(placements, options, held);
        warn_unloaded_images(source, scene.warnings);
        if (const std::string ignored = ignored_extensions(model, options); !ignored.empty()) {
            scene.warnings.push_back(origin + ": ignores the glTF extension(s) " + ignored);
        }
    } catch (...) {
        scene.textures.resize(texture_count);
        scene.materials.resize(material_count);
        scene.meshes.resize(mesh_count);
        scene.instances.resize(instance_count);
        scene.lights.resize(light_count);
        throw;
    }
}

}  // namespace penumbra
