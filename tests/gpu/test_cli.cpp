// The `penumbra` command line: exit codes, one-line error messages naming the problem
// and its origin, and no output file left behind on failure.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>

#include "cli_runner.hpp"
#include "image/png_io.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/setting_presentation.hpp"
#include "penumbra/settings.hpp"

namespace fs = std::filesystem;
using penumbra::testing::RunResult;

namespace {

using Cli = penumbra::testing::CliTest;

constexpr const char* kValidScene = R"(
[camera]
eye = [0.0, 6.0, 12.0]
target = [0.0, 0.0, 0.0]
fov = 60.0
near = 0.1
far = 200.0

[[lights]]
type = "directional"
direction = [-0.4, -1.0, -0.3]

[[objects]]
type = "plane"
size = [40.0, 40.0]

[[objects]]
type = "box"
size = [2.0, 2.0, 2.0]
translation = [0.0, 3.0, 0.0]
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

TEST_F(Cli, RendersTheDefaultSceneValidationClean) {
    const RunResult result = run("render --validate --width 96 --height 54 -o out.png");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(result.err.empty()) << result.err;
    EXPECT_NE(result.out.find("out.png"), std::string::npos);
    const penumbra::PngImage image = penumbra::read_png(dir_ / "out.png");
    EXPECT_EQ(image.width, 96u);
    EXPECT_EQ(image.height, 54u);
    EXPECT_EQ(image.channels, 4u);
}

// Contact shadows darken the shadow AOV where they find an occluder and nowhere brighten
// it. Forward shading traces them over the depth pre-pass with the same function and the
// same depth as the compute resolve, so both paths darken the same pixels; the combined
// visibility is never brighter than the contact term alone (`--aov contact`).
TEST_F(Cli, ContactShadowsOnlyDarkenAndForwardTracesAsTheResolve) {
    // Close to the box's base on its shadow side, under one coarse cascade whose texels and
    // normal offset detach the box's shadow from its base: the gap is what the trace finds.
    const std::string base =
        "render builtin:box-on-plane --validate --width 160 --height 90 --eye -3,1.2,-3 --target -1,0,-1 "
        "--shadow-resolution 512 --cascades 1 ";
    const std::string contact = "--contact-shadows ";  // the default length and steps
    const auto render = [&](const std::string& options, const std::string& file) {
        const RunResult result = run(base + options + "-o " + file);
        EXPECT_EQ(result.exit_code, 0) << result.err;
        EXPECT_TRUE(result.err.empty()) << result.err;
        return penumbra::read_png(dir_ / file).samples;
    };
    const auto off = render("--aov shadow --resolve deferred ", "off.png");
    const auto on = render("--aov shadow --resolve deferred " + contact, "on.png");
    const auto forward_off = render("--aov shadow --resolve forward ", "forward_off.png");
    const auto forward_on = render("--aov shadow --resolve forward " + contact, "forward_on.png");
    const auto term = render("--aov contact " + contact, "contact.png");
    ASSERT_EQ(off.size(), size_t{160} * 90);
    ASSERT_EQ(on.size(), off.size());
    ASSERT_EQ(forward_on.size(), off.size());
    ASSERT_EQ(term.size(), off.size());
    // The term is traced in the lighting pass as forward shading traces it (bit for bit); the
    // resolve traces from positions and normals rebuilt from the depth instead.
    size_t darker = 0, brighter = 0, paths_disagree = 0, forward_above_term = 0, resolve_above_term = 0;
    for (size_t i = 0; i < off.size(); ++i) {
        darker += on[i] < off[i];
        brighter += on[i] > off[i] || forward_on[i] > forward_off[i];
        paths_disagree += (on[i] < off[i]) != (forward_on[i] < forward_off[i]);
        forward_above_term += forward_on[i] > term[i];
        resolve_above_term += on[i] > term[i];
    }
    EXPECT_GT(darker, 30u) << "the gap between the box's base and its detached shadow";
    EXPECT_EQ(brighter, 0u);
    EXPECT_LE(paths_disagree, darker / 20) << "forward and deferred find the same contact shadow";
    EXPECT_EQ(forward_above_term, 0u);
    EXPECT_LE(resolve_above_term, darker / 20);
    expect_failure(run(base + "--aov contact -o none.png"), 2,
                   "--aov contact: the sun's contact shadows are off (--contact-shadows turns them on)");
    EXPECT_FALSE(std::filesystem::exists(dir_ / "none.png"));
}

TEST_F(Cli, ShadowAovIsSixteenBitGray) {
    write_file("scene.toml", kValidScene);
    const RunResult result = run("render scene.toml --validate --aov shadow --width 64 --height 48 -o out.png");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const penumbra::PngImage image = penumbra::read_png(dir_ / "out.png");
    EXPECT_EQ(image.channels, 1u);
    EXPECT_EQ(image.bit_depth, 16u);
    EXPECT_EQ(image.samples.front(), 65535) << "sky pixels (no geometry) are fully lit";
}

TEST_F(Cli, CommandLineOverridesConfigFileWhichOverridesSceneFile) {
    write_file("scene.toml", std::string(kValidScene) + "\n[output]\nwidth = 40\nheight = 30\n");
    write_file("config.toml", "[output]\nwidth = 50\n");
    RunResult result = run("render scene.toml --config config.toml -o out.png");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    penumbra::PngImage image = penumbra::read_png(dir_ / "out.png");
    EXPECT_EQ(image.width, 50u);
    EXPECT_EQ(image.height, 30u);
    result = run("render scene.toml --config config.toml --width 20 -o out.png");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    image = penumbra::read_png(dir_ / "out.png");
    EXPECT_EQ(image.width, 20u);
}

TEST_F(Cli, DevicesListsAtLeastOneDevice) {
    const RunResult result = run("devices");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("index"), std::string::npos);
    EXPECT_NE(result.out.find("1.3"), std::string::npos);
}

