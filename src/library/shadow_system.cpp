// ShadowSystem: the public API over the device layer and the passes. The Impl holds the
// geometry, the lights, the maps and the per-frame slots; each public call checks its
// arguments and its place in the frame (prepare -> record_shadow_maps -> record_visibility)
// before it changes anything.
#include "penumbra/shadow_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/camera_math.hpp"
#include "core/cascades.hpp"
#include "core/caster_facing.hpp"
#include "core/local_lights.hpp"
#include "core/settings_difference.hpp"
#include "library/cascade_cache.hpp"
#include "library/conversions.hpp"
#include "library/device_checks.hpp"
#include "library/frame_setup.hpp"
#include "library/frame_slots.hpp"
#include "library/geometry.hpp"
#include "library/light_checks.hpp"
#include "library/local_cache.hpp"
#include "library/retired.hpp"
#include "library/shadow_maps.hpp"
#include "library/sun_view.hpp"
#include "library/virtual_shadow_map.hpp"
#include "passes/shadow_filter_specialization.hpp"
#include "passes/visibility_resolve_pass.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/check.hpp"
#include "penumbra/gpu/debug_names.hpp"
#include "penumbra/gpu/device.hpp"

namespace penumbra {
namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

constexpr uint32_t kMaxFramesInFlight = 8;
constexpr uint32_t kMaxScreenSize = 16384;

PFN_vkGetInstanceProcAddr instance_proc_addr(const DeviceDesc& desc) {
    return desc.get_instance_proc_addr ? desc.get_instance_proc_addr : gpu::loader_instance_proc_addr();
}

gpu::Device make_device(const DeviceDesc& desc) {
    const gpu::EnabledFeatures features = library::check_device(desc, instance_proc_addr(desc));
    return gpu::Device({desc.instance, desc.physical_device, desc.device, desc.queue, desc.queue_family,
                        desc.compute_queue_family, desc.compute_queue},
                       features, instance_proc_addr(desc), desc.allocator);
}

bool compute_timestamps_match(const gpu::Device& device) {
    if (!device.shares_with_compute()) return false;
    const std::vector<VkQueueFamilyProperties> families = gpu::queue_families(device.vk(), device.physical_device());
    const uint32_t graphics_bits = families.at(device.queue_family()).timestampValidBits;
    return graphics_bits > 0 && families.at(device.compute_queue_family()).timestampValidBits == graphics_bits;
}

uint32_t checked_frames_in_flight(uint32_t frames) {
    if (frames < 1 || frames > kMaxFramesInFlight) {
        throw InputError("ShadowSystem: frames_in_flight: " + std::to_string(frames) + " is out of range (1.." +
                         std::to_string(kMaxFramesInFlight) + ")");
    }
    return frames;
}

const Settings& checked_settings(const Settings& settings) {
    validate_settings(settings, "ShadowSystem settings");
    return settings;
}

// The camera of a ViewDesc: its projection's frustum, or the symmetric perspective of its
// field of view and planes.
CameraView camera_of(const ViewDesc& view) {
    if (view.projection) {
        return make_camera_view(library::to_glm(view.view), library::to_glm(*view.projection), view.width, view.height);
    }
    const float aspect = static_cast<float>(view.width) / static_cast<float>(view.height);
    return make_camera_view(library::to_glm(view.view), view.fov_y_radians, aspect, view.near_plane, view.far_plane);
}

// A caller's projection must give a frustum in front of the camera: a near plane at a
// positive distance, a farther far plane (or none), and a non-empty extent.
void check_projection(const ViewDesc& view, const std::string& prefix) {
    const auto reject = [&](const std::string& problem) {
        throw InputError(prefix + "ViewDesc::projection: " + problem);
    };
    for (const float value : view.projection->m) {
        if (!std::isfinite(value)) reject("must be finite");
    }
    if (std::abs(glm::determinant(library::to_glm(*view.projection))) < 1e-20f) reject("is not invertible");
    const CameraView camera = camera_of(view);
    if (!(camera.near_plane > 0.0f) || !std::isfinite(camera.near_plane)) {
        reject("its near plane is at view distance " + std::to_string(camera.near_plane) +
               " (a Vulkan projection of a camera looking down -Z puts it at a finite distance > 0)");
    }
    if (!(camera.far_plane > camera.near_plane)) reject("its far plane is not beyond its near plane");
    // Edges no wider than ~179.99 degrees apart, within the world's magnitude.
    constexpr float kMaxSlope = 1e4f;
    const FrustumSpan span = vertical_frustum_span(camera);
    bool bounded = camera.near_plane < kMaxWorldMagnitude;
    for (int i = 0; i < 4; ++i) {
        bounded = bounded && glm::all(glm::lessThan(glm::abs(camera.edge_origin[i]), glm::vec2(kMaxWorldMagnitude))) &&
                  glm::all(glm::lessThan(glm::abs(camera.edge_slope[i]), glm::vec2(kMaxSlope)));
    }
    if (!bounded || !(span.base + span.per_metre > 0.0f)) reject("its frustum is empty or unbounded");
}

// `prefix` names the call, and the view among several.
void check_view(const ViewDesc& view, const std::string& prefix) {
    const auto reject = [&](const std::string& field, const std::string& problem) {
        throw InputError(prefix + "ViewDesc::" + field + ": " + problem);
    };
    for (const float value : view.view.m) {
        if (!std::isfinite(value)) reject("view", "must be finite");
    }
    if (std::abs(glm::determinant(library::to_glm(view.view))) < 1e-12f) reject("view", "is not invertible");
    if (view.width == 0 || view.height == 0 || view.width > kMaxScreenSize || view.height > kMaxScreenSize) {
        reject("width/height", std::to_string(view.width) + "x" + std::to_string(view.height) +
                                   " is out of range (1.." + std::to_string(kMaxScreenSize) + ")");
    }
    if (view.projection) {
        check_projection(view, prefix);
        return;
    }
    if (!(view.fov_y_radians > 0.0f && view.fov_y_radians < 3.14159f)) {
        reject("fov_y_radians", std::to_string(view.fov_y_radians) + " is outside (0, pi)");
    }
    if (!(view.near_plane > 0.0f) || !std::isfinite(view.near_plane)) {
        reject("near_plane", std::to_string(view.near_plane) + " must be finite and > 0");
    }
    if (!(view.far_plane > view.near_plane) || !std::isfinite(view.far_plane)) {
        reject("far_plane", std::to_string(view.far_plane) + " must be finite and > near_plane");
    }
}

void check_views(std::span<const ViewDesc> views) {
    if (views.empty() || views.size() > kMaxViews) {
        throw InputError("ShadowSystem::prepare: " + std::to_string(views.size()) + " views; it takes 1.." +
                         std::to_string(kMaxViews));
    }
    for (size_t v = 0; v < views.size(); ++v) {
        check_view(views[v], "ShadowSystem::prepare: " +
                                 (views.size() > 1 ? "views[" + std::to_string(v) + "]: " : std::string()));
    }
}

bool is_virtual(const Settings& settings) { return settings.shadow.technique == ShadowTechnique::Virtual; }

// With the virtual shadow map the cascades' map is a placeholder the descriptor set binds:
// one small layer, never drawn into after its first frame.
ShadowSettings cascade_map_settings(const ShadowSettings& settings) {
    if (settings.technique != ShadowTechnique::Virtual) return settings;
    ShadowSettings placeholder = settings;
    placeholder.cascades.count = 1;
    placeholder.cascades.resolution = 512;
    placeholder.cascades.scheme = SplitScheme::Practical;
    placeholder.strategy = ShadowStrategy::PerCascade;
    placeholder.cache_static_casters = false;
    return placeholder;
}

// The screen inputs of record_visibility() and record_page_marking().
void check_screen(const std::string& call, const ScreenInputs& screen) {
    const auto reject = [&](const std::string& problem) { throw InputError("ShadowSystem::" + call + ": " + problem); };
    if (screen.depth == VK_NULL_HANDLE) reject("ScreenInputs::depth is VK_NULL_HANDLE");
    if (screen.width == 0 || screen.height == 0 || screen.width > kMaxScreenSize || screen.height > kMaxScreenSize) {
        reject("ScreenInputs::width/height: " + std::to_string(screen.width) + "x" + std::to_string(screen.height) +
               " is out of range (1.." + std::to_string(kMaxScreenSize) + ")");
    }
    const glm::mat4 view_projection = library::to_glm(screen.view_projection);
    if (std::abs(glm::determinant(view_projection)) < 1e-30f) reject("ScreenInputs::view_projection is not invertible");
}

// The frame's place and arguments for `call` (record_visibility() or _async()), whichever
// image it writes.
void check_visibility_call(const std::string& call, const library::FrameSlot& slot, const library::ViewSlot& view_slot,
                           VkCommandBuffer cmd, const ScreenInputs& screen) {
    if (!slot.shadow_maps_recorded) {
        throw UsageError("ShadowSystem::" + call + ": record_shadow_maps() has not been recorded for this frame");
    }
    if (view_slot.visibility_recorded) {
        throw UsageError("ShadowSystem::" + call + ": already recorded for this frame (once per frame and view)");
    }
    if (cmd == VK_NULL_HANDLE) throw InputError("ShadowSystem::" + call + ": cmd is VK_NULL_HANDLE");
    check_screen(call, screen);
}

void check_visibility_target(const std::string& call, const VisibilityTarget& target, const ScreenInputs& screen,
                             uint32_t slot_count) {
    const auto reject = [&](const std::string& problem) {
        throw InputError("ShadowSystem::" + call + ": VisibilityTarget::" + problem);
    };
    if (target.image == VK_NULL_HANDLE) reject("image is VK_NULL_HANDLE");
    if (target.view == VK_NULL_HANDLE) reject("view is VK_NULL_HANDLE");
    if (target.format != VK_FORMAT_R8G8B8A8_UNORM) {
        reject("format is " + gpu::format_name(target.format) + "; the resolve writes VK_FORMAT_R8G8B8A8_UNORM");
    }
    if (target.width < screen.width || target.height < screen.height) {
        reject("width/height: " + std::to_string(target.width) + "x" + std::to_string(target.height) +
               " is smaller than the screen's " + std::to_string(screen.width) + "x" + std::to_string(screen.height));
    }
    if (target.layers < visibility_layers(slot_count)) {
        reject("layers: " + std::to_string(target.layers) + " hold " + std::to_string(target.layers * 4) +
               " slots; this frame has " + std::to_string(slot_count) + " (the sun and " +
               std::to_string(slot_count - 1) +
               " shadowed local lights): " + std::to_string(visibility_layers(slot_count)) + " layers are needed");
    }
}

// What names a view's objects and timed passes: nothing for the first (the names a single
// view always had), "_view<v>" after it.
std::string view_suffix(size_t index) { return index == 0 ? "" : "_view" + std::to_string(index); }

// The timed scopes opened while it lives are a view's (GpuTimer::set_scope_suffix).
class ViewScopes {
public:
    ViewScopes(gpu::GpuTimer* timer, size_t view) : timer_(timer) {
        if (timer_) timer_->set_scope_suffix(view_suffix(view));
    }
    ~ViewScopes() {
        if (timer_) timer_->set_scope_suffix("");
    }
    ViewScopes(const ViewScopes&) = delete;
    ViewScopes& operator=(const ViewScopes&) = delete;

private:
    gpu::GpuTimer* timer_;
};

MapImage map_image(const gpu::Image* image) {
    if (!image) return {};
    return {image->get(), image->view, image->desc.format, image->desc.aspect, image->desc.width, image->desc.layers};
}

}  // namespace

