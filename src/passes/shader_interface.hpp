#pragma once
// The C++ side of shaders/include/penumbra_shared.h: the same structs, checked member
// by member against std140 offsets so that C++ and GLSL cannot disagree.
#include <cstddef>
#include <cstdint>

#include "core/glm_config.hpp"

namespace penumbra::shader {

using mat4 = glm::mat4;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;

#include "penumbra_shared.h"

static_assert(sizeof(mat4) == 64 && sizeof(vec4) == 16 && sizeof(uvec4) == 16);
static_assert(offsetof(FrameUniforms, view) == 64);
static_assert(offsetof(FrameUniforms, cascade_view_projection) == 128);
static_assert(offsetof(FrameUniforms, camera_position) == 128 + 64 * PENUMBRA_MAX_CASCADES);
static_assert(offsetof(FrameUniforms, cascade_split_far) == offsetof(FrameUniforms, camera_position) + 16 * 4);
static_assert(offsetof(FrameUniforms, shadow_params) ==
              offsetof(FrameUniforms, cascade_split_far) + 16 * (PENUMBRA_MAX_CASCADES / 2));
static_assert(offsetof(FrameUniforms, options) == offsetof(FrameUniforms, shadow_params) + 32);
static_assert(offsetof(FrameUniforms, cascade_filter) == offsetof(FrameUniforms, options) + 16);
static_assert(offsetof(FrameUniforms, filter_params) ==
              offsetof(FrameUniforms, cascade_filter) + 16 * PENUMBRA_MAX_CASCADES);
static_assert(offsetof(FrameUniforms, moment_params) == offsetof(FrameUniforms, filter_params) + 16);
static_assert(offsetof(FrameUniforms, filter_options) == offsetof(FrameUniforms, moment_params) + 16);
static_assert(sizeof(FrameUniforms) == offsetof(FrameUniforms, filter_options) + 16);

static_assert(offsetof(DrawPushConstants, base_color) == 64);
static_assert(offsetof(DrawPushConstants, material) == 80);
static_assert(offsetof(DrawPushConstants, flags) == 96);
static_assert(sizeof(DrawPushConstants) == 112);
static_assert(sizeof(DrawPushConstants) <= 128, "Vulkan guarantees only 128 bytes of push constants");

static_assert(offsetof(TapCeilingPushConstants, counts) == 16);
static_assert(sizeof(TapCeilingPushConstants) == 32);

static_assert(sizeof(BlurPushConstants) == 16);
static_assert(offsetof(LocalMomentsPushConstants, depth_range) == 16);
static_assert(sizeof(LocalMomentsPushConstants) == 32);

static_assert(sizeof(LocalLight) == 80);
static_assert(offsetof(LocalLightUniforms, lights) == 64 * PENUMBRA_MAX_LOCAL_SHADOW_LAYERS);
static_assert(offsetof(LocalLightUniforms, counts) ==
              offsetof(LocalLightUniforms, lights) + sizeof(LocalLight) * PENUMBRA_MAX_LOCAL_LIGHTS);
static_assert(sizeof(LocalLightUniforms) == offsetof(LocalLightUniforms, counts) + 32);
static_assert(sizeof(LocalLightUniforms) <= 128u << 20, "Vulkan guarantees 128 MiB storage buffer ranges");

}  // namespace penumbra::shader