// The help of each choice flag lists every name of its table (penumbra/settings.hpp).
TEST_F(Cli, HelpListsEveryNameOfTheChoiceTables) {
    const RunResult result = run("render --help");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto expect_listed = [&](const auto& choices) {
        for (const auto& choice : choices) {
            EXPECT_NE(result.out.find(choice.name), std::string::npos) << choice.name << " is not in render --help";
        }
    };
    expect_listed(penumbra::kSplitSchemeChoices);
    expect_listed(penumbra::kFitModeChoices);
    expect_listed(penumbra::kShadowStrategyChoices);
    expect_listed(penumbra::kShadowResolveChoices);
    expect_listed(penumbra::kShadowFilterChoices);
    expect_listed(penumbra::kPcssQualityChoices);
    expect_listed(penumbra::kCasterCullingChoices);
    expect_listed(penumbra::kLocalShadowSizingChoices);
}

TEST_F(Cli, MissingSceneFile) { expect_failure(run("render missing.toml -o out.png"), 2, "missing.toml"); }

TEST_F(Cli, MalformedToml) {
    write_file("scene.toml", "[camera\neye = [0, 1");
    expect_failure(run("render scene.toml -o out.png"), 2, "scene.toml");
}

TEST_F(Cli, UnknownObjectType) {
    write_file("scene.toml", replace(kValidScene, "\"box\"", "\"cone\""));
    expect_failure(run("render scene.toml -o out.png"), 2, "cone");
}

TEST_F(Cli, UnknownKey) {
    write_file("scene.toml", replace(kValidScene, "fov = 60.0", "fov = 60.0\nzoom = 2.0"));
    expect_failure(run("render scene.toml -o out.png"), 2, "zoom");
}

TEST_F(Cli, WrongValueType) {
    write_file("scene.toml", replace(kValidScene, "fov = 60.0", "fov = \"wide\""));
    expect_failure(run("render scene.toml -o out.png"), 2, "fov");
}

TEST_F(Cli, ZeroLengthLightDirection) {
    write_file("scene.toml", replace(kValidScene, "[-0.4, -1.0, -0.3]", "[0.0, 0.0, 0.0]"));
    expect_failure(run("render scene.toml -o out.png"), 2, "direction");
}

TEST_F(Cli, EyeEqualToTarget) { expect_failure(run("render --eye 1,2,3 --target 1,2,3 -o out.png"), 2, "eye"); }

TEST_F(Cli, FieldOfViewOutOfRange) {
    expect_failure(run("render --fov 0 -o out.png"), 2, "fov");
    expect_failure(run("render --fov 180 -o out.png"), 2, "fov");
}

TEST_F(Cli, NearAndFarPlanes) {
    expect_failure(run("render --near 0 -o out.png"), 2, "near");
    expect_failure(run("render --near 5 --far 5 -o out.png"), 2, "far");
}

TEST_F(Cli, ImageSizeOutOfRange) {
    expect_failure(run("render --width 0 -o out.png"), 2, "--width");
    expect_failure(run("render --height 16385 -o out.png"), 2, "--height");
}

TEST_F(Cli, ImageSizeOutOfRangeInSceneFile) {
    write_file("scene.toml", std::string(kValidScene) + "\n[output]\nwidth = 0\n");
    expect_failure(run("render scene.toml -o out.png"), 2, "output.width");
}

TEST_F(Cli, ShadowSettingsOutOfRange) {
    expect_failure(run("render --cascades 9 -o out.png"), 2, "--cascades");
    expect_failure(run("render --shadow-resolution 256 -o out.png"), 2, "--shadow-resolution");
    expect_failure(run("render --split-lambda 1.5 -o out.png"), 2, "--split-lambda");
    expect_failure(run("render --fit loose -o out.png"), 2, "--fit");
    expect_failure(run("render --cascades 3 --splits 10,5 -o out.png"), 2, "splits");
    expect_failure(run("render --blend-width 0.9 -o out.png"), 2, "--blend-width");
}

