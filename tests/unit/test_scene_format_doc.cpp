// docs/scene-format.md stays true: its complete example parses.
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

TEST(SceneFormatDoc, CompleteExampleParses) {
    const std::filesystem::path doc = testing::test_data("../../docs/scene-format.md");
    std::ifstream stream(doc);
    ASSERT_TRUE(stream) << "cannot open " << doc;
    std::ostringstream markdown;
    markdown << stream.rdbuf();
    std::string example = first_toml_block(markdown.str());
    ASSERT_FALSE(example.empty());

    const std::filesystem::path tree = std::filesystem::path(PENUMBRA_SHARED_ASSETS_DIR) / "oaktree/oaktree.gltf";
    if (!std::filesystem::exists(tree)) GTEST_SKIP() << "shared asset " << tree << " not found";
    const std::string model_key = "\"models/oaktree.gltf\"";
    ASSERT_NE(example.find(model_key), std::string::npos);
    example.replace(example.find(model_key), model_key.size(), "\"" + tree.generic_string() + "\"");

    const Scene scene = parse_scene_toml(example, "scene-format.md", ".");
    EXPECT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.instances.size(), 5u + 2u * 2u) << "five primitives and two trees of two meshes";
}

}  // namespace
}  // namespace penumbra
