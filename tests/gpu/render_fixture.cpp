#include "render_fixture.hpp"

#include "penumbra/scene/loader.hpp"
#include "renderer/app_context.hpp"

namespace penumbra::testing {

Scene scene_from_toml(const std::string& text) { return parse_scene_toml(text, "test.toml", "."); }

RenderSettings small_settings(uint32_t width, uint32_t height) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.shadow.cascades.resolution = 1024;
    return settings;
}

RenderedFrame render_with_validation(const Scene& scene, const RenderSettings& settings) {
    VulkanContextOptions options;
    options.validation = true;
    RenderedFrame frame;
    {
        const renderer::AppContext context(options);
        renderer::Renderer renderer(context, scene, settings);
        frame.images = renderer.render(scene.camera);
        frame.info = renderer.last_frame();
    }
    frame.validation_messages = options.validation_log->messages;
    return frame;
}

}  // namespace penumbra::testing
