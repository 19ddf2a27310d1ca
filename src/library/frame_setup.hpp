#pragma once
// A frame's CPU work that makes no Vulkan calls: caster culling for every local-light
// layer (the cascades': library/cascade_cache.hpp), and the contents of the two uniform blocks of the descriptor set.
#include <cstdint>
#include <span>
#include <vector>

#include "core/camera_math.hpp"
#include "core/cascades.hpp"
#include "core/local_lights.hpp"
#include "core/shadow_inputs.hpp"
#include "passes/casters.hpp"
#include "passes/local_shadow_pass.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::library {

struct CullStats {
    uint32_t draws = 0;
    uint64_t triangles = 0;
};

// The layers to render for every shadowed local light: the draws inside each layer's
// frustum (and, for a cube face, the sphere of the range), none on a wide spot's cube
// faces its cone cannot reach; every draw when `cull` is off. Each layer knows the winding
// of faces toward its light. Layers whose index `kept` marks (cached local shadows) are
// listed with `keep` and no draws: nothing is culled for them. `gpu_culls` (the layered
// strategy): the layers to cull are marked gpu_culled, without draw lists.
std::vector<passes::LocalShadowLayer> cull_local_casters(std::span<const core::Light> lights,
                                                         const LocalShadowPlan& plan, const passes::CasterScene& scene,
                                                         bool cull, const std::vector<bool>& kept = {},
                                                         bool gpu_culls = false);

// World bounds of every draw (what local lights fit their near planes to).
std::vector<core::Aabb> caster_bounds(const passes::CasterScene& scene);

shader::PenumbraShadowUniforms build_shadow_uniforms(const CameraView& camera, const CascadeSet& cascades,
                                                     const core::Light* sun, bool sun_casts_shadows,
                                                     const ShadowSettings& settings,
                                                     const passes::CasterDepthBias& caster_bias, uint32_t frame_index);

// Settings::contact into the uniforms' contact fields (the lights it traces toward: none
// when it is off).
void set_contact_uniforms(shader::PenumbraShadowUniforms& uniforms, const ContactShadowSettings& contact);

shader::PenumbraLocalShadows build_local_shadows(std::span<const core::Light> lights, const LocalShadowPlan& plan,
                                                 const ShadowSettings& settings,
                                                 const passes::CasterDepthBias& caster_bias);

}  // namespace penumbra::library
