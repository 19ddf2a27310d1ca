// `penumbra render` of compressed glTF: the Draco-compressed Khronos 2CylinderEngine renders
// as the uncompressed one does, and damaged compressed data is exit 2 with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "cli_runner.hpp"
#include "image/png_io.hpp"

namespace fs = std::filesystem;

namespace penumbra::testing {
namespace {

// Debian's assimp-testmodels (scripts/setup.sh).
const fs::path kDracoEngine = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";
const fs::path kPlainEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

class CompressedGltfCli : public CliTest {
protected:
    // Renders `model` alone at the origin under the default camera and sun.
    PngImage render_model(const fs::path& model, const std::string& output) const {
        const fs::path scene =
            write_file(output + ".toml", "[[objects]]\ntype = \"gltf\"\nfile = \"" + model.string() + "\"\n");
        const RunResult result = run("render --validate " + scene.string() + " --width 96 --height 54 -o " + output);
        EXPECT_EQ(result.exit_code, 0) << result.err;
        return read_png(dir_ / output);
    }
};

// The Draco file's positions are quantized to 14 bits over each mesh (a step of about 0.03
// units on a 400-unit engine): at 96 x 54 nearly every pixel comes out the same.
TEST_F(CompressedGltfCli, DracoEngineRendersAsTheUncompressedOne) {
    if (!fs::exists(kDracoEngine) || !fs::exists(kPlainEngine)) {
        GTEST_SKIP() << kDracoEngine << " or " << kPlainEngine
                     << " is absent: Debian's assimp-testmodels package is not installed (scripts/setup.sh)";
    }
    const PngImage draco = render_model(kDracoEngine, "draco.png");
    const PngImage plain = render_model(kPlainEngine, "plain.png");
    ASSERT_EQ(draco.channels, 4u);
    ASSERT_EQ(draco.samples.size(), plain.samples.size());
    size_t differing = 0;
    for (size_t pixel = 0; pixel + 3 < draco.samples.size(); pixel += 4) {
        int largest = 0;
        for (size_t c = 0; c < 3; ++c) {
            largest = std::max(largest, std::abs(int{draco.samples[pixel + c]} - int{plain.samples[pixel + c]}));
        }
        if (largest > 8) ++differing;
    }
    const size_t pixels = draco.samples.size() / 4;
    EXPECT_LT(differing, pixels / 100) << differing << " of " << pixels << " pixels differ by more than 8 levels";
}

TEST_F(CompressedGltfCli, DamagedCompressedDataIsExitTwoWithOneLine) {
    const fs::path corpus = PENUMBRA_FUZZ_CORPUS_DIR "/glb";
    const auto render = [&](const char* model) {
        const fs::path scene =
            write_file("scene.toml", "[[objects]]\ntype = \"gltf\"\nfile = \"" + (corpus / model).string() + "\"\n");
        return run("render " + scene.string() + " --width 32 --height 18 -o out.png");
    };
    expect_failure(render("repro_draco_corrupt.glb"), 2,
                   "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: cannot decode the Draco mesh");
    expect_failure(render("repro_meshopt_truncated.glb"), 2,
                   "bufferViews[0].extensions.EXT_meshopt_compression: the compressed data is corrupt or cut short");
}

}  // namespace
}  // namespace penumbra::testing
