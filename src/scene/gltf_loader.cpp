#include "penumbra/scene/loader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <tuple>

#include <glm/gtc/quaternion.hpp>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"
#include "scene/mesh_tools.hpp"

namespace penumbra {
namespace {

// tinygltf's messages end in newlines and may hold several lines; an InputError is one line.
std::string one_line(const std::string& text) {
    std::string result;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            if (!result.empty() && result.back() != ' ') result += "; ";
        } else {
            result += c;
        }
    }
    while (!result.empty() && (result.back() == ' ' || result.back() == ';')) result.pop_back();
    return result.empty() ? "unknown error" : result;
}

// tinygltf hands an image's buffer view to the decoder without checking that the view lies
// inside its buffer; check first, then decode with tinygltf's stb_image loader (as RGBA8).
bool load_image_checked(tinygltf::Image* image, const int image_index, std::string* err, std::string* warn,
                        int required_width, int required_height, const unsigned char* bytes, int size,
                        void* model_being_loaded) {
    const auto* model = static_cast<const tinygltf::Model*>(model_being_loaded);
    if (image->bufferView >= 0) {
        // tinygltf has checked the view and buffer indices, not the byte range.
        const tinygltf::BufferView& view = model->bufferViews[static_cast<size_t>(image->bufferView)];
        const size_t buffer_size = model->buffers[static_cast<size_t>(view.buffer)].data.size();
        if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
            *err += "images[" + std::to_string(image_index) + "]: bufferView " + std::to_string(image->bufferView) +
                    " lies outside its buffer of " + std::to_string(buffer_size) + " bytes\n";
            return false;
        }
    }
    return tinygltf::LoadImageData(image, image_index, err, warn, required_width, required_height, bytes, size,
                                   nullptr);
}

std::string lowercase_extension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

tinygltf::Model read_gltf_model(const std::filesystem::path& file, const std::string& origin) {
    const std::string extension = lowercase_extension(file);
    if (extension != ".gltf" && extension != ".glb") {
        throw InputError(origin + ": unsupported model extension \"" + extension + "\" (expected .gltf or .glb)");
    }
    std::error_code error;
    if (!std::filesystem::exists(file, error)) throw InputError(origin + ": file not found");
    if (!std::filesystem::is_regular_file(file, error)) throw InputError(origin + ": not a regular file");
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    loader.SetImageLoader(load_image_checked, &model);
    std::string errors;
    std::string warnings;
    const bool loaded = extension == ".glb" ? loader.LoadBinaryFromFile(&model, &errors, &warnings, file.string())
                                            : loader.LoadASCIIFromFile(&model, &errors, &warnings, file.string());
    if (!loaded) throw InputError(origin + ": cannot load glTF: " + one_line(errors.empty() ? warnings : errors));
    return model;
}

bool all_finite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double value) { return std::isfinite(value); });
}

// Turns the node tree into instances: one per (mesh primitive, node, placement).
class GltfImporter {
public:
    GltfImporter(Scene& scene, const GltfSource& source) : scene_(scene), source_(source) {}

    void place_model(const std::vector<glm::mat4>& placements) {
        std::vector<int> ancestors;
        for (int root : root_nodes()) collect_node(root, glm::mat4{1.0f}, ancestors);
        for (const glm::mat4& placement : placements) {
            for (const auto& [mesh, model_transform] : placed_meshes_) place_mesh(mesh, placement * model_transform);
        }
    }

private:
    const tinygltf::Model& model() const { return source_.model; }

    // The default scene's roots; without scenes, every node that is nobody's child.
    std::vector<int> root_nodes() const {
        if (!model().scenes.empty()) {
            const int scene = model().defaultScene >= 0 ? model().defaultScene : 0;
            if (static_cast<size_t>(scene) >= model().scenes.size()) {
                source_.fail("scene", "scene " + std::to_string(scene) + " does not exist");
            }
            return model().scenes[static_cast<size_t>(scene)].nodes;
        }
        std::vector<bool> is_child(model().nodes.size(), false);
        for (const tinygltf::Node& node : model().nodes) {
            for (int child : node.children) {
                if (child >= 0 && static_cast<size_t>(child) < is_child.size()) {
                    is_child[static_cast<size_t>(child)] = true;
                }
            }
        }
        std::vector<int> roots;
        for (size_t i = 0; i < is_child.size(); ++i) {
            if (!is_child[i]) roots.push_back(static_cast<int>(i));
        }
        return roots;
    }

    void collect_node(int index, const glm::mat4& parent_transform, std::vector<int>& ancestors) {
        const std::string where = "nodes[" + std::to_string(index) + "]";
        if (index < 0 || static_cast<size_t>(index) >= model().nodes.size()) {
            source_.fail(where,
                         "node does not exist (the file has " + std::to_string(model().nodes.size()) + " nodes)");
        }
        if (std::find(ancestors.begin(), ancestors.end(), index) != ancestors.end()) {
            source_.fail(where, "node is its own ancestor (the node hierarchy has a cycle)");
        }
        const tinygltf::Node& node = model().nodes[static_cast<size_t>(index)];
        const glm::mat4 transform = parent_transform * local_transform(node, where);
        if (node.mesh >= 0) placed_meshes_.emplace_back(node.mesh, transform);
        ancestors.push_back(index);
        for (int child : node.children) collect_node(child, transform, ancestors);
        ancestors.pop_back();
    }

