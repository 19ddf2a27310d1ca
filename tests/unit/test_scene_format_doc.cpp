// docs/scene-format.md stays true: its complete example is the shipped file and loads.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

std::string first_toml_block(const std::string& markdown) {
    const std::string fence = "```toml\n";
    const size_t begin = markdown.find(fence);
    if (begin == std::string::npos) return {};
    const size_t end = markdown.find("```", begin + fence.size());
    return markdown.substr(begin + fence.size(), end - begin - fence.size());
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream stream(path);
    EXPECT_TRUE(stream) << "cannot open " << path;
    std::ostringstream text;
    text << stream.rdbuf();
    return text.str();
}

// The complete example is printed in the doc and shipped as examples/scenes/complete.toml
// (which the docs' command test renders); the two must not drift apart.
TEST(SceneFormatDoc, CompleteExampleIsTheShippedFile) {
    const std::string example = first_toml_block(read_text(testing::test_data("../../docs/scene-format.md")));
    ASSERT_FALSE(example.empty());
    EXPECT_EQ(example, read_text(testing::test_data("../../examples/scenes/complete.toml")));
}

TEST(SceneFormatDoc, CompleteExampleLoads) {
    const Scene scene = load_scene(testing::test_data("../../examples/scenes/complete.toml").string());
    EXPECT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.instances.size(), 5u + 2u * 2u) << "five primitives and two trees of two meshes";
}

}  // namespace
}  // namespace penumbra
