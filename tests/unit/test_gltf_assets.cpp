// The real models in ../shared/assets: triangle counts and material properties.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "penumbra/scene/loader.hpp"

namespace penumbra {
namespace {

std::filesystem::path shared_asset(const std::string& relative) {
    return std::filesystem::path(PENUMBRA_SHARED_ASSETS_DIR) / relative;
}

// Loads a shared asset, or returns nullopt when the assets folder is not checked out.
std::optional<Scene> load_shared_asset(const std::string& relative) {
    const std::filesystem::path file = shared_asset(relative);
    if (!std::filesystem::exists(file)) return std::nullopt;
    Scene scene;
    append_gltf(scene, file, {glm::mat4{1.0f}});
    return scene;
}

#define LOAD_SHARED_ASSET_OR_SKIP(scene, relative)                  \
    const std::optional<Scene> scene = load_shared_asset(relative); \
    if (!scene)                                                     \
    GTEST_SKIP() << "shared asset " << shared_asset(relative)       \
                 << " not found (../shared/assets "                 \
                    "is not checked out next to the repository)"

bool has_transparent_texels(const Texture& texture) {
    for (size_t i = 3; i < texture.rgba8.size(); i += 4) {
        if (texture.rgba8[i] < 128) return true;
    }
    return false;
}

void expect_valid_meshes(const Scene& scene) {
    for (const Mesh& mesh : scene.meshes) {
        EXPECT_FALSE(mesh.bounds.empty());
        EXPECT_LT(mesh.material, scene.materials.size());
        for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.vertices.size());
    }
    for (const Material& material : scene.materials) {
        EXPECT_LT(material.base_color_texture, static_cast<int32_t>(scene.textures.size()));
    }
    for (const Texture& texture : scene.textures) {
        EXPECT_EQ(texture.rgba8.size(), size_t{texture.width} * texture.height * 4);
    }
}

TEST(GltfAssets, OakTree) {
    LOAD_SHARED_ASSET_OR_SKIP(scene, "oaktree/oaktree.gltf");
    EXPECT_EQ(scene->triangle_count(), 5302u);
    ASSERT_EQ(scene->materials.size(), 2u);
    expect_valid_meshes(*scene);
    const Material& bark = scene->materials[0];
    const Material& leaves = scene->materials[1];
    EXPECT_EQ(bark.alpha_mode, AlphaMode::Opaque);
    EXPECT_EQ(leaves.alpha_mode, AlphaMode::Blend);
    EXPECT_TRUE(bark.double_sided);
    EXPECT_TRUE(leaves.double_sided);
    EXPECT_FLOAT_EQ(leaves.roughness, 0.5f);
    ASSERT_GE(leaves.base_color_texture, 0);
    EXPECT_TRUE(has_transparent_texels(scene->textures[static_cast<size_t>(leaves.base_color_texture)]))
        << "the leaf texture's alpha cuts out the leaves";
    // The nodes rotate the Z-up meshes upright (+90 degrees about X) and scale them by 2:
    // the tree stands on y = 0 and is 1.93 m tall.
    const Aabb bounds = scene->world_bounds();
    EXPECT_NEAR(bounds.min.y, 0.0f, 1e-3f);
    EXPECT_NEAR(bounds.max.y, 1.926f, 1e-3f);
}

TEST(GltfAssets, TerrainGridlines) {
    LOAD_SHARED_ASSET_OR_SKIP(scene, "terrain_gridlines/terrain_gridlines.gltf");
    EXPECT_EQ(scene->triangle_count(), 1599u);
    expect_valid_meshes(*scene);
    ASSERT_EQ(scene->materials.size(), 1u);
    EXPECT_GE(scene->materials[0].base_color_texture, 0);
    // Node scale (20, 35, 20): a wide terrain.
    EXPECT_GT(scene->world_bounds().extent().x, 20.0f);
}

TEST(GltfAssets, AlphaBlendModeTest) {
    LOAD_SHARED_ASSET_OR_SKIP(scene, "AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf");
    EXPECT_EQ(scene->triangle_count(), 61u);
    expect_valid_meshes(*scene);
    std::vector<float> mask_cutoffs;
    int blend = 0;
    int opaque = 0;
    for (const Material& material : scene->materials) {
        if (material.alpha_mode == AlphaMode::Mask) mask_cutoffs.push_back(material.alpha_cutoff);
        blend += material.alpha_mode == AlphaMode::Blend ? 1 : 0;
        opaque += material.alpha_mode == AlphaMode::Opaque ? 1 : 0;
    }
    std::sort(mask_cutoffs.begin(), mask_cutoffs.end());
    EXPECT_EQ(mask_cutoffs, (std::vector<float>{0.25f, 0.5f, 0.75f}));
    EXPECT_EQ(blend, 1);
    EXPECT_EQ(opaque, 2);  // MatBed and MatOpaque
    // The bed's base colour and its packed occlusion-roughness-metallic image (read once for
    // both slots), and the labels; the normal map is not read.
    EXPECT_EQ(scene->textures.size(), 3u) << "base colour, metallic-roughness and occlusion images become textures";
}

}  // namespace
}  // namespace penumbra
