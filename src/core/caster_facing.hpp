#pragma once
// Which winding a caster's faces toward the light have in a shadow map's clip space, so
// that the shadow passes can cull faces by their orientation to the light
// (Settings::shadow.caster_culling). No Vulkan.
#include "core/glm_config.hpp"

namespace penumbra {

// True when a triangle that faces the light (counter-clockwise seen from the light, i.e. its
// right-hand normal points toward the light) has positive area in Vulkan's framebuffer
// convention under `view_projection` (a = -1/2 sum(x_i y_i+1 - x_i+1 y_i), y down), which
// VK_FRONT_FACE_COUNTER_CLOCKWISE calls front-facing. Works for orthographic and
// perspective reverse-Z projections: the light lies toward the near plane (depth 1).
bool light_facing_is_counter_clockwise(const glm::mat4& view_projection);

}  // namespace penumbra
