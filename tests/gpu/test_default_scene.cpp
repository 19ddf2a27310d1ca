// The built-in default scene renders validation-clean, and its images are neither blank
// nor all shadow.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/shadow_filters.hpp"
#include "penumbra/scene/loader.hpp"
#include "render_fixture.hpp"

namespace penumbra::testing {
namespace {

TEST(DefaultScene, RendersValidationCleanWithShadowsAndLight) {
    const Scene scene = load_scene(std::string(kDefaultSceneName));
    const RenderedFrame frame = render_with_validation(scene, small_settings(240, 135));
    ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();

    const auto& visibility = frame.images.visibility;
    const size_t shadowed = std::count_if(visibility.begin(), visibility.end(), [](uint16_t v) { return v < 32768; });
    const size_t lit = std::count(visibility.begin(), visibility.end(), uint16_t{65535});
    EXPECT_GT(shadowed, visibility.size() / 100) << "the default scene should show shadows";
    EXPECT_GT(lit, visibility.size() / 2) << "the default scene should be mostly lit";

    // The colour image is not blank: many distinct colours.
    std::set<uint32_t> colours;
    for (size_t i = 0; i + 3 < frame.images.color_rgba8.size(); i += 4) {
        const auto* p = &frame.images.color_rgba8[i];
        colours.insert(p[0] | (p[1] << 8) | (p[2] << 16));
    }
    EXPECT_GT(colours.size(), 200u);
}

// `cast_shadows = false` on the sun: no shadow anywhere, and no caster is drawn into the
// cascades (they are only cleared), with a depth filter and with a moment filter.
TEST(DefaultScene, SunWithoutShadowsIsFullyLitWhereItFacesTheLight) {
    Scene scene = load_scene(std::string(kDefaultSceneName));
    for (Light& light : scene.lights) light.cast_shadows = false;
    for (const ShadowFilter filter : {ShadowFilter::Hard, ShadowFilter::Vsm}) {
        RenderSettings settings = small_settings(120, 68);
        settings.shadow.filter.mode = filter;
        const RenderedFrame frame = render_with_validation(scene, settings);
        ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
        // Only surfaces facing away from the sun (N.L <= 0) may be dark: the lit ground dominates.
        const auto& visibility = frame.images.visibility;
        const size_t partial =
            std::count_if(visibility.begin(), visibility.end(), [](uint16_t v) { return v != 0 && v != 65535; });
        EXPECT_EQ(partial, 0u) << "without shadows visibility is exactly 0 (facing away) or 1";
        const size_t lit = std::count(visibility.begin(), visibility.end(), uint16_t{65535});
        EXPECT_GT(lit, visibility.size() / 2);
        ASSERT_FALSE(frame.info.cascades.empty());
        for (const CascadeInfo& cascade : frame.info.cascades) {
            EXPECT_EQ(cascade.draws, 0u) << "a sun without shadows renders no casters";
        }
    }
}

}  // namespace
}  // namespace penumbra::testing
