#pragma once
// Axis-aligned bounding boxes: the currency of scene bounds, caster culling and
// the Z extension of tight cascade fitting.
#include <array>
#include <limits>

#include "core/glm_config.hpp"

namespace penumbra {

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

}  // namespace penumbra
