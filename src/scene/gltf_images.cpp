// One rule for a glTF's images that did not load (a missing file: tinygltf keeps going):
// an image Penumbra reads (a base colour or emissive texture of a placed primitive) stops
// the load with an error, every other one is named in a warning, with what refers to it,
// so that a model that lost its normal or occlusion maps is not silently accepted.
#include <string>

#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

// The material slots of glTF 2.0 (5.19) that hold a textureInfo.
void add_use(const tinygltf::Model& model, int texture, int image, const std::string& use, std::string& uses) {
    if (texture < 0 || static_cast<size_t>(texture) >= model.textures.size()) return;
    if (model.textures[static_cast<size_t>(texture)].source != image) return;
    uses += (uses.empty() ? "" : ", ") + use;
}

}  // namespace

std::string gltf_image_uses(const tinygltf::Model& model, int image) {
    std::string uses;
    for (size_t m = 0; m < model.materials.size(); ++m) {
        const tinygltf::Material& material = model.materials[m];
        const std::string of = " of materials[" + std::to_string(m) + "]";
        add_use(model, material.pbrMetallicRoughness.baseColorTexture.index, image, "baseColorTexture" + of, uses);
        add_use(model, material.pbrMetallicRoughness.metallicRoughnessTexture.index, image,
                "metallicRoughnessTexture" + of, uses);
        add_use(model, material.normalTexture.index, image, "normalTexture" + of, uses);
        add_use(model, material.occlusionTexture.index, image, "occlusionTexture" + of, uses);
        add_use(model, material.emissiveTexture.index, image, "emissiveTexture" + of, uses);
    }
    return uses.empty() ? "no material texture" : uses;
}

std::string gltf_image_name(const tinygltf::Model& model, int image) {
    const tinygltf::Image& entry = model.images.at(static_cast<size_t>(image));
    const std::string name = entry.uri.empty() || entry.uri.starts_with("data:") ? entry.name : entry.uri;
    return "images[" + std::to_string(image) + "]" + (name.empty() ? "" : " \"" + name + "\"");
}

void warn_unloaded_images(const GltfSource& source, std::vector<std::string>& warnings) {
    const tinygltf::Model& model = source.model;
    for (size_t i = 0; i < model.images.size(); ++i) {
        if (!model.images[i].image.empty()) continue;
        const int image = static_cast<int>(i);
        warnings.push_back(source.origin + ": " + gltf_image_name(model, image) +
                           " could not be read (missing file?); Penumbra does not use it (" +
                           gltf_image_uses(model, image) + ")");
    }
}

}  // namespace penumbra