TEST_F(Cli, ShadowSettingsOutOfRangeInConfigFile) {
    write_file("config.toml", "[shadow]\ncascades = 0\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "shadow.cascades");
    write_file("config.toml", "[shadow]\nnormal_offset = -1.0\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "normal_offset");
    write_file("config.toml", "[shadows]\ncascades = 2\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "shadows");
}

// An integer a double cannot hold is refused at its key by the 1e9 rule (issue 32, item 2).
TEST_F(Cli, HugeIntegersInConfigFileNameTheKey) {
    write_file("config.toml", "[shadow]\nsplit_lambda = 9223372036854775807\n");
    expect_failure(run("render --config config.toml -o out.png"), 2,
                   "config.toml: shadow.split_lambda: 9223372036854775807 is beyond 1e9 in magnitude");
    write_file("config.toml", "[sun]\ndirection = [0, -9007199254740993, 0]\n");
    expect_failure(run("render --config config.toml -o out.png"), 2,
                   "config.toml: sun.direction: -9007199254740993 is beyond 1e9");
}

// --config naming something that is not a readable regular file says what it is, and a FIFO
// or /dev/zero is never read (the run would block or never end) (issue 32, item 10).
TEST_F(Cli, ConfigThatIsNotAReadableFile) {
    expect_failure(run("render --config missing.toml -o out.png"), 2, "missing.toml: config file not found");
    expect_failure(run("render --config /dev/zero -o out.png"), 2, "/dev/zero: not a regular file");
    fs::create_directory(dir_ / "folder.toml");
    expect_failure(run("render --config folder.toml -o out.png"), 2, "folder.toml: not a regular file");
    ASSERT_EQ(::mkfifo((dir_ / "fifo.toml").c_str(), 0600), 0);
    expect_failure(run("render --config fifo.toml -o out.png"), 2, "fifo.toml: not a regular file");
    fs::remove(dir_ / "fifo.toml");
    fs::remove(dir_ / "folder.toml");

    write_file("config.toml", "[output]\nwidth = 50\n");
    fs::permissions(dir_ / "config.toml", fs::perms::none);
    // Root reads any file: run as nobody then (the shell, still root, makes the redirections;
    // nobody may write the folder, so that the output check passes and the config is read).
    fs::permissions(dir_, fs::perms::all);
    const std::string as_user = ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups" : "";
    expect_failure(run("render --config config.toml -o out.png", as_user), 2,
                   "penumbra: config.toml: cannot be read: Permission denied");
}

TEST_F(Cli, HelpDocumentsTheOptions) {
    const RunResult result = run("render --help");
    EXPECT_EQ(result.exit_code, 0);
    for (const char* option : {"--output", "--config", "--aov", "--eye", "--light-dir", "--cascades", "--fit",
                               "--slope-bias", "--normal-offset", "--shadow-strategy", "--validate", "--device"}) {
        EXPECT_NE(result.out.find(option), std::string::npos) << option;
    }
}

// docs/cli.md (with the pages its tables link to for the filter, bench, compare and viewer
// flags) documents every flag of every command's --help, and names no flag that no command
// has: the documentation cannot drift from the declarations the help is built from.
TEST_F(Cli, EveryFlagIsDocumentedAndEveryDocumentedFlagExists) {
    const auto read = [](const char* name) {
        std::ifstream file(std::string(PENUMBRA_DOCS_DIR) + "/" + name);
        EXPECT_TRUE(file) << name;
        return std::string(std::istreambuf_iterator<char>(file), {});
    };
    const std::string cli = read("cli.md");
    std::string docs = cli;
    for (const char* page : {"filters.md", "bench.md", "viewer.md", "QUALITY.md", "local-lights.md"})
        docs += read(page);
    const std::regex flag(R"((^|[^\w-])(--[a-z][a-z0-9-]*))");
    const auto flags_in = [&](const std::string& text) {
        std::set<std::string> found;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), flag); it != std::sregex_iterator(); ++it) {
            found.insert((*it)[2].str());
        }
        return found;
    };
    const std::set<std::string> documented = flags_in(docs);
    std::set<std::string> every_flag;
    for (const char* command : {"render", "bench", "compare", "view"}) {
        const RunResult help = run(std::string(command) + " --help");
        ASSERT_EQ(help.exit_code, 0) << help.err;
        for (const std::string& name : flags_in(help.out)) {
            every_flag.insert(name);
            if (name == "--help") continue;
            EXPECT_TRUE(documented.contains(name)) << command << " " << name << " is not in docs/cli.md";
        }
    }
    for (const std::string& name : flags_in(cli)) {
        EXPECT_TRUE(every_flag.contains(name)) << "docs/cli.md names " << name << ", which no command has";
    }
}

