#pragma once
// The shadow-filter part of the frame uniform block (docs/filters.md): per-cascade light
// radius and receiver-plane clamp, radii, moment parameters and the frame index.
#include <cstdint>

#include "core/cascades.hpp"
#include "core/scene.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::renderer {

void fill_filter_uniforms(shader::FrameUniforms& frame, const Scene& scene, const CascadeSet& cascades,
                          const ShadowSettings& settings, uint32_t frame_index);

}  // namespace penumbra::renderer
