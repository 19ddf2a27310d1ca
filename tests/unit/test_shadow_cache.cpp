// Cached cascades' planning (core/shadow_cache.hpp): a cascade that follows the camera
// under the stable fit moves by whole texels with an unchanged depth mapping, the shifted
// cache and the exposed strips cover the map exactly once, a caster's footprint holds
// every texel it can touch, and the plan redraws what changed and nothing else.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/camera_math.hpp"
#include "core/shadow_cache.hpp"

namespace penumbra {
namespace {

using core::Aabb;
using core::Camera;

float uniform(std::mt19937& rng, float low, float high) {
    return std::uniform_real_distribution<float>(low, high)(rng);
}

struct CacheSetup {
    Camera camera;
    glm::vec3 light_direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    CascadeSettings settings;
    Aabb scene;
};

CacheSetup random_setup(std::mt19937& rng) {
    CacheSetup setup;
    setup.camera.eye = {uniform(rng, -40.0f, 40.0f), uniform(rng, 1.0f, 20.0f), uniform(rng, -40.0f, 40.0f)};
    setup.camera.target = setup.camera.eye + glm::vec3(uniform(rng, -1.0f, 1.0f), -0.3f, uniform(rng, -1.0f, 1.0f));
    setup.camera.far_plane = 200.0f;
    setup.settings.resolution = 512u << std::uniform_int_distribution<int>(0, 3)(rng);
    setup.settings.max_distance = uniform(rng, 30.0f, 150.0f);
    setup.scene.expand(glm::vec3(-100.0f, -1.0f, -100.0f));
    setup.scene.expand(glm::vec3(100.0f, uniform(rng, 5.0f, 40.0f), 100.0f));
    return setup;
}

CascadeSet cascades_for(const CacheSetup& setup) {
    return compute_cascades(make_camera_view(setup.camera, 16.0f / 9.0f), setup.light_direction, setup.settings,
                            setup.scene);
}

glm::vec2 texel_of(const Cascade& cascade, const glm::vec3& world, uint32_t resolution) {
    const glm::vec4 clip = cascade.view_projection * glm::vec4(world, 1.0f);
    return (glm::vec2(clip) * 0.5f + 0.5f) * static_cast<float>(resolution);
}

TEST(ShadowCache, CameraMovesShiftTheCascadesByWholeTexelsAndMoveTheirContentAlong) {
    std::mt19937 rng(15);
    for (int i = 0; i < 200; ++i) {
        CacheSetup setup = random_setup(rng);
        const CascadeSet before = cascades_for(setup);
        const glm::vec3 step(uniform(rng, -3.0f, 3.0f), uniform(rng, -0.5f, 0.5f), uniform(rng, -3.0f, 3.0f));
        setup.camera.eye += step;
        setup.camera.target += step;
        const CascadeSet after = cascades_for(setup);
        const uint32_t resolution = setup.settings.resolution;
        for (size_t c = 0; c < before.cascades.size(); ++c) {
            const std::optional<glm::ivec2> shift = whole_texel_shift(before.cascades[c], after.cascades[c]);
            ASSERT_TRUE(shift) << "case " << i << " cascade " << c;
            // A point of the scene lands shift texels further in the new map.
            const glm::vec3 point(uniform(rng, -50.0f, 50.0f), uniform(rng, 0.0f, 5.0f), uniform(rng, -50.0f, 50.0f));
            const glm::vec2 moved =
                texel_of(after.cascades[c], point, resolution) - texel_of(before.cascades[c], point, resolution);
            EXPECT_NEAR(moved.x, static_cast<float>(shift->x), 0.01f) << "case " << i;
            EXPECT_NEAR(moved.y, static_cast<float>(shift->y), 0.01f) << "case " << i;
        }
    }
}

TEST(ShadowCache, ALightTurnOrANewDepthRangeOrATightFitIsNotAShift) {
    std::mt19937 rng(16);
    CacheSetup setup = random_setup(rng);
    const CascadeSet before = cascades_for(setup);
    CacheSetup turned = setup;
    turned.light_direction = glm::normalize(setup.light_direction + glm::vec3(0.01f, 0.0f, 0.0f));
    EXPECT_FALSE(whole_texel_shift(before.cascades[0], cascades_for(turned).cascades[0]));
    CacheSetup taller = setup;
    taller.scene.expand(glm::vec3(0.0f, 80.0f, 0.0f));  // a new caster above the scene: another depth range
    EXPECT_FALSE(whole_texel_shift(before.cascades[0], cascades_for(taller).cascades[0]));
    CacheSetup tight = setup;
    tight.settings.fit = FitMode::Tight;
    const CascadeSet tight_before = cascades_for(tight);
    tight.camera.target += glm::vec3(0.3f, 0.0f, 0.0f);  // turning the camera reshapes a tight window
    EXPECT_FALSE(whole_texel_shift(tight_before.cascades[1], cascades_for(tight).cascades[1]));
    EXPECT_EQ(whole_texel_shift(before.cascades[2], before.cascades[2]), glm::ivec2(0));
}

// Every texel of the map comes once: from the shifted cache or from an exposed strip.
TEST(ShadowCache, TheShiftedCacheAndTheExposedStripsCoverTheMapOnce) {
    constexpr int kSize = 16;
    for (int dy = -kSize - 1; dy <= kSize + 1; ++dy) {
        for (int dx = -kSize - 1; dx <= kSize + 1; ++dx) {
            const std::vector<TexelRect> exposed = exposed_by_shift({dx, dy}, kSize);
            EXPECT_LE(exposed.size(), 2u);
            for (int y = 0; y < kSize; ++y) {
                for (int x = 0; x < kSize; ++x) {
                    const bool from_cache = x - dx >= 0 && x - dx < kSize && y - dy >= 0 && y - dy < kSize;
                    int times = from_cache ? 1 : 0;
                    for (const TexelRect& rect : exposed) {
                        if (x >= rect.min.x && x < rect.max.x && y >= rect.min.y && y < rect.max.y) ++times;
                    }
                    ASSERT_EQ(times, 1) << "shift " << dx << "," << dy << " texel " << x << "," << y;
                }
            }
        }
    }
}

TEST(ShadowCache, AFootprintHoldsEveryTexelOfItsBoxAndNothingBeyondTheFarSide) {
    std::mt19937 rng(17);
    const CacheSetup setup = random_setup(rng);
    const CascadeSet set = cascades_for(setup);
    const uint32_t resolution = setup.settings.resolution;
    for (int i = 0; i < 200; ++i) {
        const Cascade& cascade = set.cascades[static_cast<size_t>(i) % set.cascades.size()];
        Aabb box;
        const glm::vec3 corner = setup.camera.eye + glm::vec3(uniform(rng, -30.0f, 30.0f), uniform(rng, -5.0f, 5.0f),
                                                              uniform(rng, -30.0f, 30.0f));
        box.expand(corner);
        box.expand(corner + glm::vec3(uniform(rng, 0.0f, 4.0f), uniform(rng, 0.0f, 4.0f), uniform(rng, 0.0f, 4.0f)));
        const TexelRect footprint = caster_footprint(cascade, box, resolution);
        for (int k = 0; k < 20; ++k) {
            const glm::vec3 point =
                glm::mix(box.min, box.max,
                         glm::vec3(uniform(rng, 0.0f, 1.0f), uniform(rng, 0.0f, 1.0f), uniform(rng, 0.0f, 1.0f)));
            const glm::ivec2 texel(glm::floor(texel_of(cascade, point, resolution)));
            const bool inside_map = glm::all(glm::greaterThanEqual(texel, glm::ivec2(0))) &&
                                    glm::all(glm::lessThan(texel, glm::ivec2(static_cast<int>(resolution))));
            if (!inside_map) continue;
            EXPECT_TRUE(texel.x >= footprint.min.x && texel.x < footprint.max.x && texel.y >= footprint.min.y &&
                        texel.y < footprint.max.y)
                << "case " << i;
        }
    }
    Aabb below;  // under the scene, beyond every cascade's far side
    below.expand(glm::vec3(-1.0f, -500.0f, -1.0f));
    below.expand(glm::vec3(1.0f, -400.0f, 1.0f));
    EXPECT_TRUE(caster_footprint(set.cascades[0], below, resolution).empty());
    EXPECT_TRUE(caster_footprint(set.cascades[0], Aabb{}, resolution).empty());
}

TEST(ShadowCache, ThePlanRedrawsTheExposedStripsAndTheChangedCastersOnly) {
    std::mt19937 rng(18);
    CacheSetup setup = random_setup(rng);
    setup.settings.resolution = 1024;
    const uint32_t resolution = setup.settings.resolution;
    const Cascade before = cascades_for(setup).cascades[0];
    EXPECT_FALSE(plan_cascade_update(std::nullopt, before, resolution, {}).reuse) << "no cache: render all";
    const CascadeUpdate still = plan_cascade_update(before, before, resolution, {});
    EXPECT_TRUE(still.reuse);
    EXPECT_TRUE(still.redraw.empty()) << "a still camera and no change draw nothing";
    // A moved caster: its old and new footprints.
    Aabb old_box, new_box;
    old_box.expand(setup.camera.eye + glm::vec3(2.0f, -1.0f, 2.0f));
    old_box.expand(setup.camera.eye + glm::vec3(3.0f, 0.0f, 3.0f));
    new_box = old_box;
    new_box.min.x += 2.0f;
    new_box.max.x += 2.0f;
    const Aabb changed[] = {old_box, new_box};
    const CascadeUpdate moved_caster = plan_cascade_update(before, before, resolution, changed);
    ASSERT_TRUE(moved_caster.reuse);
    ASSERT_EQ(moved_caster.redraw.size(), 2u);
    EXPECT_EQ(moved_caster.redraw[0], caster_footprint(before, old_box, resolution));
    EXPECT_LT(moved_caster.redraw_texels(), whole_map(resolution).area() / 8);
    // A moved camera: the strips its shift exposes.
    CacheSetup walked = setup;
    walked.camera.eye += glm::vec3(1.5f, 0.0f, 0.5f);
    walked.camera.target += glm::vec3(1.5f, 0.0f, 0.5f);
    const Cascade after = cascades_for(walked).cascades[0];
    const CascadeUpdate walk = plan_cascade_update(before, after, resolution, {});
    ASSERT_TRUE(walk.reuse);
    EXPECT_EQ(walk.redraw, exposed_by_shift(walk.shift, resolution));
    EXPECT_NE(walk.shift, glm::ivec2(0));
    // Too much to redraw: everything.
    std::vector<Aabb> many(kMaxRedrawRects + 1, old_box);
    EXPECT_FALSE(plan_cascade_update(before, before, resolution, many).reuse);
}

TEST(ShadowCache, ToroidalLayersKeepAWorldPointAtOneLayerTexelWhileTheCascadeMoves) {
    std::mt19937 rng(18);
    for (int i = 0; i < 200; ++i) {
        CacheSetup setup = random_setup(rng);
        const uint32_t resolution = setup.settings.resolution;
        CascadeSet before = cascades_for(setup);
        const glm::vec3 step(uniform(rng, -30.0f, 30.0f), 0.0f, uniform(rng, -30.0f, 30.0f));
        setup.camera.eye += step;
        setup.camera.target += step;
        CascadeSet after = cascades_for(setup);
        place_in_layers(before, resolution, true);
        place_in_layers(after, resolution, true);
        const float side = static_cast<float>(resolution);
        for (size_t c = 0; c < before.cascades.size(); ++c) {
            for (const Cascade* cascade : {&before.cascades[c], &after.cascades[c]}) {
                EXPECT_TRUE(glm::all(glm::greaterThanEqual(cascade->layer_origin, glm::ivec2(0))));
                EXPECT_TRUE(glm::all(glm::lessThan(cascade->layer_origin, glm::ivec2(static_cast<int>(resolution)))));
            }
            const glm::vec3 point(uniform(rng, -50.0f, 50.0f), uniform(rng, 0.0f, 5.0f), uniform(rng, -50.0f, 50.0f));
            const auto layer_texel = [&](const Cascade& cascade) {
                const glm::vec2 texel = texel_of(cascade, point, resolution) + glm::vec2(cascade.layer_origin);
                return texel - side * glm::floor(texel / side);  // modulo the layer's side
            };
            const glm::vec2 moved = layer_texel(after.cascades[c]) - layer_texel(before.cascades[c]);
            // The same layer texel (or the same one seen across the wrap).
            for (int axis = 0; axis < 2; ++axis) {
                const float wrapped = moved[axis] - side * std::round(moved[axis] / side);
                EXPECT_NEAR(wrapped, 0.0f, 0.01f) << "case " << i << " cascade " << c;
            }
        }
        place_in_layers(after, resolution, false);
        for (const Cascade& cascade : after.cascades) EXPECT_EQ(cascade.layer_origin, glm::ivec2(0));
    }
}

TEST(ShadowCache, LayerPiecesCoverTheWindowRectangleOnceAtItsWrappedLayerTexels) {
    std::mt19937 rng(19);
    const uint32_t resolution = 16;
    const int size = static_cast<int>(resolution);
    for (int i = 0; i < 500; ++i) {
        const auto coordinate = [&](int low, int high) { return std::uniform_int_distribution<int>(low, high)(rng); };
        const glm::ivec2 origin(coordinate(0, size - 1), coordinate(0, size - 1));
        const glm::ivec2 a(coordinate(0, size), coordinate(0, size));
        const glm::ivec2 b(coordinate(0, size), coordinate(0, size));
        const TexelRect rect{glm::min(a, b), glm::max(a, b)};
        std::vector<int> covered(resolution * resolution, 0);
        std::vector<int> layer_covered(resolution * resolution, 0);
        for (const LayerPiece& piece : layer_pieces(rect, origin, resolution)) {
            EXPECT_FALSE(piece.window.empty());
            EXPECT_EQ(intersect(piece.layer, whole_map(resolution)), piece.layer) << "case " << i;
            EXPECT_EQ(piece.layer.max - piece.layer.min, piece.window.max - piece.window.min);
            for (int y = piece.window.min.y; y < piece.window.max.y; ++y) {
                for (int x = piece.window.min.x; x < piece.window.max.x; ++x) {
                    ++covered[y * size + x];
                    const glm::ivec2 layer = glm::ivec2(x, y) - piece.window.min + piece.layer.min;
                    EXPECT_EQ(layer, (glm::ivec2(x, y) + origin) % size) << "case " << i;
                    // The tile says which axes wrapped.
                    EXPECT_EQ((piece.tile & 1u) != 0, x + origin.x >= size);
                    EXPECT_EQ((piece.tile & 2u) != 0, y + origin.y >= size);
                    ++layer_covered[layer.y * size + layer.x];
                }
            }
        }
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const bool inside = x >= rect.min.x && x < rect.max.x && y >= rect.min.y && y < rect.max.y;
                ASSERT_EQ(covered[y * size + x], inside ? 1 : 0) << "case " << i << " texel " << x << ", " << y;
            }
        }
        for (const int count : layer_covered) ASSERT_LE(count, 1) << "case " << i;
    }
}

TEST(ShadowCache, BoxesAndOriginsNearTheFloatRangeStayDefined) {
    // Found by fuzz_shadow_system: bounds whose projection overflows to inf - inf = NaN.
    std::mt19937 rng(20);
    CacheSetup setup = random_setup(rng);
    CascadeSet set = cascades_for(setup);
    const uint32_t resolution = setup.settings.resolution;
    const Aabb huge{glm::vec3(-3.0e38f), glm::vec3(3.0e38f)};
    for (const Cascade& cascade : set.cascades) {
        EXPECT_EQ(caster_footprint(cascade, huge, resolution), whole_map(resolution)) << "conservative: every texel";
    }
    set.cascades.front().texel_origin = glm::vec2(std::numeric_limits<float>::infinity(), 1.0e30f);
    set.cascades.back().texel_origin = glm::vec2(std::nanf(""), -1.0e30f);
    place_in_layers(set, resolution, true);
    EXPECT_EQ(set.cascades.front().layer_origin, glm::ivec2(0));
    EXPECT_EQ(set.cascades.back().layer_origin, glm::ivec2(0));
}

}  // namespace
}  // namespace penumbra
