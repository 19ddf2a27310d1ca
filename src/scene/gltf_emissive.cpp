#include <algorithm>
#include <string>

#include "gltf_internal.hpp"

namespace penumbra {
namespace {

// KHR_materials_emissive_strength: a factor on emissiveFactor, so that HDR emission can go
// beyond the [0, 1] the core spec allows (default 1).
float emissive_strength(const GltfSource& source, const tinygltf::Material& material, const std::string& where) {
    const auto extension = material.extensions.find("KHR_materials_emissive_strength");
    if (extension == material.extensions.end() || !extension->second.Has("emissiveStrength")) return 1.0f;
    const tinygltf::Value& strength = extension->second.Get("emissiveStrength");
    const double value = strength.IsNumber() ? strength.GetNumberAsDouble() : -1.0;
    if (!within_float_math(value) || value < 0.0) {
        source.fail(where + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
                    "expected a finite number >= 0");
    }
    return static_cast<float>(value);
}

}  // namespace

GltfEmissive read_gltf_emissive(const GltfSource& source, int material_index) {
    const tinygltf::Material& material = source.model.materials[static_cast<size_t>(material_index)];
    const std::string where = "materials[" + std::to_string(material_index) + "]";
    GltfEmissive emissive;
    const std::vector<double>& factor = material.emissiveFactor;
    if (factor.size() != 3) source.fail(where + ".emissiveFactor", "expected 3 numbers");
    for (int i = 0; i < 3; ++i) {
        if (!within_float_math(factor[i]) || factor[i] < 0.0) {
            source.fail(where + ".emissiveFactor", "expected 3 finite numbers >= 0");
        }
        emissive.factor[i] = static_cast<float>(factor[i]);
    }
    emissive.factor *= emissive_strength(source, material, where);
    const tinygltf::TextureInfo& texture = material.emissiveTexture;
    emissive.texture =
        read_texture_reference(source, texture.index, texture.texCoord, texture.extensions, where + ".emissiveTexture");
    return emissive;
}

GltfTextureReference read_texture_reference(const GltfSource& source, int texture, int tex_coord,
                                            const tinygltf::ExtensionMap& extensions, const std::string& where) {
    GltfTextureReference reference;
    if (texture < 0) return reference;
    reference.texture = texture;
    reference.uv_set = std::max(tex_coord, 0);
    reference.where = where;
    const auto transform = extensions.find("KHR_texture_transform");
    if (transform != extensions.end()) {
        reference.uv_transform = read_texture_transform(source, transform->second,
                                                        where + ".extensions.KHR_texture_transform", reference.uv_set);
    }
    return reference;
}

}  // namespace penumbra