    // glTF: a column-major matrix, or translation * rotation * scale.
    glm::mat4 local_transform(const tinygltf::Node& node, const std::string& where) const {
        if (!all_finite(node.matrix) || !all_finite(node.translation) || !all_finite(node.rotation) ||
            !all_finite(node.scale)) {
            source_.fail(where, "transform holds a non-finite number");
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

    void place_mesh(int mesh, const glm::mat4& world) {
        if (mesh < 0 || static_cast<size_t>(mesh) >= model().meshes.size()) {
            source_.fail("meshes[" + std::to_string(mesh) + "]",
                         "mesh does not exist (the file has " + std::to_string(model().meshes.size()) + " meshes)");
        }
        // A mirroring transform turns counter-clockwise triangles clockwise; such placements
        // get a copy of the mesh with reversed winding so front faces stay CCW in the world.
        const bool mirrored = glm::determinant(glm::mat3{world}) < 0.0f;
        const size_t primitive_count = model().meshes[static_cast<size_t>(mesh)].primitives.size();
        for (size_t primitive = 0; primitive < primitive_count; ++primitive) {
            const std::optional<uint32_t> scene_mesh = convert_mesh(mesh, static_cast<int>(primitive), mirrored);
            if (scene_mesh) scene_.instances.push_back({*scene_mesh, world});
        }
    }

    std::optional<uint32_t> convert_mesh(int mesh, int primitive_index, bool mirrored) {
        const auto key = std::make_tuple(mesh, primitive_index, mirrored);
        if (const auto found = converted_meshes_.find(key); found != converted_meshes_.end()) return found->second;
        const tinygltf::Primitive& primitive =
            model().meshes[static_cast<size_t>(mesh)].primitives[static_cast<size_t>(primitive_index)];
        const std::string where =
            "meshes[" + std::to_string(mesh) + "].primitives[" + std::to_string(primitive_index) + "]";
        std::optional<Mesh> converted = convert_gltf_primitive(source_, primitive, where);
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
        const tinygltf::PbrMetallicRoughness& pbr = gltf.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() != 4 || !all_finite(pbr.baseColorFactor)) {
            source_.fail(material_where + ".pbrMetallicRoughness.baseColorFactor", "expected 4 finite numbers");
        }
        Material material;
        material.base_color = {pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                               pbr.baseColorFactor[3]};
        if (pbr.baseColorTexture.index >= 0) {
            material.base_color_texture =
                convert_texture(pbr.baseColorTexture.index, material_where + ".pbrMetallicRoughness.baseColorTexture");
        }
        material.alpha_mode = read_alpha_mode(gltf.alphaMode, material_where + ".alphaMode");
        material.alpha_cutoff = static_cast<float>(gltf.alphaCutoff);
        material.double_sided = gltf.doubleSided;
        material.roughness = std::clamp(static_cast<float>(pbr.roughnessFactor), 0.0f, 1.0f);
        material.metallic = std::clamp(static_cast<float>(pbr.metallicFactor), 0.0f, 1.0f);
        return material;
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
        if (const auto found = converted_images_.find(image); found != converted_images_.end()) return found->second;
        const auto scene_index = static_cast<int32_t>(scene_.textures.size());
        scene_.textures.push_back(convert_gltf_image(source_, model().images[static_cast<size_t>(image)],
                                                     "images[" + std::to_string(image) + "]"));
        converted_images_.emplace(image, scene_index);
        return scene_index;
    }

    Scene& scene_;
    const GltfSource& source_;
    std::vector<std::pair<int, glm::mat4>> placed_meshes_;  // (mesh, model-space transform)
    std::map<std::tuple<int, int, bool>, std::optional<uint32_t>> converted_meshes_;
    std::map<int, uint32_t> converted_materials_;
    std::map<int, int32_t> converted_images_;
};

}  // namespace

void append_gltf(Scene& scene, const std::filesystem::path& file, const std::vector<glm::mat4>& placements) {
    const std::string origin = file.string();
    const tinygltf::Model model = read_gltf_model(file, origin);
    const GltfSource source{model, origin};
    // On error, leave the scene as it was rather than half-appended.
    const size_t texture_count = scene.textures.size();
    const size_t material_count = scene.materials.size();
    const size_t mesh_count = scene.meshes.size();
    const size_t instance_count = scene.instances.size();
    try {
        GltfImporter(scene, source).place_model(placements);
    } catch (...) {
        scene.textures.resize(texture_count);
        scene.materials.resize(material_count);
        scene.meshes.resize(mesh_count);
        scene.instances.resize(instance_count);
        throw;
    }
}

}  // namespace penumbra