struct ShadowSystem::Impl {
    gpu::Device device;
    Settings settings;
    uint32_t frames_in_flight;
    // Sets of maps: one, or one per frame in flight (ShadowSystemDesc::maps_per_frame_in_flight).
    uint32_t map_set_count;
    bool timestamps;  // ShadowSystemDesc::timestamps
    // The async compute family's timestamps tick as the graphics family's: the resolve on it
    // is timed too.
    bool compute_timestamps;
    library::RetiredObjects retired;
    library::FrameSetLayouts layouts;
    gpu::UniqueDescriptorSetLayout alpha_mask_layout;
    // The local lights' maps the settings size (SettingEffect::Resource replaces them, and
    // each view's sun maps, the scene stays), with what they hold between frames: one set,
    // or one per frame in flight as the views' sun maps (library::SunMaps).
    struct LocalMapSet {
        std::unique_ptr<library::LocalMaps> maps;
        library::LocalShadowCache cache;
        uint64_t static_changes_seen = 0;  // as SunMaps::static_changes_seen
    };
    std::vector<LocalMapSet> local_sets;
    std::optional<Settings> pending_settings;  // update_settings(): applied by the next prepare()
    passes::VisibilityResolvePass resolve;
    library::FrameSlots slots;
    library::Geometry geometry;
    // The views of the last prepare(), each with its sun's maps (one from the start, so that
    // shadow_maps() answers before the first frame).
    std::vector<std::unique_ptr<library::SunView>> views;

    std::vector<core::Light> lights;
    uint64_t frame = 0;  // prepare() calls so far; the current frame's number
    FrameInfo info;
    uint64_t planned_static_changes = 0;  // Geometry::static_change_end() when the frame was planned
    LocalShadowPlan plan;
    std::vector<passes::LocalShadowLayer> local_layers;
    // The layered strategy: which layers each shadowed light had in the recent frames (one
    // entry per frame in flight and one more), to attribute the GPU's counts of a frame.
    struct LocalLayerRange {
        uint32_t light = 0;
        uint32_t first_layer = 0;
        uint32_t layers = 0;
    };
    struct LocalLayerHistory {
        uint64_t frame = 0;
        std::vector<LocalLayerRange> ranges;
    };
    std::vector<LocalLayerHistory> local_history;
    // Every specialization shader_specialization() handed out, kept for the system's life
    // (ShaderSpecialization views them); one per distinct content.
    struct Specialization {
        std::vector<VkSpecializationMapEntry> entries;
        std::vector<uint32_t> data;
    };
    mutable std::deque<Specialization> specializations;
    // GPU times of the frames whose slots prepare() reused (complete by its contract), the
    // newest last, at most frames_in_flight of them: gpu_times() of a frame still answers
    // after the prepare() that retired it, when an engine that waits for a slot's fence
    // first can read it.
    std::deque<GpuTimes> retired_times;

