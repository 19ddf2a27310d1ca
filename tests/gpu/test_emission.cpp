// Emission (scene files' `emissive`, glTF's emissiveFactor and emissiveTexture) is light
// the surface gives off itself: it is added to the colour, unshadowed, and nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render_fixture.hpp"

namespace penumbra::testing {
namespace {

// The renderer's tone curve (apps/renderer/shaders/include/shading.glsl) and the sRGB
// encoding of its R8G8B8A8_SRGB target, for one channel.
double displayed(double radiance) {
    const double x = radiance * 0.8;
    const double mapped = std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    const double encoded = mapped <= 0.0031308 ? 12.92 * mapped : 1.055 * std::pow(mapped, 1.0 / 2.4) - 0.055;
    return encoded * 255.0;
}

// A black ground under the camera, emitting `emissive`; a sun that a box shadows.
std::string emissive_ground_scene(const std::string& emissive, bool sun) {
    std::string text = R"(
[camera]
eye = [0.0, 8.0, 6.0]
target = [0.0, 0.0, 0.0]
fov = 50.0

[ambient]
color = [0.0, 0.0, 0.0]

[[objects]]
type = "plane"
size = [40.0, 40.0]
color = [0.0, 0.0, 0.0]
roughness = 1.0
emissive = )" + emissive +
                       R"(

[[objects]]
type = "box"
size = [2.0, 2.0, 2.0]
translation = [0.0, 1.5, 0.0]
color = [0.0, 0.0, 0.0]
)";
    if (sun) text += "\n[[lights]]\ntype = \"directional\"\ndirection = [0.3, -1.0, 0.2]\nintensity = 3.0\n";
    return text;
}

// Without lights the ground shows exactly its emission, and only red; the box, black and
// not emissive, shows nothing.
TEST(Emission, IsTheColourOfAnUnlitSurface) {
    const RenderedFrame frame = render_with_validation(scene_from_toml(emissive_ground_scene("[0.3, 0.0, 0.0]", false)),
                                                       small_settings(160, 120));
    ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
    const auto& rgba = frame.images.color_rgba8;
    const auto pixel = [&](uint32_t x, uint32_t y) { return &rgba[(size_t{y} * 160 + x) * 4]; };
    const uint8_t* ground = pixel(10, 110);  // a bottom corner: ground, far from the box
    EXPECT_NEAR(ground[0], displayed(0.3), 1.0);
    EXPECT_EQ(ground[1], 0);
    EXPECT_EQ(ground[2], 0);
    const uint8_t* box = pixel(80, 50);  // the box's top, in the middle of the image
    EXPECT_EQ(box[0], 0);
}

// Under a sun, the box's shadow on the emissive ground keeps the emission: the darkest
// ground pixel is the emission itself, not black.
TEST(Emission, IsNotShadowed) {
    const RenderedFrame frame = render_with_validation(scene_from_toml(emissive_ground_scene("[0.0, 0.2, 0.0]", true)),
                                                       small_settings(160, 120));
    ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
    const auto& visibility = frame.images.visibility;
    const auto& rgba = frame.images.color_rgba8;
    size_t shadowed = 0;
    for (size_t i = 0; i < visibility.size(); ++i) {
        if (visibility[i] != 0 || rgba[i * 4 + 1] == 0) continue;  // lit, or the (black) box
        ++shadowed;
        EXPECT_NEAR(rgba[i * 4 + 1], displayed(0.2), 1.0) << "pixel " << i;
    }
    EXPECT_GT(shadowed, 200u) << "the box should shadow part of the ground";
}

}  // namespace
}  // namespace penumbra::testing
