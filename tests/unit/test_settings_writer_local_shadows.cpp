// The local shadow settings (spot/point lights) go through a saved config file and back:
// what `penumbra view` saves, `penumbra render --config` renders with.
#include <gtest/gtest.h>

#include "penumbra/errors.hpp"
#include "penumbra/scene/settings_files.hpp"

namespace penumbra {
namespace {

TEST(SettingsWriterLocalShadows, BudgetAndResolutionRoundTrip) {
    RenderSettings written;
    written.local_shadows.budget = 3;
    written.local_shadows.resolution = 96;  // any size 16..8192, not only powers of two
    const std::string text = format_settings_file(written, Camera{}, nullptr);
    EXPECT_NE(text.find("local_shadow_budget = 3\n"), std::string::npos) << text;
    EXPECT_NE(text.find("local_shadow_resolution = 96\n"), std::string::npos) << text;

    RenderSettings read;
    apply_overrides(parse_settings_text(text, "saved.toml"), read);
    EXPECT_EQ(read.local_shadows.budget, 3u);
    EXPECT_EQ(read.local_shadows.resolution, 96u);
}

TEST(SettingsWriterLocalShadows, ZeroBudgetRoundTrips) {
    RenderSettings written;
    written.local_shadows.budget = 0;  // every local light unshadowed
    RenderSettings read;
    apply_overrides(parse_settings_text(format_settings_file(written, Camera{}, nullptr), "saved.toml"), read);
    EXPECT_EQ(read.local_shadows.budget, 0u);
    EXPECT_EQ(read.local_shadows.resolution, written.local_shadows.resolution);
}

TEST(SettingsWriterLocalShadows, SizingRoundTripsAndBadNamesAreOneLine) {
    for (const LocalShadowSizing sizing : {LocalShadowSizing::Fixed, LocalShadowSizing::Coverage}) {
        RenderSettings written;
        written.local_shadows.sizing = sizing;
        RenderSettings read;
        read.local_shadows.sizing =
            sizing == LocalShadowSizing::Fixed ? LocalShadowSizing::Coverage : LocalShadowSizing::Fixed;
        apply_overrides(parse_settings_text(format_settings_file(written, Camera{}, nullptr), "saved.toml"), read);
        EXPECT_EQ(read.local_shadows.sizing, sizing);
    }
    try {
        parse_settings_text("[shadow]\nlocal_shadow_sizing = \"screen\"\n", "bad.toml");
        FAIL() << "an unknown sizing must be rejected";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("bad.toml: shadow.local_shadow_sizing"), std::string::npos) << message;
        EXPECT_NE(message.find("coverage"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace penumbra