    // The timer the passes of `slot` record into; null (no queries) without timestamps.
    gpu::GpuTimer* timer_of(library::FrameSlot& slot) { return timestamps ? &slot.timer : nullptr; }

    // Before prepare() reuses `slot` for the next frame: checks that the frame which last
    // used it has completed, and keeps its times. Its timestamps are the witness: by
    // prepare()'s contract they are all available; one that is not means the caller has
    // more frames in flight than this system was made for (or never submitted the frame),
    // and rewriting the slot's descriptor set now would race the GPU. Without timestamps
    // (a queue family without them) nothing is checked.
    void retire_slot(const library::FrameSlot& slot) {
        if (slot.frame == 0 || !slot.shadow_maps_recorded || !timestamps || !slot.timer.supported()) return;
        const std::optional<std::vector<gpu::ScopeTime>> times = slot.timer.read();
        if (!times) {
            throw UsageError("ShadowSystem::prepare: frame " + std::to_string(slot.frame) + ", " +
                             std::to_string(frames_in_flight) +
                             " frame(s) ago, has not completed on the GPU (or was never submitted); "
                             "ShadowSystemDesc::frames_in_flight is " +
                             std::to_string(frames_in_flight) +
                             ": wait for that frame before prepare(), or create the ShadowSystem with as many "
                             "frames in flight as the renderer has");
        }
        GpuTimes kept{slot.frame, {}};
        for (const gpu::ScopeTime& time : *times) kept.passes.push_back({time.name, time.milliseconds});
        retired_times.push_back(std::move(kept));
        while (retired_times.size() > frames_in_flight) retired_times.pop_front();
    }

    explicit Impl(const ShadowSystemDesc& desc)
        : device(make_device(desc.device)),
          settings(checked_settings(desc.settings)),
          frames_in_flight(checked_frames_in_flight(desc.frames_in_flight)),
          map_set_count(desc.maps_per_frame_in_flight ? frames_in_flight : 1),
          timestamps(desc.timestamps),
          compute_timestamps(compute_timestamps_match(device)),
          retired(frames_in_flight),
          // Each part's Vulkan objects are named for it (VK_EXT_debug_utils).
          layouts(gpu::named(device, "set layouts", [&] { return library::create_frame_set_layouts(device); })),
          alpha_mask_layout(
              gpu::named(device, "alpha masks", [&] { return passes::create_alpha_mask_set_layout(device); })),
          local_sets(make_local_sets(0)),  // no scene yet: no static change
          resolve(gpu::named(
              device, "visibility resolve",
              [&] { return passes::VisibilityResolvePass(device, layouts.sampling, settings.shadow.filter); })),
          slots(gpu::named(device, "frame slots", [&] { return library::FrameSlots(device, frames_in_flight); })),
          geometry(device, retired, alpha_mask_layout, [this](const passes::VertexFormats& formats) {
              const gpu::ObjectNames names(device, "caster pipelines");
              prepare_pipelines(formats);
          }) {
        views.push_back(make_view(0));
    }

    // Each part's Vulkan objects are named for it (VK_EXT_debug_utils).
    std::unique_ptr<library::CascadeMaps> make_cascades(size_t index) {
        return gpu::named(device, "cascade maps" + view_suffix(index), [&] {
            return std::make_unique<library::CascadeMaps>(device, layouts.caster, alpha_mask_layout,
                                                          cascade_map_settings(settings.shadow), frames_in_flight);
        });
    }
    // New local maps for the current settings; they hold nothing yet, so the static changes
    // up to `changes_seen` (Geometry::static_change_end()) are in what they draw first.
    std::vector<LocalMapSet> make_local_sets(uint64_t changes_seen) {
        std::vector<LocalMapSet> sets(map_set_count);
        for (LocalMapSet& set : sets) {
            set.static_changes_seen = changes_seen;
            set.maps = gpu::named(device, "local light maps", [&] {
                return std::make_unique<library::LocalMaps>(device, layouts.caster, alpha_mask_layout, settings.shadow,
                                                            retired, frames_in_flight);
            });
        }
        return sets;
    }
    std::unique_ptr<library::VirtualShadowMap> make_virtual_map(size_t index) {
        if (!is_virtual(settings)) return nullptr;
        return gpu::named(device, "virtual shadow map" + view_suffix(index), [&] {
            return std::make_unique<library::VirtualShadowMap>(device, layouts.caster, alpha_mask_layout,
                                                               settings.shadow, frames_in_flight);
        });
    }
    // A view's sun maps for the current settings (they hold nothing yet: every caster is
    // drawn again, and the static changes so far are in that).
    void make_sun_maps(library::SunView& view, size_t index) {
        view.map_sets = std::vector<library::SunMaps>(map_set_count);
        for (library::SunMaps& maps : view.map_sets) {
            maps.cascades = make_cascades(index);
            maps.virtual_map = make_virtual_map(index);
            maps.static_changes_seen = geometry.static_change_end();
        }
    }
    std::unique_ptr<library::SunView> make_view(size_t index) {
        auto view = std::make_unique<library::SunView>(gpu::named(device, "view slots" + view_suffix(index), [&] {
            return library::ViewSlots(device, slots, layouts, resolve.screen_set_layout());
        }));
        make_sun_maps(*view, index);
        geometry.for_each_vertex_format(
            [&](const passes::VertexFormats& formats) { prepare_sun_pipelines(*view, formats); });
        return view;
    }

    // Makes the frame's views `count`: new ones are made first (so that a failure leaves the
    // system as it was), views beyond `count` are retired (frames in flight may use them).
    void fit_view_count(size_t count) {
        std::vector<std::unique_ptr<library::SunView>> added;
        for (size_t index = views.size(); index < count; ++index) added.push_back(make_view(index));
        for (std::unique_ptr<library::SunView>& view : added) views.push_back(std::move(view));
        while (views.size() > count) {
            retired.retire(std::move(views.back()), frame);
            views.pop_back();
        }
    }

    // The caster pipelines of the maps for one vertex format combination of the scene.
    void prepare_sun_pipelines(library::SunView& view, const passes::VertexFormats& formats) {
        for (library::SunMaps& maps : view.map_sets) {
            maps.cascades->prepare_pipelines(formats);
            if (maps.virtual_map) maps.virtual_map->prepare_pipelines(formats);
        }
    }
    void prepare_pipelines(const passes::VertexFormats& formats) {
        const gpu::ObjectNames names(device, "caster pipelines");
        for (const std::unique_ptr<library::SunView>& view : views) prepare_sun_pipelines(*view, formats);
        for (LocalMapSet& set : local_sets) set.maps->prepare_pipelines(formats);
    }

    // Settings that update_settings() took, from the start of a frame (before anything of it
    // is planned): Resource changes replace the maps, Pipeline changes respecialise the
    // resolve (and the moment conversions, which carry the filter's parameters). The
    // replaced objects are retired: frames still in flight may sample them. The scene, the
    // descriptor set layouts and the frame slots stay.
    void apply_pending_settings() {
        if (!pending_settings) return;
        const Settings next = *std::exchange(pending_settings, std::nullopt);
        const SettingEffect effect = settings_change_effect(settings, next);
        const bool moments = is_moment_filter(settings.shadow.filter.mode) || is_moment_filter(next.shadow.filter.mode);
        settings = next;
        if (effect == SettingEffect::Live) return;
        retired.retire(resolve.respecialize(settings.shadow.filter), frame);
        if (effect == SettingEffect::Resource || moments) replace_maps();
    }

