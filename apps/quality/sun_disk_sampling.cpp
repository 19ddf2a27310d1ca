#include "quality/sun_disk_sampling.hpp"

#include <cmath>

namespace penumbra::quality {

glm::vec2 concentric_disk(glm::vec2 square) {
    const glm::vec2 offset = 2.0f * square - 1.0f;
    if (offset.x == 0.0f && offset.y == 0.0f) return glm::vec2(0.0f);
    constexpr float kQuarterPi = 0.78539816339f;
    float radius = 0.0f;
    float theta = 0.0f;
    if (std::abs(offset.x) > std::abs(offset.y)) {
        radius = offset.x;
        theta = kQuarterPi * (offset.y / offset.x);
    } else {
        radius = offset.y;
        theta = 2.0f * kQuarterPi - kQuarterPi * (offset.x / offset.y);
    }
    return radius * glm::vec2(std::cos(theta), std::sin(theta));
}

glm::vec2 fibonacci_lattice(uint32_t index, uint32_t count, glm::vec2 shift) {
    constexpr double kGoldenConjugate = 0.6180339887498949;
    const double x = (static_cast<double>(index) + 0.5) / static_cast<double>(count) + shift.x;
    const double y = static_cast<double>(index) * kGoldenConjugate + shift.y;
    return {static_cast<float>(x - std::floor(x)), static_cast<float>(y - std::floor(y))};
}

namespace {

uint32_t pcg_hash(uint32_t value) {
    const uint32_t state = value * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

}  // namespace

glm::vec2 hash_to_unit_square(uint32_t value) {
    const uint32_t first = pcg_hash(value);
    const uint32_t second = pcg_hash(first);
    constexpr float kScale = 1.0f / 4294967296.0f;
    return {static_cast<float>(first) * kScale, static_cast<float>(second) * kScale};
}

TangentBasis orthonormal_basis(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}};
}

SunDisk::SunDisk(const glm::vec3& to_sun, float angular_diameter_degrees)
    : to_sun_(glm::normalize(to_sun)),
      basis_(orthonormal_basis(to_sun_)),
      tan_half_angle_(std::tan(glm::radians(angular_diameter_degrees) * 0.5f)) {}

glm::vec3 SunDisk::direction(glm::vec2 disk_point) const {
    const glm::vec3 lateral = basis_.tangent * disk_point.x + basis_.bitangent * disk_point.y;
    return glm::normalize(to_sun_ + lateral * tan_half_angle_);
}

}  // namespace penumbra::quality