// Every setting's row in docs/cli.md or docs/filters.md gives what its declaration says:
// the default, the range's bounds (or the allowed values, or every choice), and its config
// key appears in the config example or the filters' key column. The flag of each setting
// is read from --help, where its declaration's help line follows it.
TEST_F(Cli, EverySettingsDocRowAgreesWithItsDeclaration) {
    using namespace penumbra;
    const auto read = [](const char* name) {
        std::ifstream file(std::string(PENUMBRA_DOCS_DIR) + "/" + name);
        EXPECT_TRUE(file) << name;
        return std::string(std::istreambuf_iterator<char>(file), {});
    };
    const std::string docs = read("cli.md") + read("filters.md");
    const RunResult help = run("render --help");
    ASSERT_EQ(help.exit_code, 0) << help.err;
    // The table row whose first cell names the flag.
    const auto row_of = [&](const std::string& flag) {
        const std::regex row("\\n(\\| [^|\\n]*`" + flag + "[` \\\\][^\\n]*)");
        std::smatch match;
        return std::regex_search(docs, match, row) ? match[1].str() : std::string();
    };
    // Whether the row writes `value` ("0.005", "1e+05" as "100000", "3e-05" as "3e-5").
    const auto mentions = [](const std::string& row, double value) {
        const std::regex number(R"([0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?)");
        for (auto it = std::sregex_iterator(row.begin(), row.end(), number); it != std::sregex_iterator(); ++it) {
            const double found = std::stod(it->str());
            if (std::abs(found - value) <= 1e-6 * std::abs(value)) return true;
            // A negative bound ("-4..4"): the number after a minus sign.
            const bool negative = it->position() > 0 && row[static_cast<size_t>(it->position()) - 1] == '-';
            if (negative && std::abs(-found - value) <= 1e-6 * std::abs(value)) return true;
        }
        return false;
    };
    const auto number_of = [](const SettingValue& value) {
        return std::holds_alternative<int64_t>(value) ? static_cast<double>(std::get<int64_t>(value))
                                                      : std::get<double>(value);
    };
    std::vector<const SettingDeclaration*> settings;
    for (const SettingDeclaration& setting : kOutputSettingDeclarations) settings.push_back(&setting);
    for (const SettingDeclaration& setting : kSettingDeclarations) settings.push_back(&setting);
    for (const SettingDeclaration* declared : settings) {
        const SettingDeclaration& setting = *declared;
        const SettingPresentation& presentation = presentation_of(setting);
        const size_t help_at = help.out.find(presentation.help);
        ASSERT_NE(help_at, std::string::npos) << setting.name << "'s help line is not in --help";
        const size_t flag_at = help.out.rfind("  --", help_at);
        const std::string flag = help.out.substr(flag_at + 2, help.out.find_first_of(" \n", flag_at + 2) - flag_at - 2);
        const std::string row = row_of(flag);
        ASSERT_FALSE(row.empty()) << flag << " has no table row in docs/cli.md or docs/filters.md";
        const SettingValue default_value = setting.get(RenderSettings{});
        const std::string key = presentation.key_in_config();
        EXPECT_TRUE(docs.find("\n" + key + " = ") != std::string::npos ||
                    docs.find("`" + key + "`") != std::string::npos)
            << key << " (" << flag << ") is in neither the config example nor the filters' key column";
        switch (setting.type) {
            case SettingType::Integer:
            case SettingType::Number:
                EXPECT_TRUE(mentions(row, number_of(default_value))) << flag << ": default missing: " << row;
                for (const int64_t allowed : setting.allowed) {
                    EXPECT_TRUE(mentions(row, static_cast<double>(allowed)))
                        << flag << ": " << allowed << " missing: " << row;
                }
                if (setting.allowed.empty() && std::isfinite(setting.maximum)) {
                    EXPECT_TRUE(mentions(row, setting.minimum)) << flag << ": minimum: " << row;
                    EXPECT_TRUE(mentions(row, setting.maximum)) << flag << ": maximum: " << row;
                }
                break;
            case SettingType::Choice:
                for (const char* choice : setting.choices) {
                    EXPECT_NE(row.find(choice), std::string::npos) << flag << ": choice " << choice << ": " << row;
                }
                break;
            case SettingType::Boolean:
            case SettingType::NumberList:
                break;
        }
    }
}

TEST_F(Cli, UnknownFlag) { expect_failure(run("render --shadows-please -o out.png"), 2, "--shadows-please"); }

TEST_F(Cli, MalformedVectorFlag) { expect_failure(run("render --eye 1,2 -o out.png"), 2, "--eye"); }

TEST_F(Cli, UnknownAov) { expect_failure(run("render --aov depth -o out.png"), 2, "--aov"); }

TEST_F(Cli, MissingGltfFile) {
    write_file("scene.toml", std::string(kValidScene) + "\n[[objects]]\ntype = \"gltf\"\nfile = \"nope.gltf\"\n");
    expect_failure(run("render scene.toml -o out.png"), 2, "nope.gltf");
}

TEST_F(Cli, TruncatedGltf) {
    write_file("model.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [");
    write_file("scene.toml", std::string(kValidScene) + "\n[[objects]]\ntype = \"gltf\"\nfile = \"model.gltf\"\n");
    expect_failure(run("render scene.toml -o out.png"), 2, "model.gltf");
}

// The scene above with one glTF object reading model.gltf.
std::string scene_with_model() {
    return std::string(kValidScene) + "\n[[objects]]\ntype = \"gltf\"\nfile = \"model.gltf\"\n";
}

// The textured quad fixture reading its base colour image from `image_file` beside it.
std::string textured_quad_reading(const std::string& image_file) {
    std::string text = penumbra::testing::read_text(fs::path(PENUMBRA_TEST_DATA_DIR) / "gltf/textured.gltf");
    const size_t start = text.find("\"data:image/png;base64,");
    return text.replace(start, text.find('"', start + 1) - start + 1, "\"" + image_file + "\"");
}

// Issue 32, item 6: a PNG declaring 16384 x 32767 pixels (a few bytes here, 0.5 MB in the
// report) peaked at 6.4 GB; it is refused from its header, saying so.
TEST_F(Cli, DecompressionBombTextureIsRefused) {
    std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\x40\0\0\0\x7f\xff\x08\x06\0\0\0\0\0\0\0", 33);
    write_file("bomb.png", png + std::string(100, '\0'));
    write_file("model.gltf", textured_quad_reading("bomb.png"));
    write_file("scene.toml", scene_with_model());
    expect_failure(run("render scene.toml -o out.png"), 2,
                   "images[0]: 16384 x 32767 pixels (2147418112 bytes as RGBA8) would take the scene past the load "
                   "budget of 1073741824 bytes (--max-scene-bytes raises it); refused before decoding");
}

