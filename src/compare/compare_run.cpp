// run_compare_job: renders the frames, traces their references and measures them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "compare/compare_job.hpp"
#include "core/camera_math.hpp"
#include "core/cascades.hpp"
#include "core/local_lights.hpp"
#include "penumbra/errors.hpp"
#include "quality/camera_jitter.hpp"
#include "quality/local_light_reference.hpp"
#include "quality/reference_visibility.hpp"
#include "quality/shadow_ray_tracer.hpp"
#include "renderer/renderer.hpp"
#include "scene/scene_loader.hpp"

namespace penumbra::compare {
namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

constexpr uint8_t kNoCascade = 255;  // FrameImages::cascade where no cascade covers the pixel

// One frame reduced to what the metrics read.
struct CapturedFrame {
    std::vector<float> rendered;
    std::vector<uint8_t> hard;
    std::vector<uint8_t> evaluated;
    std::vector<glm::vec4> positions;
    CameraView camera;
};

const Light& require_sun(const Scene& scene, const std::string& origin) {
    const Light* sun = scene.sun();
    if (!sun) {
        throw InputError(origin +
                         ": compare needs a directional light (the sun) to trace shadow rays toward; "
                         "the scene has none");
    }
    if (!sun->cast_shadows) throw InputError(origin + ": the sun casts no shadows (cast_shadows = false)");
    return *sun;
}

const char* light_type_name(LightType type) {
    return type == LightType::Spot ? "spot" : type == LightType::Point ? "point" : "directional";
}

// The spot or point light `--light index` names, checked to cast a shadow the renderer
// draws (shadow-casting, lit, within the shadow budget); null when it names the sun.
const Light* require_local_light(const Scene& scene, const RenderSettings& settings, int32_t index) {
    const std::string flag = "--light " + std::to_string(index);
    if (static_cast<size_t>(index) >= scene.lights.size()) {
        throw InputError(flag + ": the scene has " + std::to_string(scene.lights.size()) +
                         " light(s) (indices start at 0)");
    }
    const Light& light = scene.lights[static_cast<size_t>(index)];
    const std::string kind = std::string("light ") + std::to_string(index) + " (" + light_type_name(light.type) + ")";
    if (light.type == LightType::Directional) {
        if (&light != scene.sun()) {
            throw InputError(flag + ": " + kind + " is not rendered (only the first directional light is the sun)");
        }
        return nullptr;
    }
    if (!light.cast_shadows) throw InputError(flag + ": " + kind + " casts no shadows (cast_shadows = false)");
    const LocalShadowPlan plan = plan_local_shadows(scene, settings.local_shadows);
    const auto lit = std::find(plan.local_lights.begin(), plan.local_lights.end(), static_cast<uint32_t>(index));
    if (lit == plan.local_lights.end()) {
        throw InputError(flag + ": " + kind + " is beyond the " + std::to_string(kMaxLocalLights) +
                         " spot/point lights the renderer lights");
    }
    const bool shadowed = std::any_of(plan.slots.begin(), plan.slots.end(), [&](const LocalShadowSlot& slot) {
        return slot.light == static_cast<uint32_t>(index);
    });
    if (!shadowed) {
        throw InputError(flag + ": " + kind + " is beyond the local shadow budget of " +
                         std::to_string(settings.local_shadows.budget) +
                         " and renders unshadowed (raise --local-shadow-budget)");
    }
    return &light;
}

std::vector<float> visibility_as_float(const std::vector<uint16_t>& visibility) {
    std::vector<float> values(visibility.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(visibility[i]) / 65535.0f;
    return values;
}

// Evaluated pixels: geometry, facing the sun, inside the shadow distance.
std::vector<uint8_t> evaluated_pixels(const renderer::FrameImages& images, const glm::vec3& to_sun,
                                      PixelCounts& counts) {
    counts = PixelCounts{};
    std::vector<uint8_t> evaluated(images.world_position.size(), 0);
    for (size_t i = 0; i < evaluated.size(); ++i) {
        counts.total += 1;
        if (images.world_position[i].w <= 0.5f) continue;
        counts.geometry += 1;
        if (!quality::faces_sun(images.world_position[i], images.world_normal[i], to_sun)) {
            counts.facing_away += 1;
        } else if (images.cascade[i] == kNoCascade) {
            counts.beyond_shadow_distance += 1;
        } else {
            evaluated[i] = 1;
            counts.evaluated += 1;
        }
    }
    return evaluated;
}

// A spot or point light's evaluated pixels: geometry, facing the light point, inside its
// range and where the cone factor exceeds kMinConeFactor. There `rendered` (the AOV,
// shadow x cone) becomes the shadow term alone: divided by the cone factor computed as the
// shader does, so that the reference stays a pure visibility (binary for the hard metrics).
std::vector<uint8_t> evaluated_local_pixels(const renderer::FrameImages& images, const Light& light,
                                            PixelCounts& counts, std::vector<float>& rendered) {
    counts = PixelCounts{};
    std::vector<uint8_t> evaluated(images.world_position.size(), 0);
    for (size_t i = 0; i < evaluated.size(); ++i) {
        counts.total += 1;
        const glm::vec4& position = images.world_position[i];
        if (position.w <= 0.5f) continue;
        counts.geometry += 1;
        if (glm::dot(glm::vec3(images.world_normal[i]), light.position - glm::vec3(position)) <= 0.0f) {
            counts.facing_away += 1;
            continue;
        }
        const float cone = quality::light_reach(light, position, images.world_normal[i]);
        if (cone <= kMinConeFactor) {
            counts.outside_light += 1;
            continue;
        }
        evaluated[i] = 1;
        counts.evaluated += 1;
        rendered[i] = std::min(rendered[i] / cone, 1.0f);
    }
    return evaluated;
}

// What the reference is traced toward: the sun's options, or a spot/point light.
struct TraceTarget {
    quality::ReferenceOptions sun;
    const Light* local_light = nullptr;
};

CapturedFrame capture(renderer::FrameImages& images, const quality::ShadowRayTracer& tracer, const TraceTarget& target,
                      PixelCounts& counts, std::vector<float>* soft) {
    CapturedFrame frame;
    frame.rendered = visibility_as_float(images.visibility);
    frame.evaluated = target.local_light ? evaluated_local_pixels(images, *target.local_light, counts, frame.rendered)
                                         : evaluated_pixels(images, target.sun.to_sun, counts);
    quality::SurfaceImage surfaces{images.width, images.height, std::move(images.world_position),
                                   std::move(images.world_normal)};
    quality::ReferenceImages reference =
        target.local_light
            ? quality::trace_local_light_reference(tracer, surfaces, *target.local_light, target.sun.rays)
            : quality::trace_reference(tracer, surfaces, target.sun);
    frame.positions = std::move(surfaces.positions);
    frame.hard = std::move(reference.hard);
    if (soft) *soft = std::move(reference.soft);
    return frame;
}

// The unit of the camera motions: a texel of the nearest cascade as the stable fit sizes
// it, whatever the fit in use, so that runs that differ only in fitting move the camera
// identically.
float aspect_of(const RenderSettings& settings) {
    return static_cast<float>(settings.width) / static_cast<float>(settings.height);
}

float motion_texel_size(const PreparedJob& prepared, const glm::vec3& light_direction) {
    CascadeSettings cascades = prepared.settings.shadow.cascades;
    cascades.fit = FitMode::Stable;
    const CascadeSet set = compute_cascades(make_camera_view(prepared.scene.camera, aspect_of(prepared.settings)),
                                            light_direction, cascades, prepared.scene.world_bounds());
    return set.cascades.empty() ? 0.01f : set.cascades.front().texel_world_size;
}

// Renders frame 0 and then frames 1.. with the cascades fitted to slightly moved cameras
// (the image itself stays put, so each pixel shows the same surface point in every frame
// and any change of its visibility is the shadow map's: shimmer). Each frame's reference
// is traced right away (frame 0's with the soft reference too). A spot or point light has
// no cascades to refit: one frame only.
std::vector<CapturedFrame> render_and_trace(const CompareJob& job, const PreparedJob& prepared,
                                            const quality::ShadowRayTracer& tracer, CompareResult& result) {
    gpu::ContextOptions device_options = job.render.device;
    device_options.log = std::make_shared<gpu::ValidationLog>();
    std::vector<CapturedFrame> frames;
    {
        gpu::Context context(device_options);
        result.device_name = context.info().name;
        renderer::Renderer renderer(context, prepared.scene, prepared.settings);
        TraceTarget target{{result.to_sun, result.sun_angular_diameter_degrees, job.rays},
                           result.local_light ? &*result.local_light : nullptr};
        const uint32_t frame_count = result.local_light ? 1 : job.stability_frames;
        for (uint32_t k = 0; k < frame_count; ++k) {
            const Camera& camera = prepared.scene.camera;
            if (k > 0) {
                renderer.fit_cascades_to(quality::jittered_camera(camera, k, result.nearest_texel_world_size));
            }
            Clock::time_point start = Clock::now();
            renderer::FrameImages images = renderer.render(camera);
            result.timings.render_ms += milliseconds_since(start);
            if (k == 0) {
                result.images.color_rgba8 = images.color_rgba8;
                result.images.world_position = images.world_position;
            }
            start = Clock::now();
            PixelCounts counts;
            frames.push_back(capture(images, tracer, target, counts, k == 0 ? &result.images.frame.soft : nullptr));
            frames.back().camera = make_camera_view(camera, aspect_of(prepared.settings));
            result.timings.trace_ms += milliseconds_since(start);
            if (k == 0) result.pixels = counts;
            target.sun.rays = 0;  // later frames: the hard reference only
        }
    }
    // Checked after the device and instance are gone, so leak reports count too.
    check_validation(*device_options.log);
    return frames;
}

void measure(std::vector<CapturedFrame>& frames, const CompareJob& job, CompareResult& result) {
    quality::VisibilityComparison& frame = result.images.frame;
    frame.width = result.settings.width;
    frame.height = result.settings.height;
    frame.rendered = frames[0].rendered;
    frame.hard = frames[0].hard;
    frame.evaluated = frames[0].evaluated;
    const std::vector<uint8_t> boundary =
        quality::shadow_boundary(frame.width, frame.height, frame.hard, frame.evaluated);
    const std::vector<uint8_t> band = quality::edge_band(frame.width, frame.height, boundary, job.edge_band);
    result.hard = quality::hard_shadow_metrics(frame, boundary, band);
    result.soft = quality::soft_shadow_metrics(frame, boundary, band);

    std::vector<quality::StabilityFrame> stability;
    for (const CapturedFrame& captured : frames) {
        stability.push_back({captured.rendered, captured.hard, captured.evaluated, captured.positions,
                             captured.camera.view_projection, captured.camera.eye});
    }
    const float pixel_angle = 2.0f * std::tan(frames[0].camera.fov_y_radians * 0.5f) / static_cast<float>(frame.height);
    result.stability = quality::stability_metrics(stability, {frame.width, frame.height, pixel_angle});
}

}  // namespace

void validate_compare_job(const CompareJob& job) {
    if (job.rays < 1 || job.rays > kMaxRays) {
        throw InputError("--rays: must be 1.." + std::to_string(kMaxRays) + ", got " + std::to_string(job.rays));
    }
    if (job.stability_frames < 1 || job.stability_frames > kMaxStabilityFrames) {
        throw InputError("--stability-frames: must be 1.." + std::to_string(kMaxStabilityFrames) + ", got " +
                         std::to_string(job.stability_frames));
    }
    if (job.light < -1)
        throw InputError("--light: must be a light index (0, 1, ...), got " + std::to_string(job.light));
    if (job.edge_band > kMaxEdgeBand) {
        throw InputError("--edge-band: must be 0.." + std::to_string(kMaxEdgeBand) + ", got " +
                         std::to_string(job.edge_band));
    }
}

CompareResult run_compare_job(const CompareJob& job) {
    validate_compare_job(job);
    const std::string scene_name = job.render.scene.empty() ? std::string(kDefaultSceneName) : job.render.scene;
    return compare_prepared(job, prepare_render_job(job.render), scene_name);
}

CompareResult compare_prepared(const CompareJob& job, PreparedJob prepared, const std::string& scene_name) {
    validate_compare_job(job);
    const Light* local_light =
        job.light >= 0 ? require_local_light(prepared.scene, prepared.settings, job.light) : nullptr;
    prepared.settings.geometry_aovs = true;
    prepared.settings.visibility_light = local_light ? job.light : -1;

    CompareResult result;
    result.version = PENUMBRA_VERSION;
    result.scene = scene_name;
    result.settings = prepared.settings;
    result.job = job;
    if (local_light) {
        result.light_index = job.light;
        result.local_light = *local_light;
        result.stability_note =
            "not measured: it jitters the fit of the sun's cascades, which spot and point light shadow maps "
            "do not use";
    } else {
        const Light& sun = require_sun(prepared.scene, scene_name);
        result.light_index = static_cast<int32_t>(&sun - prepared.scene.lights.data());
        result.to_sun = -glm::normalize(sun.direction);
        result.sun_angular_diameter_degrees = sun.angular_diameter_degrees;
        result.nearest_texel_world_size = motion_texel_size(prepared, glm::normalize(sun.direction));
    }

    const Clock::time_point start = Clock::now();
    const quality::ShadowRayTracer tracer(prepared.scene);
    result.timings.bvh_ms = milliseconds_since(start);
    result.triangles = tracer.triangle_count();

    std::vector<CapturedFrame> frames = render_and_trace(job, prepared, tracer, result);
    measure(frames, job, result);
    return result;
}

}  // namespace penumbra::compare