    void replace_maps() {
        for (size_t index = 0; index < views.size(); ++index) {
            library::SunView& view = *views[index];
            retired.retire(std::move(view.map_sets), frame);
            make_sun_maps(view, index);
        }
        retired.retire(std::exchange(local_sets, make_local_sets(geometry.static_change_end())), frame);
        geometry.for_each_vertex_format([this](const passes::VertexFormats& formats) { prepare_pipelines(formats); });
    }

    // A setting that changes the depths the caches hold.
    void invalidate_caches() {
        for (const std::unique_ptr<library::SunView>& view : views) {
            for (library::SunMaps& maps : view->map_sets) {
                maps.cascade_cache.invalidate();
                if (maps.virtual_map) maps.virtual_map->invalidate();
            }
        }
        for (LocalMapSet& set : local_sets) set.cache.invalidate();
    }

    ~Impl() {
        // Nothing the caller recorded may still run (the destructor's contract); retired
        // objects go before the pools and passes they came from.
        retired.release(~uint64_t{0} / 2);
    }

    const core::Light* sun() const {
        for (const core::Light& light : lights) {
            if (light.type == LightType::Directional) return &light;
        }
        return nullptr;
    }

    // The local maps frame `frame` draws and samples.
    LocalMapSet& local_set() { return local_sets[frame % local_sets.size()]; }
    const LocalMapSet& local_set() const { return local_sets[frame % local_sets.size()]; }

    // Forgets the static changes every map set has drawn.
    void forget_drawn_static_changes() {
        uint64_t drawn = planned_static_changes;
        for (const LocalMapSet& set : local_sets) drawn = std::min(drawn, set.static_changes_seen);
        for (const std::unique_ptr<library::SunView>& view : views) {
            for (const library::SunMaps& maps : view->map_sets) drawn = std::min(drawn, maps.static_changes_seen);
        }
        geometry.forget_static_changes_before(drawn);
    }

    library::SunView& view_at(const char* call, uint32_t index) const {
        if (index >= views.size()) {
            throw UsageError(std::string("ShadowSystem::") + call + ": view " + std::to_string(index) +
                             " is not a view of the last prepare(), which had " + std::to_string(views.size()));
        }
        return *views[index];
    }

    // What both techniques set of a view's sun: the casters' face culling as the light sees
    // them (the virtual map's pages share the cascades' orientation), its direction and
    // where its shadow ends.
    void set_sun_frame_info(library::SunView& view, const CascadeSet& set, const glm::vec3& direction) {
        view.culling = {settings.shadow.caster_culling,
                        light_facing_is_counter_clockwise(set.cascades.front().view_projection)
                            ? VK_FRONT_FACE_COUNTER_CLOCKWISE
                            : VK_FRONT_FACE_CLOCKWISE};
        info.sun_direction = library::to_public(direction);
        view.info.shadow_distance = set.shadow_distance;
        view.info.cascades.clear();
    }

    // A view's virtual shadow map: the clipmap around its camera and what invalidates its
    // pages; the cascades' uniforms keep the camera and filter values, with no cascade.
    void prepare_virtual_sun(library::SunView& view, const CameraView& camera, const ViewDesc& desc,
                             const passes::CasterScene& scene) {
        const Clock::time_point start = Clock::now();
        const core::Light* sun_light = sun();
        const glm::vec3 direction = sun_light ? glm::normalize(sun_light->direction) : glm::vec3(0.0f, -1.0f, 0.0f);
        const bool casts = sun_light && sun_light->cast_shadows;
        const ShadowSettings placeholder = cascade_map_settings(settings.shadow);
        const CascadeSet set = compute_cascades(camera, direction, placeholder.cascades, geometry.depth_range_bounds());
        view.cascade_draws = std::vector<passes::CascadeDraws>(set.cascades.size());
        view.planned_cascades = set;
        view.sun_casts = false;  // nothing drawn into the cascades' placeholder
        library::VirtualFrameInputs inputs;
        inputs.frame = frame;
        inputs.camera = &camera;
        const FrustumSpan span = vertical_frustum_span(camera);
        inputs.footprint_per_metre = span.per_metre / static_cast<float>(desc.height);
        inputs.footprint_base = span.base / static_cast<float>(desc.height);
        inputs.shadow_distance = set.shadow_distance;
        inputs.light_direction = direction;
        inputs.sun_angular_diameter_degrees = sun_light ? sun_light->angular_diameter_degrees : 0.0f;
        inputs.casts = casts;
        inputs.scene = &scene;
        library::SunMaps& maps = view.maps(frame);
        inputs.static_changes = geometry.static_changes_since(maps.static_changes_seen);
        inputs.depth_range_bounds = geometry.depth_range_bounds();
        maps.virtual_map->prepare(inputs, settings.shadow);
        info.cpu_fit_ms += milliseconds_since(start);
        set_sun_frame_info(view, set, direction);
        // The last frame known complete drew this set too: its counts are this set's.
        view.info.virtual_map = maps.virtual_map->info(frame > frames_in_flight ? frame - frames_in_flight : 0);
        shader::PenumbraShadowUniforms uniforms = library::build_shadow_uniforms(
            camera, set, sun_light, casts, settings.shadow, passes::caster_depth_bias(device, settings.shadow.bias),
            sampling_frame_of(desc));
        uniforms.cascade_count = 0;  // the sun's shadow is the virtual map's (penumbra_sun_is_virtual)
        library::set_contact_uniforms(uniforms, settings.contact);
        std::memcpy(view.slots.at(frame).shadow_uniforms.mapped, &uniforms, sizeof(uniforms));
    }

    // Rotates the Poisson/PCSS patterns (ViewDesc::sampling_frame).
    uint32_t sampling_frame_of(const ViewDesc& desc) const {
        return desc.sampling_frame.value_or(static_cast<uint32_t>(frame - 1));
    }

    void prepare_sun(library::SunView& view, const CameraView& camera, const ViewDesc& desc,
                     const passes::CasterScene& scene) {
        view.info.virtual_map.reset();
        Clock::time_point start = Clock::now();
        const core::Light* sun_light = sun();
        const glm::vec3 direction = sun_light ? glm::normalize(sun_light->direction) : glm::vec3(0.0f, -1.0f, 0.0f);
        CascadeSet set = compute_cascades(camera, direction, settings.shadow.cascades, geometry.depth_range_bounds());
        place_in_layers(set, settings.shadow.cascades.resolution,
                        settings.shadow.strategy != ShadowStrategy::Multiview);
        info.cpu_fit_ms += milliseconds_since(start);
        start = Clock::now();
        const bool casts = sun_light && sun_light->cast_shadows;
        library::SunMaps& maps = view.maps(frame);
        if (!casts) maps.cascade_cache.invalidate();
        // The layered strategy culls on the GPU (record_shadow_maps) into each cascade's four
        // tiles: the plan lists no static caster.
        const bool gpu_culls = settings.shadow.strategy == ShadowStrategy::Layered;
        if (gpu_culls && casts) {
            passes::check_gpu_culling_room(device, scene.draws.size(), 4 * static_cast<uint32_t>(set.cascades.size()));
        }
        view.cascade_draws =
            casts ? maps.cascade_cache.plan(set, scene, settings.shadow.cull_casters, maps.cascades->cached(),
                                            geometry.static_changes_since(maps.static_changes_seen),
                                            settings.shadow.cascades.resolution, !gpu_culls)
                  : std::vector<passes::CascadeDraws>(set.cascades.size());
        view.sun_casts = casts;
        view.planned_cascades = set;
        info.cpu_cull_ms += milliseconds_since(start);
        set_sun_frame_info(view, set, direction);
        for (size_t c = 0; c < set.cascades.size(); ++c) view.info.cascades.push_back(cascade_info(view, set, c));
        shader::PenumbraShadowUniforms uniforms = library::build_shadow_uniforms(
            camera, set, sun_light, casts, settings.shadow, passes::caster_depth_bias(device, settings.shadow.bias),
            sampling_frame_of(desc));
        library::set_contact_uniforms(uniforms, settings.contact);
        std::memcpy(view.slots.at(frame).shadow_uniforms.mapped, &uniforms, sizeof(uniforms));
    }

