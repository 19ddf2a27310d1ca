// Scene files that parse: values, defaults, transforms, materials and glTF objects.
#include <gtest/gtest.h>

#include <algorithm>

#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using testing::parse_scene_text;
using testing::test_data;

glm::vec3 world_translation(const Instance& instance) { return glm::vec3{instance.world[3]}; }

TEST(SceneToml, EmptyFileGivesTheDefaults) {
    const Scene scene = parse_scene_text("");
    const Camera defaults;
    EXPECT_EQ(scene.camera.eye, defaults.eye);
    EXPECT_EQ(scene.camera.target, defaults.target);
    EXPECT_EQ(scene.camera.fov_y_degrees, defaults.fov_y_degrees);
    EXPECT_TRUE(scene.lights.empty());
    EXPECT_EQ(scene.sun(), nullptr);
    EXPECT_EQ(scene.ambient, Scene{}.ambient);
    EXPECT_TRUE(scene.instances.empty());
}

TEST(SceneToml, ReadsTheExampleFile) {
    const Scene scene = load_scene(test_data("scenes/example.toml").string());
    EXPECT_EQ(scene.camera.eye, glm::vec3(0.0f, 6.0f, 12.0f));
    EXPECT_EQ(scene.camera.up, glm::vec3(0.0f, 1.0f, 0.0f)) << "up is normalised";
    EXPECT_FLOAT_EQ(scene.camera.fov_y_degrees, 45.0f);
    EXPECT_FLOAT_EQ(scene.camera.near_plane, 0.5f);
    EXPECT_FLOAT_EQ(scene.camera.far_plane, 150.0f);

    ASSERT_EQ(scene.lights.size(), 1u);
    const Light& sun = scene.lights[0];
    EXPECT_EQ(sun.type, LightType::Directional);
    EXPECT_EQ(sun.direction, glm::vec3(0.0f, -1.0f, 0.0f)) << "direction is normalised";
    EXPECT_EQ(sun.color, glm::vec3(1.0f, 0.96f, 0.9f));
    EXPECT_FLOAT_EQ(sun.intensity, 3.0f);
    EXPECT_FLOAT_EQ(sun.angular_diameter_degrees, 0.53f);
    EXPECT_FALSE(sun.cast_shadows);
    EXPECT_EQ(scene.ambient, glm::vec3(0.1f, 0.2f, 0.3f));

    // Four primitives plus two instances of the one-mesh glTF quad.
    EXPECT_EQ(scene.meshes.size(), 5u);
    ASSERT_EQ(scene.instances.size(), 6u);
    EXPECT_EQ(scene.instances[4].mesh, scene.instances[5].mesh);
    EXPECT_EQ(world_translation(scene.instances[1]), glm::vec3(0.0f, 3.0f, 0.0f));
    EXPECT_EQ(world_translation(scene.instances[2]), glm::vec3(3.0f, 1.0f, 0.0f)) << "integers are numbers";
}

TEST(SceneToml, GltfInstancesApplyTheirTransformOverTheNodes) {
    const Scene scene = load_scene(test_data("scenes/example.toml").string());
    // The quad's node sits at (1, 2, 3); the second instance scales by 2 and moves to (-3, 0, 1).
    const glm::vec3 node_origin{scene.instances[5].world * glm::vec4{0.0f, 0.0f, 0.0f, 1.0f}};
    EXPECT_NEAR(node_origin.x, -3.0f + 2.0f, 1e-5f);
    EXPECT_NEAR(node_origin.y, 0.0f + 4.0f, 1e-5f);
    EXPECT_NEAR(node_origin.z, 1.0f + 6.0f, 1e-5f);
}

TEST(SceneToml, GltfWithoutInstancesUsesTheObjectTransform) {
    const Scene scene = parse_scene_text(R"(
        [[objects]]
        type = "gltf"
        file = "../gltf/quad.gltf"
        translation = [10.0, 0.0, 0.0]
    )");
    ASSERT_EQ(scene.instances.size(), 1u);
    EXPECT_EQ(world_translation(scene.instances[0]), glm::vec3(11.0f, 2.0f, 3.0f));
}

TEST(SceneToml, PrimitiveMaterialDefaultsAndOverrides) {
    const Scene scene = parse_scene_text(R"(
        [[objects]]
        type = "box"

        [[objects]]
        type = "sphere"
        color = [0.1, 0.2, 0.3, 0.5]
        roughness = 0.25
        metallic = 1
        emissive = [2.0, 0.5, 0.0]
        double_sided = true
        alpha_mode = "blend"
    )");
    ASSERT_EQ(scene.materials.size(), 2u);
    const Material& plain = scene.materials[scene.meshes[0].material];
    EXPECT_EQ(plain.base_color, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f));
    EXPECT_EQ(plain.alpha_mode, AlphaMode::Opaque);
    EXPECT_EQ(plain.base_color_texture, -1);
    EXPECT_FALSE(plain.double_sided);
    EXPECT_EQ(plain.emissive, glm::vec3(0.0f));
    const Material& custom = scene.materials[scene.meshes[1].material];
    EXPECT_EQ(custom.base_color, glm::vec4(0.1f, 0.2f, 0.3f, 0.5f));
    EXPECT_FLOAT_EQ(custom.roughness, 0.25f);
    EXPECT_FLOAT_EQ(custom.metallic, 1.0f);
    EXPECT_EQ(custom.emissive, glm::vec3(2.0f, 0.5f, 0.0f));
    EXPECT_TRUE(custom.double_sided);
    EXPECT_EQ(custom.alpha_mode, AlphaMode::Blend);
}

