// `penumbra view` under Xvfb with lavapipe: the window opens and presents frames
// validation-clean; its screenshot matches `penumbra render` of the same scene, camera
// and settings; a scripted settings change (cascades 4 -> 2, resolution 2048 -> 1024,
// a window resize) takes effect and saves a config that `render` reproduces; and
// without a window system the viewer fails with one line and exit code 3.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "cli_runner.hpp"
#include "image/png_io.hpp"

namespace fs = std::filesystem;
using penumbra::testing::read_text;
using penumbra::testing::RunResult;

namespace {

bool have_xvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

class View : public penumbra::testing::CliTest {
protected:
    // A private X server with a 24-bit screen (xvfb-run's default is 8-bit).
    RunResult run_in_window(const std::string& arguments) const {
        return run(arguments, "xvfb-run -a -s '-screen 0 1280x1024x24'");
    }
};

// Fraction of pixels where any channel differs by more than `tolerance`.
double fraction_differing(const penumbra::PngImage& a, const penumbra::PngImage& b, int tolerance) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.channels, b.channels);
    if (a.samples.size() != b.samples.size() || a.channels == 0) return 1.0;
    size_t differing = 0;
    for (size_t pixel = 0; pixel < a.samples.size() / a.channels; ++pixel) {
        for (uint32_t c = 0; c < a.channels; ++c) {
            const size_t i = pixel * a.channels + c;
            if (std::abs(int(a.samples[i]) - int(b.samples[i])) > tolerance) {
                ++differing;
                break;
            }
        }
    }
    return static_cast<double>(differing) / static_cast<double>(a.samples.size() / a.channels);
}

constexpr const char* kSize = " --width 320 --height 240";

TEST_F(View, WithoutWindowSystemFailsWithOneLineAndExitCode3) {
    expect_failure(run("view --frames 1", "env -u DISPLAY -u WAYLAND_DISPLAY"), 3, "no window system");
}

TEST_F(View, ScreenshotColourMatchesRender) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    const RunResult view = run_in_window(std::string("view --frames 3 --screenshot view.png --validate") + kSize);
    ASSERT_EQ(view.exit_code, 0) << view.err;
    EXPECT_NE(view.out.find("presented 3 frames"), std::string::npos) << view.out;
    const RunResult render = run(std::string("render -o render.png") + kSize);
    ASSERT_EQ(render.exit_code, 0) << render.err;
    // The window image is the renderer's colour target blitted sRGB -> sRGB: at most one
    // level of rounding, and the panel is never in a screenshot.
    EXPECT_LE(fraction_differing(penumbra::read_png(dir_ / "view.png"), penumbra::read_png(dir_ / "render.png"), 1),
              0.001);
}

TEST_F(View, ShadowAovScreenshotMatchesRender) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    const std::string camera = " --eye 3,5,9 --target 0,0.5,0 --light-dir -0.5,-1,-0.2";
    const RunResult view = run_in_window(
        std::string("view --frames 4 --screenshot view.png --screenshot-aov shadow --validate") + kSize + camera);
    ASSERT_EQ(view.exit_code, 0) << view.err;
    const RunResult render = run(std::string("render --aov shadow -o render.png") + kSize + camera);
    ASSERT_EQ(render.exit_code, 0) << render.err;
    EXPECT_LE(fraction_differing(penumbra::read_png(dir_ / "view.png"), penumbra::read_png(dir_ / "render.png"), 0),
              0.001);
}

// Cascades 4 -> 2 and resolution 2048 -> 1024 by script, a move of the camera and the
// sun, a window resize: the run stays validation-clean, the cascade AOV holds only the
// two cascades, and the saved config makes `render` produce the same shadow image.
TEST_F(View, ScriptedSettingsChangeTakesEffectAndSavedSettingsReproduce) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    write_file("change.txt",
               "# frame action\n"
               "0 set shadow.cascades = 4\n"
               "0 set shadow.resolution = 2048\n"
               "2 set shadow.cascades = 2\n"
               "2 set shadow.resolution = 1024\n"
               "3 move 0.5 0 1\n"
               "3 turn 5 -3\n"
               "3 sun 60 40\n"
               "4 resize 300 200\n"
               "5 ui hide\n"
               "6 screenshot cascade_mid.png\n");
    const RunResult view =
        run_in_window(std::string("view --frames 9 --script change.txt --screenshot view.png --screenshot-aov shadow "
                                  "--save-settings saved.toml --validate") +
                      kSize);
    ASSERT_EQ(view.exit_code, 0) << view.err;
    const std::string saved = read_text(dir_ / "saved.toml");
    EXPECT_NE(saved.find("cascades = 2\n"), std::string::npos) << saved;
    EXPECT_NE(saved.find("resolution = 1024\n"), std::string::npos) << saved;
    EXPECT_NE(saved.find("width = 300\n"), std::string::npos) << saved;
    EXPECT_NE(saved.find("height = 200\n"), std::string::npos) << saved;

    const penumbra::PngImage shot = penumbra::read_png(dir_ / "view.png");
    EXPECT_EQ(shot.width, 300u);
    EXPECT_EQ(shot.height, 200u);
    const RunResult render = run("render --config saved.toml --aov shadow -o render.png");
    ASSERT_EQ(render.exit_code, 0) << render.err;
    EXPECT_LE(fraction_differing(shot, penumbra::read_png(dir_ / "render.png"), 0), 0.001);

    const RunResult cascades = run("render --config saved.toml --aov cascade -o cascade.png");
    ASSERT_EQ(cascades.exit_code, 0) << cascades.err;
    const penumbra::PngImage cascade = penumbra::read_png(dir_ / "cascade.png");
    for (uint16_t index : cascade.samples) ASSERT_TRUE(index <= 1 || index == 255) << index;
    EXPECT_TRUE(fs::exists(dir_ / "cascade_mid.png"));  // the script's own screenshot
}

// Resizes, a filter change, a debug view that reads the shadow map back each frame and
// the panel shown: every one recreates something while frames keep being presented.
TEST_F(View, RecreationsStayValidationClean) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    write_file("stress.txt",
               "1 resize 200 150\n"
               "2 set shadow.filter = \"pcf\"\n"
               "3 resize 360 200\n"
               "3 set shadow.resolution = 512\n"
               "4 mode orbit\n"
               "4 zoom 0.7\n"
               "5 animate-sun 90\n"
               "7 reset-camera\n"
               "8 quit\n");
    const RunResult view =
        run_in_window(std::string("view --frames 50 --debug shadowmap --script stress.txt --validate") + kSize);
    EXPECT_EQ(view.exit_code, 0) << view.err;
    EXPECT_NE(view.out.find("presented 8 frames"), std::string::npos) << view.out;
}

TEST_F(View, BadScriptIsAnInputErrorNamingTheLine) {
    write_file("bad.txt", "0 set shadow.cascades = 2\n1 fly-to-the-moon\n");
    expect_failure(run("view --frames 2 --script bad.txt"), 2, "bad.txt:2: unknown action \"fly-to-the-moon\"");
}

}  // namespace
