#pragma once
// The value types the shadow math works on: world-space boxes, a look-at camera and a
// light, in glm. The library's own (penumbra::core): the library never includes the scene
// component, whose Aabb, Camera and Light are the tools' scene model; the library converts
// its public descriptions (penumbra/math.hpp, penumbra/lights.hpp) into these, once, at the
// boundary (src/library/conversions.hpp).
#include <array>
#include <cstdint>
#include <limits>

#include "core/glm_config.hpp"
#include "penumbra/lights.hpp"

namespace penumbra::core {

// An axis-aligned box; empty (min > max) until something is added.
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

// Bounds of a box after an affine transform (Arvo's method: exact for the transformed
// corners, no loop over 8 points needed).
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

// A camera at `eye` looking at `target` (core/camera_math.hpp makes its matrices).
struct Camera {
    glm::vec3 eye{0.0f, 6.0f, 12.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 60.0f;  // vertical field of view
    float near_plane = 0.1f;
    float far_plane = 200.0f;
};

// What the cascade and local-light math need of a light: a LightDesc (penumbra/lights.hpp)
// less its colour, with a unit direction and glm vectors.
struct Light {
    LightType type = LightType::Directional;
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // travel direction (light -> receivers); unit length
    glm::vec3 position{0.0f};                // spot and point lights
    float angular_diameter_degrees = 0.53f;  // directional: the sun's disk
    bool cast_shadows = true;
    float inner_angle_degrees = 20.0f;  // spot: full intensity inside (half-angle from the axis)
    float outer_angle_degrees = 30.0f;  // spot: zero outside; the shadow frustum's fov is twice this
    float range = 25.0f;                // metres: the light and its shadow end here
    float radius = 0.1f;                // metres: the light's size, for soft shadows (pcss)
    uint32_t shadow_resolution = 0;     // texels per side of its shadow map; 0 = the settings' default
};

}  // namespace penumbra::core
