#pragma once
// The C++ side of shaders/include/renderer_shared.h, checked against its std140/std430
// offsets.
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "penumbra/scene/render_settings.hpp"

namespace penumbra::renderer::shader {

using mat4 = glm::mat4;
using vec4 = glm::vec4;
using vec3 = glm::vec3;
using uvec4 = glm::uvec4;

#include "renderer_shared.h"

static_assert(RENDERER_MAX_LOCAL_LIGHTS == kMaxLocalLights);
static_assert(offsetof(FrameUniforms, camera_position) == 64);
static_assert(offsetof(FrameUniforms, debug_view) == 128);
static_assert(offsetof(FrameUniforms, inverse_view_projection) == 144);
static_assert(offsetof(FrameUniforms, screen) == 208);
static_assert(sizeof(FrameUniforms) == 224);
static_assert(offsetof(LocalLight, direction) == 16);
static_assert(offsetof(LocalLight, radiance) == 32);
static_assert(offsetof(LocalLight, cos_inner) == 48);
static_assert(offsetof(LocalLight, shadow_index) == 52);
static_assert(offsetof(LocalLight, visibility_slot) == 56);
static_assert(sizeof(LocalLight) == 64);
static_assert(sizeof(LocalLights) == 64 * RENDERER_MAX_LOCAL_LIGHTS);
static_assert(offsetof(DrawPushConstants, material) == 16);
static_assert(offsetof(DrawPushConstants, flags) == 32);
static_assert(offsetof(DrawPushConstants, emissive) == 48);
// At most 128 bytes: the push-constant size every Vulkan device supports (maxPushConstantsSize).
static_assert(sizeof(DrawPushConstants) == 64);

}  // namespace penumbra::renderer::shader
