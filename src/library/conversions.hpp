#pragma once
// Between the public API's plain value types (penumbra/math.hpp, lights.hpp) and the glm
// types of the internal layers. Vec3 and Mat4 share glm's memory layout (checked here).
#include <algorithm>
#include <cmath>

#include "core/glm_config.hpp"
#include "core/shadow_inputs.hpp"
#include "penumbra/lights.hpp"
#include "penumbra/math.hpp"

namespace penumbra::library {

static_assert(sizeof(Vec3) == sizeof(glm::vec3) && sizeof(Vec2) == sizeof(glm::vec2));
static_assert(sizeof(Mat4) == sizeof(glm::mat4));

inline glm::vec3 to_glm(const Vec3& v) { return {v.x, v.y, v.z}; }
inline Vec3 to_public(const glm::vec3& v) { return {v.x, v.y, v.z}; }

inline glm::mat4 to_glm(const Mat4& m) { return glm::make_mat4(m.m.data()); }

inline Mat4 to_public(const glm::mat4& m) {
    Mat4 result;
    const float* values = glm::value_ptr(m);
    std::copy(values, values + 16, result.m.begin());
    return result;
}

inline core::Aabb to_aabb(const Bounds& bounds) { return {to_glm(bounds.min), to_glm(bounds.max)}; }

// The internal light of the local-light and cascade math (colour and intensity unused).
// A direction normalised in double precision: any finite non-zero vector set_lights()
// accepts (components of 1e30 or 1e-30 alike) becomes a unit vector, where float arithmetic
// on the raw vector would overflow or underflow its length to infinity or zero.
inline glm::vec3 unit_direction(const Vec3& v) {
    const double x = v.x;
    const double y = v.y;
    const double z = v.z;
    const double length = std::sqrt(x * x + y * y + z * z);
    return {static_cast<float>(x / length), static_cast<float>(y / length), static_cast<float>(z / length)};
}

inline core::Light to_light(const LightDesc& desc) {
    core::Light light;
    light.type = desc.type;
    light.direction = unit_direction(desc.direction);
    light.position = to_glm(desc.position);
    light.angular_diameter_degrees = desc.angular_diameter_degrees;
    light.cast_shadows = desc.cast_shadows;
    light.inner_angle_degrees = desc.inner_angle_degrees;
    light.outer_angle_degrees = desc.outer_angle_degrees;
    light.range = desc.range;
    light.radius = desc.radius;
    light.shadow_resolution = desc.shadow_resolution;
    return light;
}

}  // namespace penumbra::library
