#include "core/caster_facing.hpp"

#include <array>
#include <cmath>

namespace penumbra {
namespace {

glm::vec3 unproject(const glm::mat4& inverse_view_projection, const glm::vec3& ndc) {
    const glm::vec4 world = inverse_view_projection * glm::vec4(ndc, 1.0f);
    return glm::vec3(world) / world.w;
}

}  // namespace

bool light_facing_is_counter_clockwise(const glm::mat4& view_projection) {
    // A small triangle at the centre of the map, halfway in depth, whose normal points
    // toward the light (toward the near plane along the ray through the centre).
    const glm::mat4 inverse = glm::inverse(view_projection);
    const glm::vec3 centre = unproject(inverse, {0.0f, 0.0f, 0.5f});
    const glm::vec3 toward_light = glm::normalize(unproject(inverse, {0.0f, 0.0f, 1.0f}) - centre);
    const glm::vec3 helper =
        std::abs(toward_light.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 u = glm::normalize(glm::cross(helper, toward_light));
    const glm::vec3 v = glm::cross(toward_light, u);  // cross(u, v) == toward_light
    const float size = 1e-3f * std::max(1.0f, glm::length(centre));
    const std::array<glm::vec3, 3> triangle{centre, centre + u * size, centre + v * size};
    std::array<glm::vec2, 3> screen{};
    for (size_t i = 0; i < 3; ++i) {
        const glm::vec4 clip = view_projection * glm::vec4(triangle[i], 1.0f);
        screen[i] = glm::vec2(clip) / clip.w;  // framebuffer x and y grow with NDC x and y
    }
    float area = 0.0f;
    for (size_t i = 0; i < 3; ++i) {
        const glm::vec2 a = screen[i];
        const glm::vec2 b = screen[(i + 1) % 3];
        area += a.x * b.y - b.x * a.y;
    }
    return -0.5f * area > 0.0f;
}

}  // namespace penumbra