    CascadeInfo cascade_info(const library::SunView& view, const CascadeSet& set, size_t c) const {
        const Cascade& cascade = set.cascades[c];
        CascadeInfo out{library::to_public(cascade.view_projection),
                        cascade.split_near,
                        cascade.split_far,
                        cascade.texel_world_size,
                        library::to_public(cascade.light_extent),
                        0,
                        0};
        const passes::CascadeDraws& draws = view.cascade_draws[c];
        const library::CascadeDrawStats stats = library::cascade_draw_stats(draws, settings.shadow.cascades.resolution);
        out.draws = stats.draws;
        out.cache_reused = stats.cache_reused;
        out.texels_rendered = stats.texels_rendered;
        out.texels_copied = stats.texels_copied;
        out.layer_origin_x = static_cast<uint32_t>(cascade.layer_origin.x);
        out.layer_origin_y = static_cast<uint32_t>(cascade.layer_origin.y);
        const auto region_of = [](const TexelRect& rect) {
            return TexelRegion{static_cast<uint32_t>(rect.min.x), static_cast<uint32_t>(rect.min.y),
                               static_cast<uint32_t>(rect.max.x - rect.min.x),
                               static_cast<uint32_t>(rect.max.y - rect.min.y)};
        };
        for (const passes::CascadeDraws::Region& region : draws.regions)
            out.redrawn.push_back(region_of(region.window));
        for (const TexelRect& rect : draws.dynamic_window) out.dynamic_regions.push_back(region_of(rect));
        library::for_each_draw(draws, [&](uint32_t draw) { out.triangles += geometry.triangles(draw); });
        // The layered strategy's counts are the GPU's (report_gpu_counts), not the dynamic
        // casters the plan lists.
        if (settings.shadow.strategy == ShadowStrategy::Layered) {
            out.draws = 0;
            out.triangles = 0;
        }
        return out;
    }

    // The layered strategy culls on the GPU while a frame runs: FrameInfo reports the counts
    // of the last frame known complete (this one less frames_in_flight), which the culling
    // copied for the host.
    void report_gpu_counts() {
        if (settings.shadow.strategy != ShadowStrategy::Layered) return;
        if (local_history.size() != frames_in_flight + 1) local_history.assign(frames_in_flight + 1, {});
        LocalLayerHistory& now = local_history[frame % local_history.size()];
        now = {frame, {}};
        for (const LocalShadowSlot& slot : plan.slots) {
            now.ranges.push_back({slot.light, slot.first_layer, static_cast<uint32_t>(slot.view_projection.size())});
        }
        if (frame <= frames_in_flight) return;
        const uint64_t complete = frame - frames_in_flight;
        for (const std::unique_ptr<library::SunView>& view : views) {
            // With the virtual shadow map the cascades' placeholder has no GPU culling.
            const passes::GpuCasterCulling* culling = view->maps(frame).cascades->gpu_culling();
            const auto counted = culling ? culling->culled(complete) : std::nullopt;
            if (!counted) continue;
            // Four culled layers per cascade: its tiles.
            for (size_t c = 0; c < view->info.cascades.size(); ++c) {
                CascadeInfo& out = view->info.cascades[c];
                out.draws = 0;
                out.triangles = 0;
                for (size_t layer = 4 * c; layer < 4 * c + 4 && layer < counted->size(); ++layer) {
                    out.draws += (*counted)[layer].draws;
                    out.triangles += (*counted)[layer].triangles;
                }
            }
        }
        const LocalLayerHistory& then = local_history[complete % local_history.size()];
        const auto counted = local_set().maps->gpu_culling()->culled(complete);
        if (then.frame != complete || !counted) return;
        for (LocalShadowInfo& out : info.local_shadows) {
            for (const LocalLayerRange& range : then.ranges) {
                if (range.light != out.light) continue;
                for (uint32_t layer = range.first_layer;
                     layer < range.first_layer + range.layers && layer < counted->size(); ++layer) {
                    out.draws += (*counted)[layer].draws;
                    out.triangles += (*counted)[layer].triangles;
                }
            }
        }
    }

    // The local lights' maps, shared by the views: each sized for the view that needs it largest.
    void prepare_local(std::span<const SizedCamera> cameras, const passes::CasterScene& scene) {
        Clock::time_point start = Clock::now();
        plan = plan_local_shadows(lights, settings.local_shadows);
        fit_local_shadows(plan, lights, library::caster_bounds(scene));
        size_local_shadows(plan, lights, cameras, settings.local_shadows.resolution);
        info.cpu_fit_ms += milliseconds_since(start);
        start = Clock::now();
        if (settings.shadow.strategy == ShadowStrategy::Layered) {
            passes::check_gpu_culling_room(device, scene.draws.size(), plan.layer_count);
        }
        LocalMapSet& local = local_set();
        local.maps->fit(plan, frame);
        const std::vector<bool> kept =
            settings.shadow.cache_static_casters
                ? local.cache.kept_layers(lights, plan, scene, geometry.static_changes_since(local.static_changes_seen),
                                          local.maps->generation())
                : std::vector<bool>{};
        local_layers = library::cull_local_casters(lights, plan, scene, settings.shadow.cull_casters, kept,
                                                   settings.shadow.strategy == ShadowStrategy::Layered);
        info.cpu_cull_ms += milliseconds_since(start);
        info.local_shadows.clear();
        for (size_t s = 0; s < plan.slots.size(); ++s) {
            const LocalShadowSlot& slot = plan.slots[s];
            LocalShadowInfo out{slot.light,
                                static_cast<uint32_t>(s + 1),
                                slot.first_layer,
                                static_cast<uint32_t>(slot.view_projection.size()),
                                slot.resolution,
                                slot.near_plane,
                                0,
                                0};
            for (const passes::LocalShadowLayer& layer : local_layers) {
                if (layer.layer < slot.first_layer || layer.layer >= slot.first_layer + out.layers) continue;
                if (layer.keep) {
                    ++out.layers_kept;
                    continue;
                }
                out.draws += static_cast<uint32_t>(layer.draws.size());
                for (const uint32_t draw : layer.draws) out.triangles += geometry.triangles(draw);
            }
            info.local_shadows.push_back(out);
        }
        info.unshadowed_lights = plan.unshadowed;
        const shader::PenumbraLocalShadows uniforms = library::build_local_shadows(
            lights, plan, settings.shadow, passes::caster_depth_bias(device, settings.shadow.bias));
        std::memcpy(slots.at(frame).local_shadows.mapped, &uniforms, sizeof(uniforms));
    }