// A texture the budget allows but wider than the device's maxImageDimension2D (16384 at
// most on the devices tested) is refused before vkCreateImage: one line, no invalid usage.
TEST_F(Cli, TextureBeyondTheDeviceLimitIsRefused) {
    penumbra::write_png_gray8(dir_ / "wide.png", 65536, 1, std::vector<uint8_t>(65536, 200));
    write_file("model.gltf", textured_quad_reading("wide.png"));
    write_file("scene.toml", scene_with_model());
    expect_failure(run("render scene.toml --validate --width 32 --height 32 -o out.png"), 2,
                   "model.gltf: images[0]: 65536 x 1 texels exceed this device's maxImageDimension2D of ");
}

// Issue 32, item 7: 8 primitives of 2^24 - 1 zeros without a buffer view (a 400-byte file)
// made 9.8 GB and ran out of device memory after 40 s. Zeros alone are now skipped (no
// area); with three sparse points over them (a data uri of 48 bytes: indices 0, 1, 2 and
// three corners) they are refused at once from the counts.
// The limit is the user's to raise, and a lowered one refuses a small model too. The scene's
// plane and box (812 triangles) count against the budget with the model.
TEST_F(Cli, GeometryBombIsRefusedAndTheBudgetIsSettable) {
    std::string primitives;
    for (int p = 0; p < 8; ++p) primitives += std::string(p ? "," : "") + R"({"attributes":{"POSITION":0}})";
    write_file("model.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
                             R"("meshes":[{"primitives":[)" +
                                 primitives +
                                 R"(]}],"accessors":[{"componentType":5126,"count":16777215,"type":"VEC3",)"
                                 R"("sparse":{"count":3,"indices":{"bufferView":0,"componentType":5125},)"
                                 R"("values":{"bufferView":1}}}],"buffers":[{"byteLength":48,"uri":)"
                                 R"("data:application/octet-stream;base64,)"
                                 R"(AAAAAAEAAAACAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/"}],)"
                                 R"("bufferViews":[{"buffer":0,"byteLength":12},)"
                                 R"({"buffer":0,"byteOffset":12,"byteLength":36}]})");
    write_file("scene.toml", scene_with_model());
    const auto start = std::chrono::steady_clock::now();
    expect_failure(run("render scene.toml -o out.png"), 2,
                   "model.gltf: meshes: would make 44739240 triangles as placed (the scene held 812 before), over the "
                   "load budget of 33554432 "
                   "(--max-scene-triangles raises it)");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
    expect_failure(
        run("render scene.toml --max-scene-triangles 50000000 -o out.png"), 2,
        "images and meshes would take 5368708800 bytes (the scene held 68208 before), over the load budget of "
        "1073741824 bytes "
        "(--max-scene-bytes raises it)");

    write_file("model.gltf", penumbra::testing::read_text(fs::path(PENUMBRA_TEST_DATA_DIR) / "gltf/quad.gltf"));
    expect_failure(run("render scene.toml --max-scene-triangles 1 -o out.png"), 2,
                   "would make 2 triangles as placed (the scene held 812 before), over the load budget of 1 ");
    expect_failure(run("render scene.toml --max-scene-bytes 0 -o out.png"), 2, "--max-scene-bytes");
    const RunResult raised = run("render scene.toml --max-scene-triangles 814 --width 32 --height 32 -o out.png");
    EXPECT_EQ(raised.exit_code, 0) << raised.err;
}

TEST_F(Cli, OutputFolderMissing) {
    expect_failure(run("render --width 32 --height 32 -o nowhere/out.png"), 2, "nowhere");
}

TEST_F(Cli, NoVulkanDevice) {
    // Point the loader at a driver manifest that does not exist: no device can be found.
    expect_failure(run("render -o out.png", "VK_DRIVER_FILES=/nonexistent.json VK_ICD_FILENAMES=/nonexistent.json"), 3,
                   "Vulkan");
}

TEST_F(Cli, UnknownDeviceSelector) { expect_failure(run("render --device nosuchgpu -o out.png"), 3, "nosuchgpu"); }

}  // namespace

// Shadow filters (docs/filters.md): flags and [shadow] keys, and their range errors.
TEST_F(Cli, FilterFlagsRenderValidationClean) {
    for (const char* flags : {"--filter pcss --pcss-quality high --pcss-early-out --angular-diameter 2",
                              "--filter evsm --evsm-components 2 --blur-radius 0 --moments-poisson",
                              "--filter msm --msm-quantization --light-bleeding 0.1"}) {
        const RunResult result = run(std::string("render --validate --width 64 --height 48 --shadow-resolution 512 ") +
                                     flags + " -o out.png");
        EXPECT_EQ(result.exit_code, 0) << flags << ": " << result.err;
        EXPECT_TRUE(fs::exists(dir_ / "out.png")) << flags;
        fs::remove(dir_ / "out.png");
    }
}

