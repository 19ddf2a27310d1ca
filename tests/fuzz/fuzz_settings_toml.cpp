// libFuzzer harness: config files ([output], [shadow], [camera], [sun]). Any input must
// parse, apply and validate, or throw one InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "penumbra/errors.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/settings_files.hpp"
#include "penumbra/scene/settings_overrides.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const penumbra::SettingsOverrides overrides = penumbra::parse_settings_text(text, "fuzz.toml");
        penumbra::RenderSettings settings;
        penumbra::apply_overrides(overrides, settings);
        penumbra::validate_render_settings(settings, "fuzz.toml");
        penumbra::Scene scene;
        penumbra::apply_overrides(overrides, scene);
        penumbra::validate_camera_and_sun(scene, "fuzz.toml");
    } catch (const penumbra::InputError&) {
    }
    return 0;
}
