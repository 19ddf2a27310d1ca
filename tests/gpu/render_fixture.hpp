#pragma once
// Rendering for tests: a scene from TOML text, rendered in-process with the validation
// layer on. The returned frame is only valid when the layer reported nothing (including
// while the device and instance were destroyed); the helpers assert that.
#include <ostream>
#include <string>

#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"
#include "renderer/renderer.hpp"

namespace penumbra {

// gtest prints a test's parameter with PrintTo, found by argument-dependent lookup: a filter
// by its name rather than as raw bytes in the test log.
inline void PrintTo(ShadowFilter filter, std::ostream* os) {
    for (const auto& [name, value] : shadow_filter_names()) {
        if (value == filter) *os << name;
    }
}

}  // namespace penumbra

namespace penumbra::testing {

struct RenderedFrame {
    renderer::FrameImages images;
    renderer::FrameInfo info;
    std::vector<std::string> validation_messages;
};

Scene scene_from_toml(const std::string& text);

// Small defaults for lavapipe: 160x120 and a 1024 shadow map.
RenderSettings small_settings(uint32_t width = 160, uint32_t height = 120);

RenderedFrame render_with_validation(const Scene& scene, const RenderSettings& settings);

// Visibility in [0, 1] at a pixel.
inline float visibility_at(const renderer::FrameImages& images, uint32_t x, uint32_t y) {
    return images.visibility[size_t{y} * images.width + x] / 65535.0f;
}

}  // namespace penumbra::testing
