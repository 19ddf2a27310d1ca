// KHR_texture_transform: offset, rotation and scale of a texture's coordinates. It decides
// which texels of an alpha mask cut a shadow, so it is applied, not ignored.
#include <cmath>

#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

// An optional [x, y] property (default `fallback`).
glm::vec2 read_pair(const GltfSource& source, const tinygltf::Value& object, const char* key, glm::vec2 fallback,
                    const std::string& where) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsArray() || value.ArrayLen() != 2 || !value.Get(0).IsNumber() || !value.Get(1).IsNumber() ||
        !within_float_math(value.Get(0).GetNumberAsDouble()) || !within_float_math(value.Get(1).GetNumberAsDouble())) {
        source.fail(where + "." + key, "expected 2 finite numbers");
    }
    return {static_cast<float>(value.Get(0).GetNumberAsDouble()), static_cast<float>(value.Get(1).GetNumberAsDouble())};
}

}  // namespace

glm::mat3 read_texture_transform(const GltfSource& source, const tinygltf::Value& extension, const std::string& where,
                                 int& uv_set) {
    if (!extension.IsObject()) source.fail(where, "expected an object");
    const glm::vec2 offset = read_pair(source, extension, "offset", glm::vec2{0.0f}, where);
    const glm::vec2 scale = read_pair(source, extension, "scale", glm::vec2{1.0f}, where);
    double rotation = 0.0;
    if (extension.Has("rotation")) {
        const tinygltf::Value& value = extension.Get("rotation");
        if (!value.IsNumber() || !within_float_math(value.GetNumberAsDouble())) {
            source.fail(where + ".rotation", "expected a finite number (radians)");
        }
        rotation = value.GetNumberAsDouble();
    }
    if (extension.Has("texCoord")) {
        const tinygltf::Value& value = extension.Get("texCoord");
        if (!value.IsInt() || value.GetNumberAsInt() < 0) source.fail(where + ".texCoord", "expected an index >= 0");
        uv_set = value.GetNumberAsInt();
    }
    // u' = cos u + sin v, v' = -sin u + cos v: counter-clockwise in glTF's UV space, where v
    // points down. The extension text's GLSL listing has the transpose, a known error
    // (KhronosGroup/glTF#1563); Babylon.js, three.js, Blender and the TextureTransformTest
    // sample model agree on this one.
    const auto c = static_cast<float>(std::cos(rotation));
    const auto s = static_cast<float>(std::sin(rotation));
    const glm::mat3 translation{1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, offset.x, offset.y, 1.0f};
    const glm::mat3 rotate{c, -s, 0.0f, s, c, 0.0f, 0.0f, 0.0f, 1.0f};
    const glm::mat3 scaling{scale.x, 0.0f, 0.0f, 0.0f, scale.y, 0.0f, 0.0f, 0.0f, 1.0f};
    return translation * rotate * scaling;
}

}  // namespace penumbra
