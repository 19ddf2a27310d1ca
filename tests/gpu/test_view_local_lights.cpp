// `penumbra view` and spot/point lights: the local shadow budget and resolution are config
// keys that a script sets (`set shadow.local_shadow_budget = N`), the viewer re-creates the
// renderer for them validation-clean, its `--screenshot-aov shadow:N` equals `penumbra
// render --aov shadow:N` with the same flags, and the saved config reproduces it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli_runner.hpp"
#include "image/png_io.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"
#include "script.hpp"

using penumbra::testing::read_text;
using penumbra::testing::RunResult;

namespace {

bool have_xvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

// A box on a plane lit by the sun (light 0), a spot from above (light 1) and a point light
// beside the box at its height (light 2), which throws a long shadow across the ground.
constexpr const char* kLocalLightsScene = R"toml(
[camera]
eye = [0.0, 7.0, 9.0]
target = [0.0, 0.5, 0.0]
fov = 60.0

[[lights]]
type = "directional"
direction = [-0.4, -1.0, -0.3]
intensity = 1.0

[[lights]]
type = "spot"
position = [1.5, 6.0, 1.0]
direction = [-0.25, -1.0, -0.15]
inner_angle = 25.0
outer_angle = 35.0
range = 20.0
intensity = 30.0

[[lights]]
type = "point"
position = [-3.0, 1.2, 1.5]
range = 12.0
intensity = 20.0

[[objects]]
type = "plane"
size = [16.0, 16.0]

[[objects]]
type = "box"
size = [1.5, 1.5, 1.5]
translation = [0.0, 0.75, 0.0]
)toml";

constexpr const char* kSize = " --width 160 --height 90";

class ViewLocalLights : public penumbra::testing::CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        write_file("lights.toml", kLocalLightsScene);
    }

    // A private X server with a 24-bit screen (xvfb-run's default is 8-bit).
    RunResult run_in_window(const std::string& arguments) const {
        return run(arguments, "xvfb-run -a -s '-screen 0 1280x1024x24'");
    }

    // `render lights.toml --aov shadow:2 -o FILE` with `options`; the image read back.
    penumbra::PngImage render_point_light_visibility(const std::string& options, const std::string& file) const {
        const RunResult render = run("render lights.toml --aov shadow:2 -o " + file + kSize + options);
        EXPECT_EQ(render.exit_code, 0) << render.err;
        return penumbra::read_png(dir_ / file);
    }
};

// Pixels where the two 16-bit visibility images differ at all.
size_t pixels_differing(const penumbra::PngImage& a, const penumbra::PngImage& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.samples.size() != b.samples.size()) return a.samples.size() + b.samples.size();
    size_t differing = 0;
    for (size_t i = 0; i < a.samples.size(); ++i) differing += a.samples[i] != b.samples[i];
    return differing;
}

// Budget 1 and resolution 256 first (the point light, light 2, is beyond the budget: no
// shadow), then budget 2 and resolution 32 (a coarse shadow). Both states are compared with
// `render` given the same flags; the saved config must reproduce the final one.
TEST_F(ViewLocalLights, ScriptedBudgetAndResolutionMatchRenderAndSavedConfig) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    write_file("local.txt",
               "0 set shadow.local_shadow_budget = 1\n"
               "0 set shadow.local_shadow_resolution = 256\n"
               "2 screenshot budget1.png\n"
               "3 set shadow.local_shadow_budget = 2\n"
               "3 set shadow.local_shadow_resolution = 32\n");
    const RunResult view = run_in_window(
        std::string("view lights.toml --frames 5 --script local.txt --screenshot final.png --screenshot-aov shadow:2 "
                    "--save-settings saved.toml --validate") +
        kSize);
    ASSERT_EQ(view.exit_code, 0) << view.err;
    EXPECT_NE(view.out.find("presented 5 frames"), std::string::npos) << view.out;
    const std::string saved = read_text(dir_ / "saved.toml");
    EXPECT_NE(saved.find("local_shadow_budget = 2\n"), std::string::npos) << saved;
    EXPECT_NE(saved.find("local_shadow_resolution = 32\n"), std::string::npos) << saved;

    const penumbra::PngImage budget1 = penumbra::read_png(dir_ / "budget1.png");
    const penumbra::PngImage final_shot = penumbra::read_png(dir_ / "final.png");
    EXPECT_EQ(pixels_differing(budget1, render_point_light_visibility(
                                            " --local-shadow-budget 1 --local-shadow-resolution 256", "b1.png")),
              0u);
    EXPECT_EQ(pixels_differing(final_shot, render_point_light_visibility(
                                               " --local-shadow-budget 2 --local-shadow-resolution 32", "b2.png")),
              0u);
    EXPECT_EQ(pixels_differing(final_shot, render_point_light_visibility(" --config saved.toml", "saved.png")), 0u);

    // The changes took effect: the point light's shadow appears with budget 2, and its
    // 32-texel map draws another outline than the default 1024 texels.
    EXPECT_GT(pixels_differing(budget1, final_shot), 100u);
    EXPECT_GT(pixels_differing(final_shot, render_point_light_visibility(" --local-shadow-budget 2", "fine.png")), 0u);
}

TEST(ViewLocalLightsScript, SetsTheLocalShadowKeys) {
    const auto actions = penumbra::view::parse_script(
        "0 set shadow.local_shadow_budget = 3\n1 set shadow.local_shadow_resolution = 512\n", "s.txt");
    ASSERT_EQ(actions.size(), 2u);
    EXPECT_EQ(*std::get<penumbra::view::action::Set>(actions[0].action).overrides.settings.find("local_shadow_budget"),
              penumbra::SettingValue(int64_t{3}));
    EXPECT_EQ(
        *std::get<penumbra::view::action::Set>(actions[1].action).overrides.settings.find("local_shadow_resolution"),
        penumbra::SettingValue(int64_t{512}));
    const std::string too_many = std::to_string(penumbra::kMaxLocalShadowBudget + 1);
    try {
        penumbra::view::parse_script("0 set shadow.local_shadow_budget = " + too_many + "\n", "s.txt");
        ADD_FAILURE() << "budget " << too_many << " was accepted";
    } catch (const penumbra::InputError& error) {
        const std::string expected = "s.txt:1: shadow.local_shadow_budget: " + too_many +
                                     " is outside the allowed range [0, " +
                                     std::to_string(penumbra::kMaxLocalShadowBudget) + "]";
        EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
}

}  // namespace
