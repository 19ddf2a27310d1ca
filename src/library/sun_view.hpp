#pragma once
// One view's sun shadow: the cascades (or the virtual shadow map) fitted to its camera,
// their caches and this frame's plan, its slots (uniforms and descriptor sets per frame in
// flight) and its visibility image. A ShadowSystem has one per view of the frame; the
// scene, the settings and the local lights' maps are the system's.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/cascades.hpp"
#include "library/cascade_cache.hpp"
#include "library/frame_slots.hpp"
#include "library/shadow_maps.hpp"
#include "library/virtual_shadow_map.hpp"
#include "passes/casters.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/shadow_system.hpp"

namespace penumbra::library {

struct SunView {
    explicit SunView(ViewSlots view_slots) : slots(std::move(view_slots)) {}

    ViewSlots slots;
    // The maps the settings size (SettingEffect::Resource replaces them).
    std::unique_ptr<CascadeMaps> cascades;
    std::unique_ptr<VirtualShadowMap> virtual_map;  // Settings::shadow.technique = virtual
    bool cascade_placeholder_drawn = false;         // with virtual_map: the cascades' placeholder is in its layout
    // What prepare() computed for record_shadow_maps().
    std::vector<passes::CascadeDraws> cascade_draws;
    CascadeCache cascade_cache;
    CascadeSet planned_cascades;  // the cascades cascade_draws were planned for
    passes::CasterFaceCulling culling;
    bool sun_casts = false;  // the sun casts shadows this frame
    ViewShadowInfo info;
    std::unique_ptr<gpu::Image> visibility;          // Penumbra's own target, made on first use
    std::optional<VisibilityImage> last_visibility;  // what the last record_visibility() wrote
};

}  // namespace penumbra::library
