// `render --debug virtual-pages`: the virtual shadow map's levels, page borders and
// unserved pages drawn over the colour image. Checked against the same frame without the
// debug view: tints and dark border lines where pixels sample a level, magenta only where
// the pool cannot hold what the frame asks for.
#include <gtest/gtest.h>

#include <string>

#include "cli_runner.hpp"
#include "image/png_io.hpp"

namespace {

struct DebugCounts {
    size_t pixels = 0;
    size_t tinted = 0;   // differ from the plain frame by more than 8 levels in a channel
    size_t borders = 0;  // at most 0.4 of a bright plain pixel in every channel
    size_t magenta = 0;  // exactly (255, 0, 255)
};

class VirtualPagesDebug : public penumbra::testing::CliTest {
protected:
    penumbra::PngImage render(const std::string& flags, const std::string& name) const {
        const auto result = run("render builtin:default --validate --shadow-technique virtual --resolve deferred " +
                                flags + " -o " + name + ".png");
        EXPECT_EQ(result.exit_code, 0) << name << ": " << result.err;
        return penumbra::read_png(dir_ / (name + ".png"));
    }

    DebugCounts compare(const std::string& flags) const {
        const penumbra::PngImage plain = render(flags, "plain");
        const penumbra::PngImage debug = render(flags + " --debug virtual-pages", "debug");
        DebugCounts counts;
        EXPECT_EQ(plain.samples.size(), debug.samples.size());
        if (plain.samples.size() != debug.samples.size() || plain.channels != 4) return counts;
        for (size_t i = 0; i + 3 < plain.samples.size(); i += 4) {
            ++counts.pixels;
            bool differs = false, dark = true;
            for (size_t c = 0; c < 3; ++c) {
                const int a = plain.samples[i + c], b = debug.samples[i + c];
                differs = differs || std::abs(a - b) > 8;
                dark = dark && a > 40 && b <= 0.4 * a + 2;
            }
            counts.tinted += differs;
            counts.borders += dark;
            counts.magenta += debug.samples[i] == 255 && debug.samples[i + 1] == 0 && debug.samples[i + 2] == 255;
        }
        return counts;
    }
};

TEST_F(VirtualPagesDebug, LevelsAreTintedAndPageBordersDrawnWhereEveryPageIsResident) {
    const DebugCounts counts = compare("--width 96 --height 64");
    EXPECT_GT(counts.tinted, counts.pixels / 2) << "the ground and the boxes sample a level";
    EXPECT_GT(counts.borders, 0u) << "page borders";
    EXPECT_LT(counts.borders, counts.pixels / 4) << "borders are lines";
    EXPECT_EQ(counts.magenta, 0u) << "the default pool holds every page of this frame";
}

// A pool of 256 pages for a frame that asks for far more (texels 16 times finer than the
// pixels): the pixels whose pages are not resident are marked.
TEST_F(VirtualPagesDebug, UnservedPagesAreMarkedInMagenta) {
    const DebugCounts counts = compare("--width 192 --height 128 --virtual-pool-mib 16 --virtual-lod-bias -4");
    EXPECT_GT(counts.magenta, 0u);
    EXPECT_LT(counts.magenta, counts.pixels / 2) << "stripes: every other diagonal band at most";
}

TEST_F(VirtualPagesDebug, CascadesHaveNoPagesToShow) {
    const auto result = run("render builtin:default --validate --debug virtual-pages -o out.png");
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(
        result.err.find("--debug virtual-pages: the sun has cascades (--shadow-technique virtual gives it pages)"),
        std::string::npos)
        << result.err;
}

}  // namespace
