// run_compare_job: renders the frames, traces their references and measures them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "compare/compare_job.hpp"
#include "compare/compare_report.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/scene/inventory.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/shadow_system.hpp"
#include "quality/camera_jitter.hpp"
#include "quality/local_light_reference.hpp"
#include "quality/reference_visibility.hpp"
#include "quality/shadow_ray_tracer.hpp"
#include "renderer/frame_uniforms.hpp"
#include "renderer/renderer.hpp"

namespace penumbra::compare {
namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

constexpr uint8_t kNoCascade = 255;  // FrameImages::cascade where no cascade covers the pixel

// The camera a frame was rendered with, as the stability metrics read it.
struct FrameCamera {
    glm::mat4 view_projection{1.0f};
    glm::vec3 eye{0.0f};
    float fov_y_radians = 1.0f;
};

// One frame reduced to what the metrics read.
struct CapturedFrame {
    std::vector<float> rendered;
    std::vector<uint8_t> hard;
    std::vector<uint8_t> evaluated;
    std::vector<uint8_t> contact;  // quality::ReferenceImages::contact (frame 0, sun only)
    std::vector<glm::vec4> positions;
    FrameCamera camera;
};

Vec3 to_vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

glm::mat4 to_glm(const Mat4& m) {
    glm::mat4 result;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) result[column][row] = m(row, column);
    }
    return result;
}

ViewDesc view_of(const Camera& camera, const RenderSettings& settings) {
    return look_at_view(to_vec3(camera.eye), to_vec3(camera.target), to_vec3(camera.up),
                        glm::radians(camera.fov_y_degrees), camera.near_plane, camera.far_plane, settings.width,
                        settings.height);
}

FrameCamera frame_camera(const Camera& camera, const RenderSettings& settings) {
    const ViewDesc view = view_of(camera, settings);
    return {to_glm(reverse_z_projection(view)) * to_glm(view.view), camera.eye, view.fov_y_radians};
}

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

