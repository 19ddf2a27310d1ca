#pragma once
// The inverse of load_settings_file(): writes render settings, a camera and a sun as a
// config file (docs/cli.md) that `penumbra render --config` reads back to the same
// values. Floats are written with 9 significant digits, which round-trips every float.
#include <filesystem>
#include <string>

#include "core/render_settings.hpp"
#include "core/scene.hpp"

namespace penumbra {

// Every key of [output] and [shadow], every key of [camera], and [sun] when `sun` is not
// null. The debug view has no config key and is not written.
std::string format_settings_file(const RenderSettings& settings, const Camera& camera, const Light* sun);

// Writes format_settings_file() to `path` atomically (a temporary file renamed into place).
// Throws InputError when the file cannot be written.
void write_settings_file(const std::filesystem::path& path, const RenderSettings& settings, const Camera& camera,
                         const Light* sun);

}  // namespace penumbra
