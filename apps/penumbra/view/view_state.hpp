#pragma once
// What the viewer shows and what its panel, keyboard and script change: the scene (its
// camera and sun are live), the settings the next frame renders with, and requests that
// the frame loop carries out (screenshot, save settings, resize, quit).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"
#include "view_controls.hpp"

namespace penumbra::view {

struct Requests {
    std::optional<std::filesystem::path> screenshot;
    std::optional<std::filesystem::path> save_settings;
    std::optional<VkExtent2D> resize;
    bool quit = false;
};

struct ViewState {
    Scene scene;
    RenderSettings settings;  // wanted for the next frame; the renderer follows (recreated if needed)
    CameraController camera;
    bool show_ui = true;
    bool animate_sun = false;
    float sun_degrees_per_second = 15.0f;
    std::filesystem::path settings_file;  // where F5 / "Save settings" write
    std::filesystem::path screenshot_file;
    Requests requests;
    std::string status;  // the last message for the panel (a rejected setting, a saved file)

    // The first directional light, or nullptr.
    Light* sun() {
        for (Light& light : scene.lights) {
            if (light.type == LightType::Directional) return &light;
        }
        return nullptr;
    }
};

}  // namespace penumbra::view