TEST(SceneToml, ThreeComponentColourGetsOpaqueAlpha) {
    const Scene scene = parse_scene_text("[[objects]]\ntype = \"box\"\ncolor = [0.1, 0.2, 0.3]\n");
    EXPECT_EQ(scene.materials[0].base_color, glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
}

TEST(SceneToml, TextureWithHolesImpliesAlphaMaskAndIsShared) {
    const Scene scene = parse_scene_text(R"(
        [[objects]]
        type = "plane"
        texture = "round_holes"

        [[objects]]
        type = "box"
        texture = "round_holes"
        alpha_cutoff = 0.25

        [[objects]]
        type = "box"
        texture = "checker"
    )");
    ASSERT_EQ(scene.textures.size(), 2u);
    const Material& holes = scene.materials[0];
    EXPECT_EQ(holes.alpha_mode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(holes.alpha_cutoff, 0.5f);
    EXPECT_EQ(scene.materials[1].base_color_texture, holes.base_color_texture);
    EXPECT_FLOAT_EQ(scene.materials[1].alpha_cutoff, 0.25f);
    EXPECT_EQ(scene.materials[2].alpha_mode, AlphaMode::Opaque);

    const Texture& texture = scene.textures[static_cast<size_t>(holes.base_color_texture)];
    ASSERT_EQ(texture.rgba8.size(), size_t{texture.width} * texture.height * 4);
    size_t transparent = 0;
    for (size_t i = 3; i < texture.rgba8.size(); i += 4) transparent += texture.rgba8[i] == 0 ? 1 : 0;
    const double hole_fraction = static_cast<double>(transparent) / (texture.width * texture.height);
    EXPECT_NEAR(hole_fraction, 3.14159 * 0.35 * 0.35, 0.02) << "round holes of radius 0.35 cell";
}

TEST(SceneToml, CutoffAloneImpliesMaskUnlessAlphaModeSaysOtherwise) {
    const Scene scene = parse_scene_text(R"(
        [[objects]]
        type = "box"
        alpha_cutoff = 0.3

        [[objects]]
        type = "box"
        alpha_cutoff = 0.3
        alpha_mode = "opaque"
    )");
    EXPECT_EQ(scene.materials[0].alpha_mode, AlphaMode::Mask);
    EXPECT_EQ(scene.materials[1].alpha_mode, AlphaMode::Opaque);
}

TEST(SceneToml, UvScaleMultipliesTheUvs) {
    const Scene scene = parse_scene_text("[[objects]]\ntype = \"plane\"\nuv_scale = [4.0, 2.0]\n");
    float max_u = 0.0f;
    float max_v = 0.0f;
    for (const Vertex& vertex : scene.meshes[0].vertices) {
        max_u = std::max(max_u, vertex.uv.x);
        max_v = std::max(max_v, vertex.uv.y);
    }
    EXPECT_FLOAT_EQ(max_u, 4.0f);
    EXPECT_FLOAT_EQ(max_v, 2.0f);
}

TEST(SceneToml, PrimitiveSizesAndScalarScale) {
    const Scene scene = parse_scene_text(R"(
        [[objects]]
        type = "box"
        size = [1.0, 2.0, 3.0]
        scale = 2
        translation = [0.0, 2.0, 0.0]

        [[objects]]
        type = "cylinder"
        radius = 0.25
        height = 4.0
    )");
    const Aabb box = transform_aabb(scene.meshes[0].bounds, scene.instances[0].world);
    EXPECT_EQ(box.min, glm::vec3(-1.0f, 0.0f, -3.0f));
    EXPECT_EQ(box.max, glm::vec3(1.0f, 4.0f, 3.0f));
    EXPECT_NEAR(scene.meshes[1].bounds.max.x, 0.25f, 1e-6f);
    EXPECT_NEAR(scene.meshes[1].bounds.max.y, 2.0f, 1e-6f);
}

TEST(SceneToml, LightDefaultsToDirectional) {
    const Scene scene = parse_scene_text("[[lights]]\ndirection = [0, 0, -3]\n");
    ASSERT_NE(scene.sun(), nullptr);
    EXPECT_EQ(scene.sun()->direction, glm::vec3(0.0f, 0.0f, -1.0f));
    EXPECT_TRUE(scene.sun()->cast_shadows);
}

TEST(SceneToml, UpParallelToTheViewDirectionIsAccepted) {
    const Scene scene = parse_scene_text("[camera]\neye = [0, 10, 0]\ntarget = [0, 0, 0]\n");
    EXPECT_EQ(scene.camera.up, glm::vec3(0.0f, 1.0f, 0.0f));
}

}  // namespace
}  // namespace penumbra
