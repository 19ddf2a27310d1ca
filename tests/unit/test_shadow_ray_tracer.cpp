// The Embree shadow-ray reference (src/quality) against shadows known in closed form:
// a box and a sphere above the ground, alpha-masked casters, instancing.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene/primitives.hpp"
#include "quality/alpha_mask.hpp"
#include "quality/reference_visibility.hpp"
#include "quality/shadow_ray_tracer.hpp"

namespace penumbra::quality {
namespace {

Scene scene_with(std::vector<std::pair<Mesh, glm::mat4>> objects) {
    Scene scene;
    scene.materials.emplace_back();
    for (auto& [mesh, world] : objects) {
        scene.instances.push_back({static_cast<uint32_t>(scene.meshes.size()), world});
        scene.meshes.push_back(std::move(mesh));
    }
    return scene;
}

glm::mat4 translation(const glm::vec3& offset) { return glm::translate(glm::mat4(1.0f), offset); }

// Is the ground point (x, 0, z) lit by the sun along `to_sun` according to the tracer?
bool ground_lit(const ShadowRayTracer& tracer, float x, float z, const glm::vec3& to_sun) {
    return !tracer.occluded(shadow_ray_origin({x, 0.0f, z}, {0.0f, 1.0f, 0.0f}), to_sun);
}

TEST(ShadowRayTracer, BoxShadowIsTheBoxProjectedAlongTheLight) {
    // Box [-1, 1] x [2, 3] x [-1, 1]; the light travels along -to_sun.
    const Scene scene =
        scene_with({{make_plane(40, 40), glm::mat4(1.0f)}, {make_box({2, 1, 2}), translation({0, 2.5f, 0})}});
    const ShadowRayTracer tracer(scene);
    EXPECT_EQ(tracer.triangle_count(), scene.triangle_count());
    const glm::vec3 to_sun = glm::normalize(glm::vec3(1.0f, 2.0f, 0.0f));
    // The ray from (x, 0, 0) is at x + y / 2 at height y: it meets the box (|x| <= 1 for
    // y in [2, 3]) exactly when x lies in [-1 - 1.5, 1 - 1] = [-2.5, 0].
    for (float x = -4.0f; x <= 3.0f; x += 0.05f) {
        const bool inside = x > -2.5f + 1e-3f && x < 0.0f - 1e-3f;
        const bool outside = x < -2.5f - 1e-3f || x > 0.0f + 1e-3f;
        if (inside) {
            EXPECT_FALSE(ground_lit(tracer, x, 0.0f, to_sun)) << x;
        } else if (outside) {
            EXPECT_TRUE(ground_lit(tracer, x, 0.0f, to_sun)) << x;
        }
    }
}

TEST(ShadowRayTracer, SphereShadowIsAnEllipse) {
    const glm::vec3 center(0.0f, 3.0f, 0.0f);
    const float radius = 1.0f;
    const Scene scene =
        scene_with({{make_plane(40, 40), glm::mat4(1.0f)}, {make_sphere(radius, 64, 32), translation(center)}});
    const ShadowRayTracer tracer(scene);
    const glm::vec3 to_sun = glm::normalize(glm::vec3(-0.8f, 1.0f, 0.3f));
    int checked = 0;
    for (float x = -8.0f; x <= 4.0f; x += 0.1f) {
        for (float z = -4.0f; z <= 4.0f; z += 0.1f) {
            // Shadowed exactly when the line toward the sun passes within `radius` of the centre.
            const glm::vec3 point(x, 0.0f, z);
            const glm::vec3 to_center = center - point;
            const float axis_distance = glm::length(to_center - to_sun * glm::dot(to_center, to_sun));
            if (std::abs(axis_distance - radius) < 0.02f * radius) continue;  // tessellation
            EXPECT_EQ(ground_lit(tracer, x, z, to_sun), axis_distance > radius) << x << ", " << z;
            ++checked;
        }
    }
    EXPECT_GT(checked, 9000);
}

TEST(ShadowRayTracer, AlphaMaskLetsLightThroughTheHoles) {
    Scene scene = scene_with({{make_plane(40, 40), glm::mat4(1.0f)}, {make_plane(4, 4), translation({0, 2, 0})}});
    // A 2x1 texture: left half opaque, right half transparent, nearest-looking at the centres.
    scene.textures.push_back({2, 1, {255, 255, 255, 255, 255, 255, 255, 0}});
    Material masked;
    masked.base_color_texture = 0;
    masked.alpha_mode = AlphaMode::Mask;
    masked.alpha_cutoff = 0.5f;
    scene.materials.push_back(masked);
    scene.meshes[1].material = 1;
    const ShadowRayTracer tracer(scene);
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    // The caster's u runs along x over [-2, 2]: texel centres at u = 0.25 (x = -1) and 0.75 (x = 1).
    EXPECT_FALSE(ground_lit(tracer, -1.0f, 0.0f, up));
    EXPECT_TRUE(ground_lit(tracer, 1.0f, 0.0f, up));
    EXPECT_TRUE(ground_lit(tracer, 3.0f, 0.0f, up));  // beyond the caster

    scene.materials[1].alpha_mode = AlphaMode::Blend;  // cast as MASK at 0.5
    const ShadowRayTracer blend_tracer(scene);
    EXPECT_TRUE(ground_lit(blend_tracer, 1.0f, 0.0f, up));
    scene.materials[1].alpha_mode = AlphaMode::Opaque;
    const ShadowRayTracer opaque_tracer(scene);
    EXPECT_FALSE(ground_lit(opaque_tracer, 1.0f, 0.0f, up));
}

TEST(ShadowRayTracer, InstancesUseTheirWorldTransforms) {
    Scene scene = scene_with({{make_plane(40, 40), glm::mat4(1.0f)}, {make_box({1, 1, 1}), translation({5, 2, 0})}});
    scene.instances.push_back({1, translation({-5, 2, 0})});
    const ShadowRayTracer tracer(scene);
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    EXPECT_FALSE(ground_lit(tracer, 5.0f, 0.0f, up));
    EXPECT_FALSE(ground_lit(tracer, -5.0f, 0.0f, up));
    EXPECT_TRUE(ground_lit(tracer, 0.0f, 0.0f, up));
}

TEST(AlphaMask, BilinearRepeatMatchesTheSampler) {
    const Texture texture{2, 1, {0, 0, 0, 0, 0, 0, 0, 255}};
    EXPECT_NEAR(sample_alpha(texture, {0.25f, 0.5f}), 0.0f, 1e-6f);
    EXPECT_NEAR(sample_alpha(texture, {0.75f, 0.5f}), 1.0f, 1e-6f);
    EXPECT_NEAR(sample_alpha(texture, {0.5f, 0.5f}), 0.5f, 1e-6f);
    EXPECT_NEAR(sample_alpha(texture, {1.0f, 0.5f}), 0.5f, 1e-6f);  // wraps to texel 0
    EXPECT_NEAR(sample_alpha(texture, {1.75f, 0.5f}), 1.0f, 1e-6f);
}

// The glTF sampler's wrap modes and filter, as Vulkan's texel wrapping defines them: a
// 2-texel row [0, 1] read past its right edge.
TEST(AlphaMask, ClampMirrorAndNearestMatchTheSampler) {
    Texture texture{2, 1, {0, 0, 0, 0, 0, 0, 0, 255}};
    texture.wrap_u = TextureWrap::ClampToEdge;
    EXPECT_NEAR(sample_alpha(texture, {1.0f, 0.5f}), 1.0f, 1e-6f);   // clamped to texel 1
    EXPECT_NEAR(sample_alpha(texture, {-0.5f, 0.5f}), 0.0f, 1e-6f);  // clamped to texel 0
    texture.wrap_u = TextureWrap::MirroredRepeat;
    EXPECT_NEAR(sample_alpha(texture, {1.25f, 0.5f}), 1.0f, 1e-6f);   // texel 2 mirrors to 1
    EXPECT_NEAR(sample_alpha(texture, {1.75f, 0.5f}), 0.0f, 1e-6f);   // texel 3 mirrors to 0
    EXPECT_NEAR(sample_alpha(texture, {-0.25f, 0.5f}), 0.0f, 1e-6f);  // texel -1 mirrors to 0
    texture.nearest = true;
    texture.wrap_u = TextureWrap::Repeat;
    EXPECT_EQ(sample_alpha(texture, {0.49f, 0.5f}), 0.0f);
    EXPECT_EQ(sample_alpha(texture, {0.51f, 0.5f}), 1.0f);
    EXPECT_EQ(sample_alpha(texture, {1.51f, 0.5f}), 1.0f);
}

TEST(ReferenceVisibility, SoftReferenceHasAPenumbraOfTheSunsWidth) {
    // A wall edge at height 10 m: the penumbra on the ground spans 10 * 2 tan(d / 2) metres.
    const Scene scene =
        scene_with({{make_plane(200, 200), glm::mat4(1.0f)}, {make_box({40, 0.1f, 40}), translation({-20, 10, 0})}});
    const ShadowRayTracer tracer(scene);
    SurfaceImage surfaces{200, 1, {}, {}};
    for (uint32_t x = 0; x < 200; ++x) {
        surfaces.positions.emplace_back(-0.5f + 0.005f * static_cast<float>(x), 0.0f, 0.0f, 1.0f);
        surfaces.normals.emplace_back(0.0f, 1.0f, 0.0f, 0.0f);
    }
    const ReferenceImages reference = trace_reference(tracer, surfaces, {{0, 1, 0}, 2.0f, 256});
    const float penumbra = 10.0f * 2.0f * std::tan(glm::radians(1.0f));  // 0.349 m
    for (uint32_t x = 0; x < 200; ++x) {
        const float position_x = surfaces.positions[x].x;
        if (std::abs(position_x) > 1e-3f) {
            EXPECT_EQ(reference.hard[x], position_x > 0.0f ? 1 : 0) << position_x;
        }
        if (position_x < -penumbra / 2 - 0.01f) {
            EXPECT_EQ(reference.soft[x], 0.0f);
        } else if (position_x > penumbra / 2 + 0.01f) {
            EXPECT_EQ(reference.soft[x], 1.0f);
        }
        if (std::abs(position_x) < penumbra / 2 - 0.02f) {
            EXPECT_GT(reference.soft[x], 0.0f);
            EXPECT_LT(reference.soft[x], 1.0f);
        }
    }
    EXPECT_NEAR(reference.soft[100], 0.5f, 0.05f);  // x = 0: half the disk
}

}  // namespace
}  // namespace penumbra::quality