TEST_F(Cli, FilterSettingsOutOfRange) {
    expect_failure(run("render --filter soft -o out.png"), 2, "--filter");
    expect_failure(run("render --pcf-radius 6 -o out.png"), 2, "--pcf-radius");
    expect_failure(run("render --poisson-taps 20 -o out.png"), 2, "--poisson-taps");
    expect_failure(run("render --poisson-radius 0.1 -o out.png"), 2, "--poisson-radius");
    expect_failure(run("render --pcss-quality ultra -o out.png"), 2, "--pcss-quality");
    expect_failure(run("render --pcss-blocker-taps 8 -o out.png"), 2, "--pcss-blocker-taps");
    expect_failure(run("render --pcss-max-penumbra 500 -o out.png"), 2, "--pcss-max-penumbra");
    expect_failure(run("render --light-bleeding 1 -o out.png"), 2, "--light-bleeding");
    expect_failure(run("render --blur-radius 9 -o out.png"), 2, "--blur-radius");
    expect_failure(run("render --evsm-positive-exponent 0 -o out.png"), 2, "--evsm-positive-exponent");
    expect_failure(run("render --evsm-components 3 -o out.png"), 2, "--evsm-components");
    expect_failure(run("render --msm-moment-bias 0.5 -o out.png"), 2, "--msm-moment-bias");
    expect_failure(run("render --angular-diameter 50 -o out.png"), 2, "--angular-diameter");
}

