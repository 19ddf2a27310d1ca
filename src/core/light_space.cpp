// The light view basis of a directional light.
#include <cmath>
#include <stdexcept>

#include "core/cascades.hpp"

namespace penumbra {

glm::mat4 light_view_matrix(const glm::vec3& light_direction) {
    const float length = glm::length(light_direction);
    if (!(length > 0.0f) || !std::isfinite(length)) {
        throw std::invalid_argument("light_view_matrix: the light direction must be finite and non-zero");
    }
    const glm::vec3 forward = light_direction / length;
    // 1. Reference "up" for the basis: world +Y, unless the light travels (almost) along
    //    it, where cross(forward, up) vanishes; a sun at the zenith then uses world +Z.
    //    The switch is a rotation of the shadow map about the light axis, which changes
    //    nothing but texel orientation.
    const glm::vec3 world_up{0.0f, 1.0f, 0.0f};
    const glm::vec3 reference_up =
        std::abs(glm::dot(forward, world_up)) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : world_up;
    // 2. A pure rotation (the light sits at the world origin): the shadow-map texel grid
    //    is then fixed in the world, which is what texel snapping relies on. The ortho
    //    projection carries the translation of each cascade.
    return glm::lookAtRH(glm::vec3(0.0f), forward, reference_up);
}

}  // namespace penumbra
