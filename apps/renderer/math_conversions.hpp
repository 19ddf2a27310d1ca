#pragma once
// Between the renderer's glm types and the library's public math types (penumbra/math.hpp:
// column-major, as glm).
#include <glm/glm.hpp>

#include "penumbra/math.hpp"

namespace penumbra::renderer {

inline Vec3 to_vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

inline Mat4 to_mat4(const glm::mat4& m) {
    Mat4 result;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) result(row, column) = m[column][row];
    }
    return result;
}

inline glm::mat4 to_glm(const Mat4& m) {
    glm::mat4 result;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) result[column][row] = m(row, column);
    }
    return result;
}

}  // namespace penumbra::renderer