TEST_F(Cli, FilterSettingsOutOfRangeInConfigFile) {
    write_file("config.toml", "[shadow]\nfilter = \"soft\"\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "shadow.filter");
    write_file("config.toml", "[shadow]\npcf_radius = 7\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "pcf_radius");
    write_file("config.toml", "[shadow]\npoisson_taps = 24\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "poisson_taps");
    write_file("config.toml", "[shadow]\nevsm_negative_exponent = 1000.0\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "evsm_negative_exponent");
    write_file("config.toml", "[shadow]\npcss_early_out = 1\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "pcss_early_out");
    write_file("config.toml", "[sun]\nangular_diameter = -1.0\n");
    expect_failure(run("render --config config.toml -o out.png"), 2, "angular_diameter");
}

// Spot and point lights (docs/local-lights.md): `--aov shadow:N` and their scene-file errors.
constexpr const char* kLocalLights = R"(
[[lights]]
type = "spot"
position = [1.0, 6.0, 0.5]
direction = [0.0, -1.0, 0.0]
inner_angle = 20.0
outer_angle = 30.0
range = 25.0

[[lights]]
type = "point"
position = [-2.0, 3.0, 0.0]
range = 15.0
)";

TEST_F(Cli, LocalLightVisibilityAov) {
    write_file("scene.toml", std::string(kValidScene) + kLocalLights);
    for (const char* light : {"0", "1", "2"}) {
        const RunResult result = run(std::string("render scene.toml --validate --aov shadow:") + light +
                                     " --local-shadow-resolution 256 --width 64 --height 48 -o out.png");
        ASSERT_EQ(result.exit_code, 0) << result.err;
        const penumbra::PngImage image = penumbra::read_png(dir_ / "out.png");
        EXPECT_EQ(image.bit_depth, 16u);
        fs::remove(dir_ / "out.png");
    }
    expect_failure(run("render scene.toml --aov shadow:3 -o out.png"), 2, "--aov shadow:3");
    expect_failure(run("render scene.toml --aov shadow:x -o out.png"), 2, "--aov");
    expect_failure(run("render scene.toml --local-shadow-budget 33 -o out.png"), 2, "--local-shadow-budget");
    expect_failure(run("render scene.toml --local-shadow-sizing screen -o out.png"), 2, "--local-shadow-sizing");
    expect_failure(run("render scene.toml --caster-culling sideways -o out.png"), 2, "--caster-culling");
}

TEST_F(Cli, LocalLightsBeyondTheBudgetWarnOnce) {
    write_file("scene.toml", std::string(kValidScene) + kLocalLights);
    const RunResult result =
        run("render scene.toml --local-shadow-budget 1 --local-shadow-resolution 64 --width 32 --height 24 -o out.png");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find("beyond the local shadow budget of 1"), std::string::npos) << result.err;
}

TEST_F(Cli, BadLocalLightValues) {
    const std::string scene = std::string(kValidScene) + kLocalLights;
    const std::pair<const char*, const char*> cases[] = {{"outer_angle = 30.0", "outer_angle = 10.0"},
                                                         {"outer_angle = 30.0", "outer_angle = 180.0"},
                                                         {"range = 15.0", "range = 0.0"},
                                                         {"range = 15.0", "range = 15.0\nradius = -1.0"}};
    const char* keys[] = {"lights[1].inner_angle", "lights[1].outer_angle", "lights[2].range", "lights[2].radius"};
    for (size_t i = 0; i < 4; ++i) {
        write_file("scene.toml", replace(scene, cases[i].first, cases[i].second));
        expect_failure(run("render scene.toml -o out.png"), 2, std::string("scene.toml: ") + keys[i]);
    }
}

// Control characters in what the user typed or wrote (a scene's strings, a flag's value, a
// path, a builtin name or query) are escaped in the message: it stays one line (issue 17).
TEST_F(Cli, ControlCharactersInUserTextStayOnOneLine) {
    write_file("type.toml", replace(kValidScene, "type = \"box\"", "type = \"bo\\nx\""));
    expect_failure(run("render type.toml -o out.png"), 2, "bo\\nx");
    write_file("light.toml", replace(kValidScene, "type = \"directional\"", "type = \"sun\\u0000\\r\""));
    expect_failure(run("render light.toml -o out.png"), 2, "sun\\x00\\r");
    write_file("scene.toml", kValidScene);
    expect_failure(run("render scene.toml --filter \"$(printf 'pc\\nf')\" -o out.png"), 2, "pc\\nf");
    expect_failure(run("render \"$(printf 'sce\\nne.toml')\" -o out.png"), 2, "sce\\nne.toml");
    expect_failure(run("render \"$(printf 'builtin:de\\tfault')\" -o out.png"), 2, "builtin:de\\tfault");
    expect_failure(run("render \"$(printf 'builtin:forest?count=1\\n0')\" -o out.png"), 2, "1\\n0");
}

// Numbers that fit a double but not the renderer's float math (infinite after conversion,
// or overflowing when squared) are refused where they were written, naming the flag or
// the file and key, instead of rendering a wrong image with exit 0 (issue 17).
TEST_F(Cli, NumbersBeyondTheFloatMathAreRefusedWhereTheyWereWritten) {
    write_file("scene.toml", kValidScene);
    expect_failure(run("render scene.toml --far 1e39 -o out.png"), 2, "--far: expected a finite number");
    expect_failure(run("render scene.toml --far inf -o out.png"), 2, "--far");
    expect_failure(run("render scene.toml --fov nan -o out.png"), 2, "--fov");
    expect_failure(run("render scene.toml --up 0,1e20,0 -o out.png"), 2, "--up: expected finite numbers");
    expect_failure(run("render scene.toml --light-dir 1e30,-1e30,1e30 -o out.png"), 2, "--light-dir");
    write_file("far.toml", replace(kValidScene, "far = 200.0", "far = 1e308"));
    expect_failure(run("render far.toml -o out.png"), 2, "far.toml: camera.far: 1e+308 is beyond 1e9");
    write_file("big.toml", replace(kValidScene, "translation = [0.0, 3.0, 0.0]", "translation = [1e308, 3.0, 0.0]"));
    expect_failure(run("render big.toml -o out.png"), 2, "big.toml: objects[1].translation");
    write_file("sun.toml", "[sun]\ndirection = [1e30, -1e30, 1e30]\n");
    expect_failure(run("render scene.toml --config sun.toml -o out.png"), 2, "sun.toml: sun.direction");
}

// Flags that contradict each other, and an empty scene path, are errors rather than one of
// them silently winning (issue 17).
TEST_F(Cli, ContradictionsAreErrorsNotSilentChoices) {
    write_file("scene.toml", kValidScene);
    expect_failure(run("render scene.toml --aov shadow --debug cascades -o out.png"), 2, "--aov and --debug");
    expect_failure(run("render scene.toml --split-scheme uniform --splits 10,20,40 -o out.png"), 2,
                   "--splits: manual split distances need --split-scheme manual");
    expect_failure(run("render \"\" -o out.png"), 2, "the scene path is empty");
}

// Debian's toml++ 3.3.0 reaches an assertion on `a¡= 1` (marzer/tomlplusplus#190), which
// only a debug build of toml++ stops at: the release penumbra answers with exit 2 and one
// line, in a scene file and in a config file (issue 17; the fuzz corpus keeps the input).
TEST_F(Cli, TomlParserAssertionInputIsAnError) {
    write_file("bad.toml", "a\xC2\xA1= 1\n");
    expect_failure(run("render bad.toml -o out.png"), 2, "bad.toml");
    write_file("scene.toml", kValidScene);
    expect_failure(run("render scene.toml --config bad.toml -o out.png"), 2, "bad.toml");
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

// Shadow-casting control (issue 16): a closed 200 m box around the camera and the scene
// shadows every pixel and is named in a warning; with cast_shadows = false it casts nothing
// and the floating box's shadow is back; receive_shadows = false on the ground removes it.
double shadowed_fraction(const std::filesystem::path& aov) {
    const penumbra::PngImage image = penumbra::read_png(aov);
    size_t shadowed = 0;
    for (const uint16_t value : image.samples) shadowed += value < 32768;
    return static_cast<double>(shadowed) / static_cast<double>(image.samples.size());
}

TEST_F(Cli, SkyBoxIsNamedInAWarningAndCastShadowsTurnsItOff) {
    const std::string sky = "\n[[objects]]\ntype = \"box\"\nsize = [200.0, 200.0, 200.0]\n";
    write_file("sky.toml", std::string(kValidScene) + sky);
    const RunResult boxed = run("render sky.toml --validate --aov shadow --width 64 --height 48 -o boxed.png");
    ASSERT_EQ(boxed.exit_code, 0) << boxed.err;
    EXPECT_NE(boxed.err.find("warning: \"objects[2] (box)\" encloses the camera and the scene and shadows 100%"),
              std::string::npos)
        << boxed.err;
    // Every pixel showing geometry is shadowed; the rest show the sky through the culled
    // inside of the box (no geometry: visibility 1).
    EXPECT_GT(shadowed_fraction(dir_ / "boxed.png"), 0.7);

    write_file("open.toml", std::string(kValidScene) + sky + "cast_shadows = false\n");
    const RunResult open = run("render open.toml --validate --aov shadow --width 64 --height 48 -o open.png");
    ASSERT_EQ(open.exit_code, 0) << open.err;
    EXPECT_TRUE(open.err.empty()) << open.err;
    const double box_shadow = shadowed_fraction(dir_ / "open.png");
    EXPECT_GT(box_shadow, 0.005);
    EXPECT_LT(box_shadow, 0.2);

    write_file("unreceiving.toml", replace(std::string(kValidScene) + sky + "cast_shadows = false\n",
                                           "size = [40.0, 40.0]", "size = [40.0, 40.0]\nreceive_shadows = false"));
    const RunResult bare = run("render unreceiving.toml --validate --aov shadow --width 64 --height 48 -o bare.png");
    ASSERT_EQ(bare.exit_code, 0) << bare.err;
    EXPECT_LT(shadowed_fraction(dir_ / "bare.png"), box_shadow / 4.0) << "the ground still receives the shadow";
}

// The sky-box warning's advice is accepted as printed: a glTF sky whose node and mesh have
// no names is called "nodes[0]", and exclude_casters = ["nodes[0]"] turns it off.
TEST_F(Cli, UnnamedSkyNodeIsExcludedAsTheWarningSays) {
    // A cube of 2 m (8 corners, 36 16-bit indices), its node and mesh unnamed.
    write_file("sky.gltf",
               R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
               R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
               R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3",)"
               R"("min":[-1,-1,-1],"max":[1,1,1]},{"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}],)"
               R"("bufferViews":[{"buffer":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":72}],)"
               R"("buffers":[{"byteLength":168,"uri":"data:application/octet-stream;base64,)"
               R"(AACAvwAAgL8AAIC/AACAvwAAgL8AAIA/AACAvwAAgD8AAIC/AACAvwAAgD8AAIA/AACAPwAAgL8AAIC/AACAPwAAgL8AAIA/)"
               R"(AACAPwAAgD8AAIC/AACAPwAAgD8AAIA/AAABAAMAAAADAAIABAAGAAcABAAHAAUAAAAEAAUAAAAFAAEAAgADAAcAAgAHAAYA)"
               R"(AAACAAYAAAAGAAQAAQAFAAcAAQAHAAMA"}]})");
    const std::string sky = "\n[[objects]]\ntype = \"gltf\"\nfile = \"sky.gltf\"\ninstances = [{ scale = 100.0 }]\n";
    write_file("sky.toml", std::string(kValidScene) + sky);
    const RunResult warned = run("render sky.toml --validate --width 32 --height 24 -o warned.png");
    ASSERT_EQ(warned.exit_code, 0) << warned.err;
    EXPECT_NE(warned.err.find("warning: \"nodes[0]\" encloses the camera"), std::string::npos) << warned.err;
    EXPECT_NE(warned.err.find("exclude_casters = [\"nodes[0]\"]"), std::string::npos) << warned.err;
    write_file("excluded.toml", std::string(kValidScene) + sky + "exclude_casters = [\"nodes[0]\"]\n");
    const RunResult excluded = run("render excluded.toml --validate --width 32 --height 24 -o excluded.png");
    ASSERT_EQ(excluded.exit_code, 0) << excluded.err;
    EXPECT_TRUE(excluded.err.empty()) << excluded.err;
}