    // The frame's views into FrameInfo: each view's, and the first's in the top-level fields.
    void gather_view_info() {
        info.views.clear();
        for (const std::unique_ptr<library::SunView>& view : views) info.views.push_back(view->info);
        const ViewShadowInfo& first = info.views.front();
        info.cascades = first.cascades;
        info.virtual_map = first.virtual_map;
        info.shadow_distance = first.shadow_distance;
        info.descriptor_set = first.descriptor_set;
    }

    library::FrameSlot& current_slot(const char* call) {
        if (frame == 0) throw UsageError(std::string("ShadowSystem::") + call + ": call prepare() first");
        return slots.at(frame);
    }

    // A view's sun: the virtual shadow map's pages (and the cascades' placeholder once), or
    // the cascades with their cache.
    void record_sun(VkCommandBuffer cmd, library::SunView& view, const passes::CasterScene& scene,
                    gpu::GpuTimer* timer) {
        const VkDescriptorSet caster_set = view.slots.at(frame).caster_set;
        library::SunMaps& maps = view.maps(frame);
        // The maps hold the static changes the frame was planned with once the commands run.
        maps.static_changes_seen = planned_static_changes;
        if (maps.virtual_map) {
            if (!maps.cascade_placeholder_drawn) {
                maps.cascades->record(cmd, caster_set, scene, view.cascade_draws, cascade_map_settings(settings.shadow),
                                      view.culling, false, frame, nullptr);
                maps.cascade_placeholder_drawn = true;
            }
            maps.virtual_map->record_pages(cmd, caster_set, scene, frame, settings.shadow.bias, view.culling, timer);
            return;
        }
        slots.record_placeholder_layout(cmd);
        maps.cascades->record(cmd, caster_set, scene, view.cascade_draws, settings.shadow, view.culling, view.sun_casts,
                              frame, timer);
        // The cache holds this frame's static casters once the commands run.
        if (maps.cascades->cached()) {
            maps.cascade_cache.commit(view.planned_cascades, view.cascade_draws, settings.shadow.cascades.resolution);
        }
    }

    // The visibility slots of the prepared frame: the sun's and one per shadowed local light.
    uint32_t visibility_slot_count() const { return static_cast<uint32_t>(1 + info.local_shadows.size()); }

    // Records the resolve of `screen` into `target` and keeps what it wrote for
    // visibility_image().
    void record_resolve(VkCommandBuffer cmd, uint32_t view_index, const ScreenInputs& screen,
                        const passes::ResolveTarget& target,
                        passes::ResolveQueue queue = passes::ResolveQueue::Graphics);

    // `call`'s resolve of a view into the caller's target, recorded for `queue`.
    void record_into_target(const char* call, VkCommandBuffer cmd, const ScreenInputs& screen,
                            const VisibilityTarget& target, uint32_t view_index, passes::ResolveQueue queue) {
        library::FrameSlot& slot = current_slot(call);
        library::SunView& view = view_at(call, view_index);
        check_visibility_call(call, slot, view.slots.at(frame), cmd, screen);
        check_visibility_target(call, target, screen, visibility_slot_count());
        // Penumbra's own image is not needed while the caller brings one.
        if (view.visibility) retired.retire(std::move(view.visibility), frame);
        record_resolve(cmd, view_index, screen, {target.image, target.view, target.layers}, queue);
    }

    void ensure_visibility_image(library::SunView& view, uint32_t width, uint32_t height, uint32_t slot_count) {
        const uint32_t layers = visibility_layers(slot_count);
        const std::unique_ptr<gpu::Image>& image = view.visibility;
        if (image && image->desc.width == width && image->desc.height == height && image->desc.layers == layers) return;
        retired.retire(std::move(view.visibility), frame);
        const gpu::ObjectNames names(device, "visibility image");
        view.visibility = std::make_unique<gpu::Image>(passes::create_visibility_image(device, width, height, layers));
    }
};

ShadowSystem::ShadowSystem(const ShadowSystemDesc& desc) : impl_(std::make_unique<Impl>(desc)) {}

ShadowSystem::~ShadowSystem() {
    // Frames the caller submitted and did not wait for may still use the maps, buffers and
    // pipelines destroyed below: wait for the queues they run on (DeviceDesc::queue and
    // compute_queue). It returns at once when the caller already waited; a lost device has
    // nothing to wait for, so its result is ignored (a destructor does not throw).
    if (!impl_) return;
    impl_->device->vkQueueWaitIdle(impl_->device.queue());
    if (impl_->device.compute_queue()) impl_->device->vkQueueWaitIdle(impl_->device.compute_queue());
}

MeshId ShadowSystem::add_mesh(const MeshDesc& mesh) { return impl_->geometry.add_mesh(mesh); }
MeshId ShadowSystem::add_mesh(const MeshData& mesh) { return impl_->geometry.add_mesh(mesh); }
void ShadowSystem::remove_mesh(MeshId mesh) { impl_->geometry.remove_mesh(mesh, impl_->frame); }
InstanceId ShadowSystem::add_instance(const InstanceDesc& instance) { return impl_->geometry.add_instance(instance); }
void ShadowSystem::set_instance_transform(InstanceId instance, const Mat4& world) {
    impl_->geometry.set_instance_transform(instance, world);
}
void ShadowSystem::set_instance_flags(InstanceId instance, uint32_t flags) {
    impl_->geometry.set_instance_flags(instance, flags);
}
void ShadowSystem::remove_instance(InstanceId instance) { impl_->geometry.remove_instance(instance); }

void ShadowSystem::set_lights(std::span<const LightDesc> lights) {
    library::check_lights(lights);
    std::vector<core::Light> converted;
    converted.reserve(lights.size());
    for (const LightDesc& light : lights) converted.push_back(library::to_light(light));
    impl_->lights = std::move(converted);
}

SettingsChange ShadowSystem::update_settings(const Settings& settings) {
    validate_settings(settings, "ShadowSystem::update_settings");
    Impl& impl = *impl_;
    const Settings& current = impl.pending_settings ? *impl.pending_settings : impl.settings;
    const core::SettingsDifference difference = core::compare_settings(current, settings);
    SettingsChange change;
    change.effect = difference.effect;
    change.shader_specialization_changed = passes::shadow_filter_specialization(current.shadow.filter) !=
                                           passes::shadow_filter_specialization(settings.shadow.filter);
    // Biases and culling change the depths the caches hold.
    if (difference.any) impl.invalidate_caches();
    impl.pending_settings = settings;
    return change;
}

const Settings& ShadowSystem::settings() const {
    return impl_->pending_settings ? *impl_->pending_settings : impl_->settings;
}

const FrameInfo& ShadowSystem::prepare(const ViewDesc& view) { return prepare(std::span<const ViewDesc>(&view, 1)); }

