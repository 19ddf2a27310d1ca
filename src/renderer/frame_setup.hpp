#pragma once
// Per-frame CPU work that needs no Vulkan calls: the sun's cascades, per-cascade caster
// culling and the contents of the frame uniform block.
#include <cstdint>
#include <vector>

#include "core/camera_math.hpp"
#include "core/cascades.hpp"
#include "core/render_settings.hpp"
#include "core/scene.hpp"
#include "passes/draw_data.hpp"
#include "passes/shader_interface.hpp"
#include "passes/shadow_pass.hpp"

namespace penumbra::renderer {

struct CascadeStats {
    uint32_t draws = 0;
    uint64_t triangles = 0;
};

struct CulledCasters {
    std::vector<passes::CascadeDrawList> lists;  // one per cascade
    std::vector<CascadeStats> stats;
};

// The direction the sun's light travels; straight down when the scene has no sun.
glm::vec3 sun_travel_direction(const Scene& scene);

// Whether the scene has a sun and it casts shadows (`cast_shadows`, default true).
bool sun_casts_shadows(const Scene& scene);

// Draws that may cast into each cascade (all draws when culling is off; none when the sun
// casts no shadows, so the cascades are only cleared).
CulledCasters cull_casters(const Scene& scene, const CascadeSet& cascades, const passes::DrawData& data, bool cull);

// frame_index rotates the shadow filters' sampling patterns from frame to frame.
shader::FrameUniforms build_frame_uniforms(const CameraView& camera, const Scene& scene, const CascadeSet& cascades,
                                           const RenderSettings& settings, uint32_t frame_index = 0);

}  // namespace penumbra::renderer
