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

// A set of the maps a view's sun is drawn into, with what they hold between frames. A view
// has one, or one per frame in flight (ShadowSystemDesc::maps_per_frame_in_flight): frame F
// draws set F % count, whose last frame has completed, while the frames before it may
// still be sampling theirs.
struct SunMaps {
    // The maps the settings size (SettingEffect::Resource replaces them).
    std::unique_ptr<CascadeMaps> cascades;
    std::unique_ptr<VirtualShadowMap> virtual_map;  // Settings::shadow.technique = virtual
    bool cascade_placeholder_drawn = false;         // with virtual_map: the cascades' placeholder is in its layout
    CascadeCache cascade_cache;
    // Geometry's static change log up to here is drawn into these maps (static_change_end()).
    uint64_t static_changes_seen = 0;
};

struct SunView {
    explicit SunView(ViewSlots view_slots) : slots(std::move(view_slots)) {}

    // The set frame `frame` draws and samples.
    SunMaps& maps(uint64_t frame) { return map_sets[frame % map_sets.size()]; }
    const SunMaps& maps(uint64_t frame) const { return map_sets[frame % map_sets.size()]; }

    ViewSlots slots;
    std::vector<SunMaps> map_sets;
    // What prepare() computed for record_shadow_maps().
    std::vector<passes::CascadeDraws> cascade_draws;
    CascadeSet planned_cascades;  // the cascades cascade_draws were planned for
    passes::CasterFaceCulling culling;
    bool sun_casts = false;  // the sun casts shadows this frame
    ViewShadowInfo info;
    std::unique_ptr<gpu::Image> visibility;          // Penumbra's own target, made on first use
    std::optional<VisibilityImage> last_visibility;  // what the last record_visibility() wrote
};

}  // namespace penumbra::library
