#include "renderer/render_job.hpp"

#include "image/output_files.hpp"
#include "image/png_io.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/settings_files.hpp"
#include "renderer/app_context.hpp"
#include "renderer/debug_images.hpp"
#include "renderer/renderer.hpp"

namespace penumbra {
namespace {

// Writes the output image and returns its size (the shadow-map strip's, not the frame's).
std::pair<uint32_t, uint32_t> write_output(const RenderJob& job, const renderer::FrameImages& images) {
    if (job.debug == DebugView::ShadowMap) {
        const renderer::GrayImage strip = renderer::shadow_map_strip(images);
        write_png_gray8(job.output, strip.width, strip.height, strip.pixels);
        return {strip.width, strip.height};
    }
    switch (job.aov) {
        case Aov::None:
            write_png_rgba8(job.output, images.width, images.height, images.color_rgba8);
            break;
        case Aov::Shadow:
        case Aov::Contact:
            write_png_gray16(job.output, images.width, images.height, images.visibility);
            break;
        case Aov::Cascade:
            write_png_gray8(job.output, images.width, images.height, images.cascade);
            break;
    }
    return {images.width, images.height};
}

// The light whose visibility `--aov shadow:N` writes, checked against the scene: -1 for the
// sun; with `--aov contact`, kVisibilityContact.
int32_t aov_light_index(const RenderJob& job, const Scene& scene) {
    if (job.aov == Aov::Contact) return kVisibilityContact;
    if (job.aov_light < 0) return -1;
    const std::string flag = "--aov shadow:" + std::to_string(job.aov_light);
    if (static_cast<size_t>(job.aov_light) >= scene.lights.size()) {
        throw InputError(flag + ": the scene has " + std::to_string(scene.lights.size()) +
                         " light(s) (indices start at 0)");
    }
    const Light& light = scene.lights[static_cast<size_t>(job.aov_light)];
    if (light.type != LightType::Directional) return job.aov_light;
    if (&light != scene.sun()) {
        throw InputError(flag + ": only the first directional light is rendered; this one is not");
    }
    return -1;
}

}  // namespace

// Scene file < config file < command line; each source is validated under its own name.
PreparedJob prepare_render_job(const RenderJob& job) {
    const std::string scene_spec = job.scene.empty() ? std::string(kDefaultSceneName) : job.scene;
    PreparedJob prepared{load_scene(scene_spec, job.load_budget), RenderSettings{}};
    if (!scene_spec.starts_with(kBuiltinPrefix)) {
        const SettingsOverrides from_scene = load_settings_from_scene_file(scene_spec);
        apply_overrides(from_scene, prepared.settings);
        validate_render_settings(prepared.settings, scene_spec);
    }
    if (job.config) {
        const SettingsOverrides from_config = load_settings_file(*job.config);
        apply_overrides(from_config, prepared.settings);
        apply_overrides(from_config, prepared.scene);
        validate_render_settings(prepared.settings, job.config->string());
        validate_camera_and_sun(prepared.scene, job.config->string());
    }
    apply_overrides(job.overrides, prepared.settings);
    apply_overrides(job.overrides, prepared.scene);
    prepared.settings.debug = job.debug;
    prepared.settings.visibility_light = aov_light_index(job, prepared.scene);
    validate_render_settings(prepared.settings, "command line");
    if (job.aov == Aov::Contact && !(prepared.settings.contact.enabled && prepared.settings.contact.sun)) {
        throw InputError("--aov contact: the sun's contact shadows are off (--contact-shadows turns them on)");
    }
    if (job.debug == DebugView::VirtualPages && prepared.settings.shadow.technique != ShadowTechnique::Virtual) {
        throw InputError("--debug virtual-pages: the sun has cascades (--shadow-technique virtual gives it pages)");
    }
    validate_camera_and_sun(prepared.scene, "command line");
    return prepared;
}

void check_validation(const ValidationLog& log) {
    const size_t count = log.messages.size();
    if (count > 0) {
        throw ValidationFailure("the validation layer reported " + std::to_string(count) +
                                " message(s); no output was written");
    }
}

RenderSummary run_render_job(const RenderJob& job) {
    checked_output_path(job.output);  // before loading and rendering
    const PreparedJob prepared = prepare_render_job(job);
    VulkanContextOptions device_options = job.device;
    device_options.validation_log = std::make_shared<ValidationLog>();
    renderer::FrameImages images;
    std::string device_name;
    {
        const renderer::AppContext context(device_options);
        device_name = context.physical_device_info().name;
        renderer::Renderer renderer(context, prepared.scene, prepared.settings);
        images = renderer.render(prepared.scene.camera);
    }
    // Checked after the device and instance are gone, so leak reports count too.
    check_validation(*device_options.validation_log);
    const auto [width, height] = write_output(job, images);
    return {job.output, device_name, width, height};
}

}  // namespace penumbra