// compare reports the share of evaluated pixels in shadow and warns above 95 %.
TEST_F(Cli, CompareWarnsWhenAlmostEverythingIsShadowed) {
    write_file("sky.toml", std::string(kValidScene) + "\n[[objects]]\ntype = \"box\"\nsize = [200.0, 200.0, 200.0]\n");
    const RunResult boxed = run("compare sky.toml --width 48 --height 32 --rays 1 --stability-frames 1 --out-dir cmp");
    ASSERT_EQ(boxed.exit_code, 0) << boxed.err;
    EXPECT_NE(boxed.out.find("warning: more than 95% of the evaluated pixels are in shadow"), std::string::npos)
        << boxed.out;
    write_file("scene.toml", kValidScene);
    const RunResult normal =
        run("compare scene.toml --width 48 --height 32 --rays 1 --stability-frames 1 --out-dir cmp2");
    ASSERT_EQ(normal.exit_code, 0) << normal.err;
    EXPECT_NE(normal.out.find("shadowed: "), std::string::npos) << normal.out;
    EXPECT_EQ(normal.out.find("warning: more than 95%"), std::string::npos) << normal.out;
}

// The line a render prints names the size of the file it wrote: for --debug shadowmap the
// strip of shadow-map layers, not the colour image (issue 16).
TEST_F(Cli, DebugShadowMapReportsTheSizeOfTheFileItWrote) {
    write_file("scene.toml", kValidScene);
    const RunResult result = run(
        "render scene.toml --debug shadowmap --shadow-resolution 512 --cascades 2 --width 64 --height 48 -o sm.png");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const penumbra::PngImage image = penumbra::read_png(dir_ / "sm.png");
    const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height);
    EXPECT_NE(result.out.find("(" + size + ","), std::string::npos) << result.out << " vs " << size;
    EXPECT_NE(size, "64x48");
}
