// Built-in scenes: every one loads, and the default scene holds the casters it promises.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using ::testing::Contains;
using testing::input_error_message;

std::vector<Aabb> instance_bounds(const Scene& scene) {
    std::vector<Aabb> bounds;
    for (const Instance& instance : scene.instances) {
        bounds.push_back(transform_aabb(scene.meshes[instance.mesh].bounds, instance.world));
    }
    return bounds;
}

TEST(BuiltinScenes, NamesIncludeDefault) {
    EXPECT_THAT(builtin_scene_names(), Contains("default"));
    EXPECT_THAT(builtin_scene_names(), Contains("box-on-plane"));
    EXPECT_EQ(kDefaultSceneName, "builtin:default");
}

TEST(BuiltinScenes, EveryBuiltinLoadsThroughLoadScene) {
    for (const std::string& name : builtin_scene_names()) {
        SCOPED_TRACE(name);
        const Scene scene = load_scene(std::string(kBuiltinPrefix) + name);
        EXPECT_GT(scene.triangle_count(), 0u);
        ASSERT_NE(scene.sun(), nullptr);
        EXPECT_EQ(scene.instances.size(), builtin_scene(name).instances.size());
        for (const Mesh& mesh : scene.meshes) EXPECT_FALSE(mesh.bounds.empty());
    }
}

TEST(BuiltinScenes, UnknownNameListsTheValidOnes) {
    EXPECT_EQ(input_error_message([] { load_scene("builtin:cathedral"); }),
              "builtin:cathedral: unknown built-in scene \"cathedral\" (expected one of: default, box-on-plane, "
              "forest, terrain)");
}

TEST(BuiltinScenes, DefaultCameraAndLighting) {
    const Scene scene = builtin_scene("default");
    EXPECT_EQ(scene.camera.eye, glm::vec3(0.0f, 6.0f, 12.0f));
    EXPECT_EQ(scene.camera.target, glm::vec3(0.0f));
    EXPECT_FLOAT_EQ(scene.camera.fov_y_degrees, 60.0f);
    ASSERT_NE(scene.sun(), nullptr);
    EXPECT_NEAR(glm::length(scene.sun()->direction - glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f))), 0.0f, 1e-6f);
    EXPECT_EQ(scene.sun()->color, glm::vec3(1.0f, 0.96f, 0.9f));
    EXPECT_FLOAT_EQ(scene.sun()->intensity, 3.0f);
    EXPECT_FLOAT_EQ(scene.sun()->angular_diameter_degrees, 0.53f);
    EXPECT_EQ(scene.ambient, glm::vec3(0.25f, 0.3f, 0.35f));
}

TEST(BuiltinScenes, DefaultHasAWideGroundAndFarCasters) {
    const Scene scene = builtin_scene("default");
    const std::vector<Aabb> bounds = instance_bounds(scene);
    const bool has_ground = std::any_of(bounds.begin(), bounds.end(), [](const Aabb& box) {
        return box.extent().x >= 50.0f && box.extent().z >= 50.0f && box.max.y == 0.0f;
    });
    EXPECT_TRUE(has_ground);
    float farthest_caster = 0.0f;
    for (const Aabb& box : bounds) {
        if (box.max.y > 0.5f)
            farthest_caster = std::max(farthest_caster, glm::distance(box.center(), scene.camera.eye));
    }
    EXPECT_GT(farthest_caster, 40.0f) << "poles reach far enough for several cascades";
}

TEST(BuiltinScenes, DefaultHasAFloatingSlabAndThinCasters) {
    const std::vector<Aabb> bounds = instance_bounds(builtin_scene("default"));
    const bool floating_slab = std::any_of(bounds.begin(), bounds.end(), [](const Aabb& box) {
        return std::abs(box.min.y - 0.05f) < 1e-4f && box.extent().x >= 1.0f && box.extent().z >= 1.0f;
    });
    EXPECT_TRUE(floating_slab) << "a slab 5 cm above the ground (peter-panning check)";
    const bool thin_rail = std::any_of(bounds.begin(), bounds.end(), [](const Aabb& box) {
        return box.min.y > 0.1f && box.extent().y <= 0.031f && std::max(box.extent().x, box.extent().z) >= 2.0f;
    });
    EXPECT_TRUE(thin_rail) << "a rail of about 3 cm";
}

TEST(BuiltinScenes, DefaultHasAnAlphaMaskedCasterWithHoles) {
    const Scene scene = builtin_scene("default");
    const auto masked = std::find_if(scene.materials.begin(), scene.materials.end(), [](const Material& material) {
        return material.alpha_mode == AlphaMode::Mask && material.double_sided && material.base_color_texture >= 0;
    });
    ASSERT_NE(masked, scene.materials.end());
    EXPECT_FLOAT_EQ(masked->alpha_cutoff, 0.5f);
    const Texture& texture = scene.textures[static_cast<size_t>(masked->base_color_texture)];
    const bool has_holes =
        std::any_of(texture.rgba8.begin(), texture.rgba8.end(), [](uint8_t byte) { return byte == 0; });
    EXPECT_TRUE(has_holes);
}

TEST(BuiltinScenes, DefaultBoundsAreSensible) {
    const Aabb bounds = builtin_scene("default").world_bounds();
    EXPECT_FALSE(bounds.empty());
    EXPECT_GE(bounds.min.y, -1e-4f) << "nothing below the ground";
    EXPECT_LE(bounds.max.y, 10.0f);
}

}  // namespace
}  // namespace penumbra