// The spot or point light `--light index` names, checked to be one the renderer lights
// and shadows (shadow-casting, among the lit lights); null when it names the sun. Whether
// it got a shadow within the budget is checked on the rendered frame
// (require_local_shadow()).
const Light* require_local_light(const Scene& scene, int32_t index) {
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
    const std::vector<uint32_t> lit = renderer::lit_local_lights(scene.lights);
    if (std::find(lit.begin(), lit.end(), static_cast<uint32_t>(index)) == lit.end()) {
        throw InputError(flag + ": " + kind + " is beyond the " + std::to_string(kMaxLocalLights) +
                         " spot/point lights the renderer lights");
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
        if (images.world_normal[i].w > 0.5f) {  // the geometry AOV marks instances that receive no shadow
            counts.not_receiving += 1;
        } else if (!quality::faces_sun(images.world_position[i], images.world_normal[i], to_sun)) {
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
        if (images.world_normal[i].w > 0.5f) {
            counts.not_receiving += 1;
            continue;
        }
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
        target.local_light ? quality::trace_local_light_reference(tracer, surfaces, *target.local_light,
                                                                  target.sun.rays, target.sun.progress)
                           : quality::trace_reference(tracer, surfaces, target.sun);
    frame.positions = std::move(surfaces.positions);
    frame.hard = std::move(reference.hard);
    frame.contact = std::move(reference.contact);
    if (soft) *soft = std::move(reference.soft);
    return frame;
}

// A frame of a ShadowSystem of its own, with the scene's lights as the renderer gives them
// and no geometry: which lights get shadow maps, and the cascades' fit, depend only on the
// lights, the camera and the settings.
FrameInfo shadow_plan(const renderer::AppContext& context, const PreparedJob& prepared, const Settings& settings) {
    ShadowSystemDesc desc;
    desc.device = context.device_desc();
    desc.settings = settings;
    desc.frames_in_flight = 1;
    ShadowSystem shadows(desc);
    shadows.set_lights(renderer::shadow_lights(prepared.scene.lights));
    return shadows.prepare(view_of(prepared.scene.camera, prepared.settings));
}

// The unit of the camera motions: a texel of the nearest cascade as the stable fit sizes
// it, whatever the fit in use, so that runs that differ only in fitting move the camera
// identically.
float motion_texel_size(const renderer::AppContext& context, const PreparedJob& prepared) {
    Settings settings = static_cast<const Settings&>(prepared.settings);
    settings.shadow.cascades.fit = FitMode::Stable;
    const FrameInfo frame = shadow_plan(context, prepared, settings);
    return frame.cascades.empty() ? 0.01f : frame.cascades.front().texel_world_size;
}

// Rejects a spot or point light that the budget leaves unshadowed, before anything renders.
void require_local_shadow(const renderer::AppContext& context, const PreparedJob& prepared, const Light& light,
                          int32_t index) {
    const FrameInfo frame = shadow_plan(context, prepared, static_cast<const Settings&>(prepared.settings));
    const bool shadowed = std::any_of(frame.local_shadows.begin(), frame.local_shadows.end(),
                                      [&](const LocalShadowInfo& info) { return info.light == uint32_t(index); });
    if (!shadowed) {
        throw InputError("--light " + std::to_string(index) + ": light " + std::to_string(index) + " (" +
                         light_type_name(light.type) + ") is beyond the local shadow budget of " +
                         std::to_string(prepared.settings.local_shadows.budget) +
                         " and renders unshadowed (raise --local-shadow-budget)");
    }
}

// Frame 0 rendered again with its sampling pattern rotated (the next frame's rotation),
// nothing else changed: the grain of Poisson and PCSS, reported apart from stability.
quality::SamplingNoise rotated_pattern_noise(renderer::Renderer& renderer, const Camera& camera,
                                             const CapturedFrame& frame_0) {
    renderer.fix_sampling_pattern(1);
    const renderer::FrameImages rotated = renderer.render(camera);
    renderer.fix_sampling_pattern(0);
    return quality::sampling_noise(frame_0.rendered, visibility_as_float(rotated.visibility), frame_0.evaluated);
}

// Renders frame 0 and then frames 1.. with the cascades fitted to slightly moved cameras
// (the image itself stays put, so each pixel shows the same surface point in every frame
// and any change of its visibility is the shadow map's: shimmer). Each frame's reference
// is traced right away (frame 0's with the soft reference too). A spot or point light has
// no cascades to refit: one frame only.
std::vector<CapturedFrame> render_and_trace(const CompareJob& job, const PreparedJob& prepared,
                                            const quality::ShadowRayTracer& tracer, CompareResult& result) {
    VulkanContextOptions device_options = job.render.device;
    device_options.validation_log = std::make_shared<ValidationLog>();
    std::vector<CapturedFrame> frames;
    {
        const renderer::AppContext context(device_options);
        result.device_name = context.physical_device_info().name;
        if (result.local_light) {
            require_local_shadow(context, prepared, *result.local_light, job.light);
        } else {
            result.nearest_texel_world_size = motion_texel_size(context, prepared);
        }
        renderer::Renderer renderer(context, prepared.scene, prepared.settings);
        // Stability measures the shadow map's own changes under camera motion: the Poisson
        // and PCSS patterns, which otherwise rotate every frame, stay as in frame 0.
        renderer.fix_sampling_pattern(0);
        TraceTarget target{{result.to_sun, result.sun_angular_diameter_degrees, job.rays, kContactReachMetres},
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
            if (job.progress) {
                target.sun.progress = [&job, k, frame_count](uint32_t done, uint32_t rows) {
                    job.progress(k, frame_count, done, rows);
                };
            }
            PixelCounts counts;
            frames.push_back(capture(images, tracer, target, counts, k == 0 ? &result.images.frame.soft : nullptr));
            frames.back().camera = frame_camera(camera, prepared.settings);
            result.timings.trace_ms += milliseconds_since(start);
            if (k == 0) {
                result.pixels = counts;
                result.sampling_noise = rotated_pattern_noise(renderer, camera, frames.back());
            }
            target.sun.rays = 0;  // later frames: the hard reference only
            target.sun.contact_reach = 0.0f;
        }
    }
    // Checked after the device and instance are gone, so leak reports count too.
    check_validation(*device_options.validation_log);
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
    result.contact = quality::contact_metrics(frame, frames[0].contact, kContactBandPixels);
    result.pixels.shadowed = 0;
    for (size_t i = 0; i < frame.hard.size(); ++i) result.pixels.shadowed += frame.evaluated[i] && frame.hard[i] == 0;
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
    // An empty folder would put seven files into the current one: say "." for that.
    if (job.out_dir.empty()) throw InputError("--out-dir: empty; name a folder (\".\" for the current one)");
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
    check_compare_outputs(job);  // before minutes of rendering and tracing
    const std::string scene_name = job.render.scene.empty() ? std::string(kDefaultSceneName) : job.render.scene;
    return compare_prepared(job, prepare_render_job(job.render), scene_name);
}

CompareResult compare_prepared(const CompareJob& job, PreparedJob prepared, const std::string& scene_name) {
    validate_compare_job(job);
    const Light* local_light = job.light >= 0 ? require_local_light(prepared.scene, job.light) : nullptr;
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