const FrameInfo& ShadowSystem::prepare(std::span<const ViewDesc> views) {
    check_views(views);
    Impl& impl = *impl_;
    library::FrameSlot& slot = impl.slots.at(impl.frame + 1);
    impl.retire_slot(slot);  // before anything changes: throws when the slot is still in use
    impl.fit_view_count(views.size());
    impl.frame += 1;
    impl.retired.release(impl.frame);
    const Clock::time_point settings_start = Clock::now();
    impl.apply_pending_settings();
    impl.info.cpu_settings_ms = milliseconds_since(settings_start);
    slot.frame = impl.frame;
    slot.shadow_maps_recorded = false;
    slot.timer_started = false;
    impl.info.frame = impl.frame;
    impl.info.sun.reset();
    for (uint32_t i = 0; i < impl.lights.size(); ++i) {
        if (impl.lights[i].type == LightType::Directional) {
            impl.info.sun = i;
            break;
        }
    }

    const Clock::time_point start = Clock::now();
    std::vector<SizedCamera> cameras;
    for (const ViewDesc& view : views) cameras.push_back({camera_of(view), view.height});
    const passes::CasterScene& scene = impl.geometry.build_scene();
    impl.info.cpu_fit_ms = milliseconds_since(start);
    impl.info.cpu_cull_ms = 0.0;
    impl.planned_static_changes = impl.geometry.static_change_end();
    for (size_t v = 0; v < views.size(); ++v) {
        library::SunView& view = *impl.views[v];
        library::ViewSlot& view_slot = view.slots.at(impl.frame);
        view_slot.pages_marked = false;
        view_slot.visibility_recorded = false;
        if (view.maps(impl.frame).virtual_map) {
            impl.prepare_virtual_sun(view, cameras[v].camera, views[v], scene);
        } else {
            impl.prepare_sun(view, cameras[v].camera, views[v], scene);
        }
    }
    impl.prepare_local(cameras, scene);
    impl.report_gpu_counts();
    for (const std::unique_ptr<library::SunView>& view : impl.views) {
        std::optional<library::SampledVirtual> virtual_bindings;
        const library::SunMaps& maps = view->maps(impl.frame);
        if (maps.virtual_map) {
            const library::VirtualShadowMap& map = *maps.virtual_map;
            virtual_bindings = library::SampledVirtual{map.clipmap_buffer(impl.frame), map.page_table(),
                                                       map.page_table_bytes(), map.pool().view};
        }
        const VkDescriptorSet set = view->slots.at(impl.frame).sampling_set;
        impl.slots.write_sampling_set(set, maps.cascades->sampled(), impl.local_set().maps->sampled(),
                                      virtual_bindings);
        view->info.descriptor_set = set;
    }
    impl.gather_view_info();
    return impl.info;
}

void ShadowSystem::record_page_marking(VkCommandBuffer cmd, const ScreenInputs& screen, uint32_t view) {
    Impl& impl = *impl_;
    library::FrameSlot& slot = impl.current_slot("record_page_marking");
    library::SunView& marked = impl.view_at("record_page_marking", view);
    library::ViewSlot& view_slot = marked.slots.at(impl.frame);
    if (slot.shadow_maps_recorded) {
        throw UsageError(
            "ShadowSystem::record_page_marking: record_shadow_maps() was already recorded for this frame; mark the "
            "pages before it");
    }
    if (view_slot.pages_marked) {
        throw UsageError(
            "ShadowSystem::record_page_marking: already recorded for this frame (once per frame and view)");
    }
    if (cmd == VK_NULL_HANDLE) throw InputError("ShadowSystem::record_page_marking: cmd is VK_NULL_HANDLE");
    check_screen("record_page_marking", screen);
    library::VirtualShadowMap* virtual_map = marked.maps(impl.frame).virtual_map.get();
    if (!virtual_map) {  // the cascades have no pages to mark
        view_slot.pages_marked = true;
        return;
    }
    gpu::GpuTimer* timer = impl.timer_of(slot);
    if (timer && !slot.timer_started) timer->begin_frame(cmd);
    slot.timer_started = true;
    const ViewScopes scopes(timer, view);
    virtual_map->record_marking(cmd, impl.frame, screen, timer);
    view_slot.pages_marked = true;
}

void ShadowSystem::record_shadow_maps(VkCommandBuffer cmd) {
    Impl& impl = *impl_;
    library::FrameSlot& slot = impl.current_slot("record_shadow_maps");
    if (slot.shadow_maps_recorded) {
        throw UsageError("ShadowSystem::record_shadow_maps: already recorded for this frame; call prepare() first");
    }
    if (cmd == VK_NULL_HANDLE) throw InputError("ShadowSystem::record_shadow_maps: cmd is VK_NULL_HANDLE");
    for (size_t v = 0; v < impl.views.size(); ++v) {
        if (impl.views[v]->maps(impl.frame).virtual_map && !impl.views[v]->slots.at(impl.frame).pages_marked) {
            throw UsageError("ShadowSystem::record_shadow_maps: the virtual shadow map needs record_page_marking() " +
                             std::string(impl.views.size() > 1 ? "of view " + std::to_string(v) + " " : "") +
                             "earlier in this frame (the pages the frame's pixels sample)");
        }
    }
    gpu::GpuTimer* timer = impl.timer_of(slot);
    if (timer && !slot.timer_started) timer->begin_frame(cmd);
    slot.timer_started = true;
    impl.geometry.record_uploads(cmd, impl.frame);
    // The scene prepare() culled: instances changed since then show in the next frame.
    const passes::CasterScene& scene = impl.geometry.scene();
    for (size_t v = 0; v < impl.views.size(); ++v) {
        const ViewScopes scopes(timer, v);
        impl.record_sun(cmd, *impl.views[v], scene, timer);
    }
    Impl::LocalMapSet& local = impl.local_set();
    local.maps->record(cmd, impl.views.front()->slots.at(impl.frame).caster_set, scene, impl.local_layers, impl.plan,
                       impl.settings.shadow, impl.frame, timer);
    if (impl.settings.shadow.cache_static_casters) local.cache.commit(impl.lights, impl.plan, local.maps->generation());
    local.static_changes_seen = impl.planned_static_changes;
    impl.forget_drawn_static_changes();
    slot.shadow_maps_recorded = true;
}

void ShadowSystem::record_visibility(VkCommandBuffer cmd, const ScreenInputs& screen, uint32_t view) {
    Impl& impl = *impl_;
    library::FrameSlot& slot = impl.current_slot("record_visibility");
    library::SunView& resolved = impl.view_at("record_visibility", view);
    check_visibility_call("record_visibility", slot, resolved.slots.at(impl.frame), cmd, screen);
    impl.ensure_visibility_image(resolved, screen.width, screen.height, impl.visibility_slot_count());
    const gpu::Image& own = *resolved.visibility;
    impl.record_resolve(cmd, view, screen, {own.get(), own.view, own.desc.layers});
}

void ShadowSystem::record_visibility(VkCommandBuffer cmd, const ScreenInputs& screen, const VisibilityTarget& target,
                                     uint32_t view) {
    impl_->record_into_target("record_visibility", cmd, screen, target, view, passes::ResolveQueue::Graphics);
}

