#pragma once
// The library entry point behind `penumbra render`: load a scene, merge settings from
// the scene file, a config file and explicit overrides, render one frame and write the
// requested image atomically. Errors throw InputError (bad input), DeviceError (no
// usable Vulkan device) or ValidationFailure (the validation layer reported problems).
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "penumbra/device.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"
#include "penumbra/scene/settings_overrides.hpp"

namespace penumbra {

enum class Aov {
    None,     // the tone-mapped colour image (8-bit sRGB RGBA)
    Shadow,   // the sun's visibility, 16-bit gray: 65535 lit, 0 shadowed or facing away
    Cascade,  // the cascade index, 8-bit gray: 0 nearest, 255 none
    Contact,  // the sun's contact-shadow term alone, as Shadow (needs contact shadows on)
};

// The default LoadBudget, its messages naming the flags that raise it.
inline LoadBudget tools_load_budget() {
    LoadBudget budget;
    budget.max_triangles_name = "--max-scene-triangles";
    budget.max_bytes_name = "--max-scene-bytes";
    return budget;
}

struct RenderJob {
    std::string scene;  // a .toml path or "builtin:NAME"; empty = the default scene
    std::filesystem::path output = "penumbra.png";
    std::optional<std::filesystem::path> config;
    SettingsOverrides overrides;        // from the command line: highest priority
    DebugView debug = DebugView::None;  // ShadowMap writes the map's layers instead of the image
    Aov aov = Aov::None;
    // With Aov::Shadow: the [[lights]] index whose visibility is written (`--aov shadow:N`),
    // -1 for the sun. A spot or point light, or the first directional light.
    int32_t aov_light = -1;
    VulkanContextOptions device;
    // What loading the scene may make (--max-scene-triangles, --max-scene-bytes).
    LoadBudget load_budget = tools_load_budget();
};

class ValidationFailure : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct RenderSummary {
    std::filesystem::path output;
    std::string device_name;
    uint32_t width = 0;
    uint32_t height = 0;
};

RenderSummary run_render_job(const RenderJob& job);

// The scene and settings a job renders, merged as `render` does: scene file < config
// file < command line, each source validated under its own name. Shared with `bench`.
struct PreparedJob {
    Scene scene;
    RenderSettings settings;
};
PreparedJob prepare_render_job(const RenderJob& job);

// Throws ValidationFailure when the validation layer reported any message.
void check_validation(const ValidationLog& log);

}  // namespace penumbra
