#pragma once
// Per-frame CPU work for spot and point lights, no Vulkan calls: the local-light uniform
// block and the per-layer caster lists of their shadow maps (docs/local-lights.md).
#include <string>
#include <vector>

#include "core/local_lights.hpp"
#include "core/render_settings.hpp"
#include "core/scene.hpp"
#include "passes/draw_data.hpp"
#include "passes/local_shadow_pass.hpp"
#include "passes/shader_interface.hpp"
#include "renderer/renderer.hpp"

namespace penumbra::renderer {

// World bounds of every draw (the casters the near planes are fitted to).
std::vector<Aabb> draw_bounds(const passes::DrawData& data);

// The uniform block for `plan` (fitted with fit_local_shadows()): lights, shadow layers and
// the slot whose visibility the visibility target receives (settings.visibility_light).
shader::LocalLightUniforms build_local_light_uniforms(const Scene& scene, const LocalShadowPlan& plan,
                                                      const RenderSettings& settings);

// The draws that may cast into each layer (all draws when culling is off): inside the
// layer's frustum and, for a cube face, the sphere of range; none on a wide spot's cube
// faces that its cone cannot reach.
std::vector<passes::LocalShadowLayer> cull_local_casters(const Scene& scene, const LocalShadowPlan& plan,
                                                         const passes::DrawData& data, bool cull);

// Per shadowed light: its layers, resolution, near plane and the casters submitted for it.
std::vector<LocalShadowStats> local_shadow_stats(const LocalShadowPlan& plan,
                                                 const std::vector<passes::LocalShadowLayer>& layers,
                                                 const passes::DrawData& data);

// The one-line warning for lights beyond the budget; empty when every light fits.
std::string local_shadow_budget_warning(const LocalShadowPlan& plan, const LocalShadowSettings& settings);

}  // namespace penumbra::renderer