void ShadowSystem::record_visibility_async(VkCommandBuffer compute_cmd, const ScreenInputs& screen,
                                           const VisibilityTarget& target, uint32_t view) {
    Impl& impl = *impl_;
    if (!impl.device.shares_with_compute()) {
        throw UsageError(
            "ShadowSystem::record_visibility_async: the ShadowSystem was made without "
            "DeviceDesc::compute_queue_family (async compute); use record_visibility()");
    }
    impl.record_into_target("record_visibility_async", compute_cmd, screen, target, view,
                            passes::ResolveQueue::Compute);
}

void ShadowSystem::Impl::record_resolve(VkCommandBuffer cmd, uint32_t view_index, const ScreenInputs& screen,
                                        const passes::ResolveTarget& target, passes::ResolveQueue queue) {
    library::SunView& view = *views[view_index];
    library::ViewSlot& view_slot = view.slots.at(frame);
    const uint32_t slot_count = visibility_slot_count();
    const glm::mat4 view_projection = library::to_glm(screen.view_projection);
    resolve.write_screen_set(view_slot.screen_set, screen, target.view);
    shader::ResolvePushConstants constants{};
    constants.inverse_view_projection = glm::inverse(view_projection);
    constants.width = screen.width;
    constants.height = screen.height;
    constants.has_normals = screen.normals != VK_NULL_HANDLE ? 1u : 0u;
    constants.normal_encoding = static_cast<uint32_t>(screen.normal_encoding);
    constants.background_depth = screen.background_depth;
    constants.slot_count = slot_count;
    constants.has_face_normals = screen.face_normals != VK_NULL_HANDLE ? 1u : 0u;
    // On the compute queue only where its timestamps count as the graphics queue's do.
    const bool timed = queue == passes::ResolveQueue::Graphics || compute_timestamps;
    gpu::GpuTimer* timer = timed ? timer_of(slots.at(frame)) : nullptr;
    {
        const ViewScopes scopes(timer, view_index);
        gpu::TimedScope scope(device, timer, cmd, "visibility");
        resolve.record(cmd, view_slot.sampling_set, view_slot.screen_set, target, constants, queue);
    }
    view_slot.visibility_recorded = true;
    view.last_visibility = VisibilityImage{
        target.image, target.view, VK_FORMAT_R8G8B8A8_UNORM, screen.width, screen.height, target.layers, slot_count};
}

VisibilityImage ShadowSystem::visibility_image(uint32_t view) const {
    const library::SunView& resolved = impl_->view_at("visibility_image", view);
    if (!resolved.last_visibility) {
        throw UsageError("ShadowSystem::visibility_image: record_visibility() has not been recorded yet" +
                         std::string(view > 0 ? " for view " + std::to_string(view) : ""));
    }
    return *resolved.last_visibility;
}

VkDescriptorSetLayout ShadowSystem::descriptor_set_layout() const { return impl_->layouts.sampling; }

ShaderSpecialization ShadowSystem::shader_specialization(uint32_t first_constant_id) const {
    Impl::Specialization made;
    // The settings of the next prepare(): a caller rebuilds its pipelines right after
    // update_settings() said the specialization changed.
    for (const gpu::SpecializationValue& value : passes::shadow_filter_specialization(settings().shadow.filter)) {
        made.entries.push_back({first_constant_id + value.constant_id,
                                static_cast<uint32_t>(made.data.size() * sizeof(uint32_t)), sizeof(uint32_t)});
        made.data.push_back(value.value);
    }
    const auto same = [&made](const Impl::Specialization& kept) {
        return kept.data == made.data &&
               std::equal(kept.entries.begin(), kept.entries.end(), made.entries.begin(), made.entries.end(),
                          [](const VkSpecializationMapEntry& a, const VkSpecializationMapEntry& b) {
                              return a.constantID == b.constantID && a.offset == b.offset && a.size == b.size;
                          });
    };
    auto kept = std::find_if(impl_->specializations.begin(), impl_->specializations.end(), same);
    if (kept == impl_->specializations.end()) {
        // A deque never moves its elements (nor so their vectors' storage) when it grows.
        impl_->specializations.push_back(std::move(made));
        kept = std::prev(impl_->specializations.end());
    }
    return {kept->entries, kept->data};
}

VkSpecializationInfo ShaderSpecialization::info() const {
    return {static_cast<uint32_t>(entries.size()), entries.data(), data.size_bytes(), data.data()};
}

ShadowMaps ShadowSystem::shadow_maps(uint32_t view) const {
    // The set of the last prepare() (each frame's own with maps_per_frame_in_flight).
    const Impl& impl = *impl_;
    const library::SunMaps& maps = impl.view_at("shadow_maps", view).maps(impl.frame);
    const library::SampledMaps cascades = maps.cascades->sampled();
    const library::SampledMaps local = impl.local_set().maps->sampled();
    MapImage virtual_pool;
    if (maps.virtual_map) {
        const gpu::Image& pool = maps.virtual_map->pool();
        virtual_pool = {pool.get(), pool.view, pool.desc.format, pool.desc.aspect, pool.desc.width, pool.desc.layers};
    }
    return {map_image(cascades.depth), map_image(cascades.moments), map_image(local.depth), map_image(local.moments),
            virtual_pool};
}

std::optional<GpuTimes> ShadowSystem::gpu_times(uint64_t frame) const {
    const Impl& impl = *impl_;
    if (!impl.timestamps || frame == 0 || frame > impl.frame) return std::nullopt;
    if (frame + impl.frames_in_flight <= impl.frame) {  // its slot was reused: what prepare() kept
        for (const GpuTimes& times : impl.retired_times) {
            if (times.frame == frame) return times;
        }
        return std::nullopt;
    }
    const library::FrameSlot& slot = impl.slots.at(frame);
    if (slot.frame != frame || !slot.shadow_maps_recorded) return std::nullopt;
    const std::optional<std::vector<gpu::ScopeTime>> times = slot.timer.read();
    if (!times) return std::nullopt;
    GpuTimes result{frame, {}};
    for (const gpu::ScopeTime& time : *times) result.passes.push_back({time.name, time.milliseconds});
    return result;
}

MemoryStats ShadowSystem::memory() const {
    const Impl& impl = *impl_;
    MemoryStats stats;
    const auto add_culling = [&stats](const passes::GpuCasterCulling* culling) {
        if (culling) stats.buffers += culling->buffer_bytes();
    };
    for (const Impl::LocalMapSet& set : impl.local_sets) {
        stats.local_maps += set.maps->memory_bytes();
        add_culling(set.maps->gpu_culling());
    }
    stats.buffers += impl.slots.buffer_bytes() + impl.geometry.buffer_bytes();
    stats.memory_blocks = static_cast<uint32_t>(impl.device.own_memory_blocks());
    for (const std::unique_ptr<library::SunView>& view : impl.views) {
        stats.visibility += view->visibility ? view->visibility->memory_size : 0u;
        stats.buffers += view->slots.buffer_bytes();
        for (const library::SunMaps& maps : view->map_sets) {
            stats.cascade_maps += maps.cascades->memory_bytes();
            if (maps.virtual_map) {
                stats.virtual_pool += maps.virtual_map->pool_bytes();
                stats.buffers += maps.virtual_map->buffer_bytes();
            }
            add_culling(maps.cascades->gpu_culling());
        }
    }
    return stats;
}

}  // namespace penumbra
