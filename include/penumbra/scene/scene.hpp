#pragma once
// The scene model of Penumbra's scene component (Penumbra::scene): what a TOML scene file,
// a glTF model or a built-in scene becomes once loaded (penumbra/scene/loader.hpp), as
// plain data with glm vectors. Nothing here needs Vulkan or a ShadowSystem; the tools'
// renderer uploads a Scene to its own buffers and hands them to one.
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/lights.hpp"

namespace penumbra {

// The largest magnitude of any number read from a scene, config file, flag or glTF node:
// Penumbra's math is 32-bit float, which still carries squares (lengths, dot products) of
// numbers up to 1e9 (1e18 < 3.4e38); beyond, a normalisation or a projection overflows and
// the image is silently wrong.
inline constexpr double kMaxNumberMagnitude = 1e9;

struct Aabb {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{std::numeric_limits<float>::lowest()};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    glm::vec3 center() const { return (min + max) * 0.5f; }
    glm::vec3 extent() const { return max - min; }

    void expand(const glm::vec3& point) {
        min = glm::min(min, point);
        max = glm::max(max, point);
    }
    void expand(const Aabb& other) {
        if (other.empty()) return;
        expand(other.min);
        expand(other.max);
    }

    std::array<glm::vec3, 8> corners() const {
        std::array<glm::vec3, 8> result{};
        for (int i = 0; i < 8; ++i) {
            result[i] = {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
        }
        return result;
    }
};

// Bounds of a box after an affine transform (Arvo's method: exact for the
// transformed corners, no loop over 8 points needed).
inline Aabb transform_aabb(const Aabb& box, const glm::mat4& transform) {
    if (box.empty()) return box;
    Aabb result;
    const glm::vec3 translation{transform[3]};
    result.min = translation;
    result.max = translation;
    for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) {
            const float a = transform[column][row] * box.min[column];
            const float b = transform[column][row] * box.max[column];
            result.min[row] += glm::min(a, b);
            result.max[row] += glm::max(a, b);
        }
    }
    return result;
}

struct Camera {
    glm::vec3 eye{0.0f, 6.0f, 12.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 60.0f;  // vertical field of view
    float near_plane = 0.1f;
    float far_plane = 200.0f;
};

struct Light {
    LightType type = LightType::Directional;
    glm::vec3 direction{-0.4f, -1.0f, -0.3f};  // travel direction (sun -> ground); normalised
    glm::vec3 position{0.0f};                  // spot and point lights
    glm::vec3 color{1.0f};
    float intensity = 3.0f;
    float angular_diameter_degrees = 0.53f;  // directional: the sun's disk
    bool cast_shadows = true;
    // Spot and point lights (docs/local-lights.md).
    float inner_angle_degrees = 20.0f;  // spot: full intensity inside (half-angle from the axis)
    float outer_angle_degrees = 30.0f;  // spot: zero outside; the shadow frustum's fov is twice this
    float range = 25.0f;                // metres: the light and its shadow end here
    float radius = 0.1f;                // metres: the light's size, for soft shadows (pcss)
    uint32_t shadow_resolution = 0;     // texels per side of its shadow map; 0 = the renderer's default
};

enum class AlphaMode { Opaque, Mask, Blend };

// How texture coordinates outside [0, 1] map to texels (glTF sampler wrapS / wrapT).
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

struct Texture {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba8;  // width * height * 4, sRGB-encoded colour, linear alpha
    // The sampler every pass (and the ray-traced reference) reads it with: textures have
    // one level, so glTF's magFilter (or minFilter's base filter) picks nearest or bilinear.
    TextureWrap wrap_u = TextureWrap::Repeat;
    TextureWrap wrap_v = TextureWrap::Repeat;
    bool nearest = false;
    // Where it came from, for messages ("model.gltf: images[0]"); empty for procedural ones.
    std::string origin;
};

struct Material {
    glm::vec4 base_color{1.0f};       // linear RGB + alpha
    int32_t base_color_texture = -1;  // index into Scene::textures, -1 for none
    AlphaMode alpha_mode = AlphaMode::Opaque;
    float alpha_cutoff = 0.5f;  // used by Mask; Blend casts as Mask with 0.5 (docs/techniques.md)
    bool double_sided = false;
    float roughness = 0.6f;
    float metallic = 0.0f;
    // Light the surface emits itself (linear RGB radiance, unaffected by shadows): glTF's
    // emissiveFactor x KHR_materials_emissive_strength, times emissive_texture where set
    // (read with the mesh's one UV set, like the base colour texture).
    glm::vec3 emissive{0.0f};
    int32_t emissive_texture = -1;  // index into Scene::textures, -1 for none
    // glTF's metallicRoughnessTexture (roughness in G, metallic in B, multiplying the
    // factors above) and occlusionTexture (R, blended in by occlusion_strength: it darkens
    // the ambient light only), read with the base colour's UVs; -1 for none. The tools'
    // preview shades with them; shadows do not depend on them.
    int32_t metallic_roughness_texture = -1;
    int32_t occlusion_texture = -1;
    float occlusion_strength = 1.0f;
};

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec2 uv{0.0f};
    // glTF's COLOR_0 (linear RGB, 8 bits a channel), multiplying the base colour in the
    // tools' preview. Its alpha is not applied (the fourth byte is 255, a vertex format
    // every GPU reads): shadow passes alpha-test the material's alpha only.
    glm::u8vec4 color{255, 255, 255, 255};
};

// One triangle list with a single material, in its own model space.
struct Mesh {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    uint32_t material = 0;
    Aabb bounds;  // model-space bounds of the vertices
};

// Where an instance came from, in the terms scene files use: the scene file's
// `objects[i]` entry and, for glTF models, the node, mesh and primitive it was made of
// (names empty when the file gives none). `penumbra inspect` lists them, and messages
// name casters the way exclude_casters accepts them.
struct InstanceOrigin {
    int32_t object = -1;     // index into the scene file's [[objects]]; -1: made by code (built-ins)
    std::string type;        // the object's type: "plane", "box", ..., "gltf"
    std::string file;        // glTF: the model's path as the scene file wrote it
    int32_t placement = -1;  // glTF: index into the object's instances (0 without instances)
    int32_t node = -1;       // glTF: nodes[i]
    int32_t mesh = -1;       // glTF: meshes[j]
    int32_t primitive = -1;  // glTF: meshes[j].primitives[k]
    std::string node_name;
    std::string mesh_name;
};

// A mesh placed in the world.
struct Instance {
    uint32_t mesh = 0;
    glm::mat4 world{1.0f};
    bool cast_shadows = true;     // drawn into shadow maps (and traced by compare's reference)
    bool receive_shadows = true;  // false: lit as if nothing shadowed it
    bool dynamic = false;         // drawn every frame over cached static casters (--shadow-cache)
    std::string name;             // where it came from, for messages: a glTF node's name, an object's type
    InstanceOrigin origin;
};

struct Scene {
    Camera camera;
    std::vector<Light> lights;
    glm::vec3 ambient{0.25f, 0.3f, 0.35f};
    std::vector<Texture> textures;
    std::vector<Material> materials;
    std::vector<Mesh> meshes;
    std::vector<Instance> instances;
    // What loading noticed but did not refuse (a glTF's ignored extensions), one line each,
    // for the tools to print.
    std::vector<std::string> warnings;

    // World-space bounds of every instance.
    Aabb world_bounds() const;
    // The first directional light, or nullptr when the scene has none.
    const Light* sun() const;
    // Triangles submitted when every instance is drawn once.
    uint64_t triangle_count() const;
};

}  // namespace penumbra
