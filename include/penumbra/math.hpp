#pragma once
// The small value types of Penumbra's public API. Plain structs, no math library: a
// caller converts from its own (glm::vec3 and glm::mat4 have the same memory layout as
// Vec3 and Mat4: glm::make_mat4(m.m.data()) one way, memcpy from glm::value_ptr the other).
#include <array>
#include <cstddef>
#include <cstdint>

namespace penumbra {

struct Vec2 {
    float x = 0.0f;
    float y = 0.0f;
    friend bool operator==(const Vec2&, const Vec2&) = default;
};

struct Vec3 {
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
    friend bool operator==(const Vec3&, const Vec3&) = default;
};

// A 4x4 matrix in column-major order, as GLSL and glm store it: element (row r, column c)
// is m[4 * c + r], and the translation of an affine transform is m[12], m[13], m[14].
// Transforms column vectors (p' = M p).
struct Mat4 {
    std::array<float, 16> m{1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f,
                            0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f};  // identity

    float operator()(int row, int column) const { return m[static_cast<std::size_t>(4 * column + row)]; }
    float& operator()(int row, int column) { return m[static_cast<std::size_t>(4 * column + row)]; }
    friend bool operator==(const Mat4&, const Mat4&) = default;
};

// The largest coordinate, in metres along any axis, that geometry and lights may have in
// world space (and meshes in model space): Penumbra's math is 32-bit float, which still
// carries squares (lengths, dot products) of numbers up to 1e9; beyond, a normalisation or
// projection overflows. The ShadowSystem refuses anything beyond it with an InputError
// naming the argument. Every caster and receiver widens the lights' depth ranges, so keep
// the world as small as it is: far-off geometry costs every shadow depth precision.
inline constexpr float kMaxWorldMagnitude = 1e9f;

// An axis-aligned box. A box with min > max on any axis is empty.
struct Bounds {
    Vec3 min;
    Vec3 max;
    friend bool operator==(const Bounds&, const Bounds&) = default;
};

}  // namespace penumbra
