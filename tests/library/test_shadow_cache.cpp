// Cached cascades (Settings::shadow.cache_static_casters) against the same frames
// uncached, for every filter, along three camera paths (a walk that turns and then stands
// still, an orbit, a fast flythrough), with a dynamic box moving and spinning every frame,
// static boxes moved, added, removed and made dynamic on the way, and a bias changed.
// Every cascade's depth map and the ground's visibility are bit-identical to the uncached
// frames (both draw each world texel at the same layer texel: toroidal cascades), while
// the cache is reused and draws a fraction of the texels; with the per-cascade passes (the
// CPU culls) and with the layered strategy (the GPU culls into the texels drawn again).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// Boxes on a grid (static), the ground, and one box that moves every frame (dynamic).
using CacheScene = BoxesAndMover;

CacheScene add_cache_scene(ShadowSystem& shadows) {
    CacheScene scene = add_ground_and_box_mesh(shadows);
    for (int i = 0; i < 5; ++i) {
        const glm::vec3 at(-12.0f + 6.0f * static_cast<float>(i), 1.0f + 0.5f * static_cast<float>(i % 3),
                           -4.0f + 2.0f * static_cast<float>(i % 2));
        scene.statics.push_back(shadows.add_instance({scene.box_id, translation(at)}));
    }
    scene.mover =
        shadows.add_instance({scene.box_id, translation({0.0f, 2.0f, 0.0f}), kInstanceCastsShadows | kInstanceDynamic});
    const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    shadows.set_lights({&sun, 1});
    return scene;
}

// The settings of the cached system compared with an uncached one.
Settings with_cache(Settings settings) {
    settings.shadow.cache_static_casters = true;
    return settings;
}

enum class CameraPath { Walk, Orbit, Flythrough };

struct CacheCase {
    ShadowFilter filter;
    CameraPath path;
    ShadowStrategy strategy = ShadowStrategy::PerCascade;
    friend void PrintTo(const CacheCase& c, std::ostream* os) {
        static constexpr const char* kPathNames[] = {"walk", "orbit", "flythrough"};
        *os << choice_name(kShadowFilterChoices, c.filter) << ", " << kPathNames[static_cast<int>(c.path)] << ", "
            << choice_name(kShadowStrategyChoices, c.strategy);
    }
};

ViewDesc view_from(const glm::vec3& eye, const glm::vec3& target) {
    return look_at_view({eye.x, eye.y, eye.z}, {target.x, target.y, target.z}, {0.0f, 1.0f, 0.0f}, glm::radians(60.0f),
                        0.1f, 100.0f, 320, 180);
}

// Frame f of the path. Walk: 0.23 m a frame along a gentle curve, looking ahead and
// turning, then standing still from frame 15 (the dynamic box keeps moving: the cache is
// restored under it). Orbit: around the boxes at 12 m, 9 degrees a frame. Flythrough:
// 1.5 m a frame across the scene, climbing.
ViewDesc path_view(CameraPath path, int f) {
    const float t = static_cast<float>(f);
    switch (path) {
        case CameraPath::Walk: {
            const float walked = std::min(t, 15.0f);
            const glm::vec3 eye(-8.0f + 0.23f * walked, 1.7f, 6.0f - 0.005f * walked * walked);
            return view_from(eye, eye + glm::vec3(std::cos(0.04f * walked), -0.25f, -std::sin(0.04f * walked) - 1.0f));
        }
        case CameraPath::Orbit: {
            const float angle = glm::radians(9.0f) * t;
            return view_from({12.0f * std::cos(angle), 5.0f, 12.0f * std::sin(angle)}, {0.0f, 0.0f, 0.0f});
        }
        case CameraPath::Flythrough: {
            const glm::vec3 eye(-20.0f + 1.5f * t, 2.0f + 0.2f * t, 10.0f - 0.6f * t);
            return view_from(eye, eye + glm::vec3(1.0f, -0.3f, -0.4f));
        }
    }
    return view_from({0.0f, 5.0f, 10.0f}, {0.0f, 0.0f, 0.0f});
}

void change_scene(ShadowSystem& shadows, CacheScene& scene, int f) {
    const float t = static_cast<float>(f);
    // Sliding and spinning (a windmill's blade turns about its own axis); in frame 16 it
    // jumps 8 m aside and back in frame 17, so that where it was is far from where it is.
    const glm::mat4 spin = glm::rotate(glm::mat4(1.0f), 0.5f * t, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
    const float jump = f == 16 ? 8.0f : 0.0f;
    const glm::mat4 slide = glm::translate(glm::mat4(1.0f), {3.0f * std::sin(0.3f * t) + jump, 2.0f, 0.4f * t});
    shadows.set_instance_transform(scene.mover, to_mat4(slide * spin));
    if (f == 6) shadows.set_instance_transform(scene.statics[1], translation({-5.0f, 1.5f, 2.0f}));
    if (f == 9) scene.statics.push_back(shadows.add_instance({scene.box_id, translation({4.0f, 3.0f, -6.0f})}));
    if (f == 12) shadows.remove_instance(scene.statics[3]);
    if (f == 14) shadows.set_instance_flags(scene.statics[0], kInstanceCastsShadows | kInstanceDynamic);
}

class ShadowCacheTest : public LibraryTest, public ::testing::WithParamInterface<CacheCase> {};

TEST_P(ShadowCacheTest, CachedCascadesAreBitIdenticalToUncachedWithMovingCasters) {
    const CacheCase param = GetParam();
    Settings settings = test_settings();
    settings.shadow.cascades.resolution = 512;
    settings.shadow.filter.mode = param.filter;
    settings.shadow.filter.blur_radius = 5;  // wide: the moments of more texels depend on each depth
    settings.shadow.strategy = param.strategy;
    ShadowSystem uncached(system_desc(settings));
    ShadowSystem cached(system_desc(with_cache(settings)));
    CacheScene uncached_scene = add_cache_scene(uncached);
    CacheScene cached_scene = add_cache_scene(cached);
    constexpr int kFrames = 20;
    uint64_t rendered = 0, full = 0, reused = 0, copied = 0;
    for (int f = 0; f < kFrames; ++f) {
        change_scene(uncached, uncached_scene, f);
        change_scene(cached, cached_scene, f);
        if (f == 18) {  // a bias changes every depth the cache holds: it must start over
            for (ShadowSystem* system : {&uncached, &cached}) {
                Settings changed = system->settings();
                changed.shadow.bias.slope = 3.5f;
                system->update_settings(changed);
            }
        }
        const ViewDesc view = path_view(param.path, f);
        uncached.prepare(view);
        const FrameInfo& info = cached.prepare(view);
        EXPECT_TRUE(std::any_of(info.cascades.begin(), info.cascades.end(),
                                [](const CascadeInfo& cascade) { return !cascade.dynamic_regions.empty(); }))
            << "frame " << f << ": the moving box is drawn somewhere";
        for (const CascadeInfo& cascade : info.cascades) {
            // The regions it reports drew the texels it counts.
            uint64_t redrawn = 0;
            for (const TexelRegion& region : cascade.redrawn) redrawn += uint64_t{region.width} * region.height;
            EXPECT_EQ(redrawn, cascade.texels_rendered) << "frame " << f;
            rendered += cascade.texels_rendered;
            copied += cascade.texels_copied;
            full += uint64_t{512} * 512;
            reused += cascade.cache_reused ? 1 : 0;
        }
        submit([&](VkCommandBuffer cmd) {
            uncached.record_shadow_maps(cmd);
            record_ground_visibility(cmd, uncached, nullptr, NormalEncoding::SignedFloat);
        });
        const VisibilityImage2D expected_visibility = read_visibility(uncached, 0);
        const std::vector<float> expected = read_cascade_depths(uncached);
        const bool moments = uncached.shadow_maps().cascade_moments.image != VK_NULL_HANDLE;
        const std::vector<uint8_t> expected_moments =
            moments ? read_map(uncached.shadow_maps().cascade_moments) : std::vector<uint8_t>{};
        submit([&](VkCommandBuffer cmd) {
            cached.record_shadow_maps(cmd);
            record_ground_visibility(cmd, cached, nullptr, NormalEncoding::SignedFloat);
        });
        const VisibilityImage2D actual_visibility = read_visibility(cached, 0);
        const std::vector<float> actual = read_cascade_depths(cached);
        ASSERT_EQ(expected.size(), actual.size());
        if (moments) {
            // The moments too, every texel: a cached cascade converts and blurs only around
            // the texels whose depth changed.
            const std::vector<uint8_t> actual_moments = read_map(cached.shadow_maps().cascade_moments);
            ASSERT_EQ(expected_moments.size(), actual_moments.size());
            const auto [first, second] =
                std::mismatch(expected_moments.begin(), expected_moments.end(), actual_moments.begin());
            ASSERT_EQ(first, expected_moments.end())
                << "frame " << f << ": moments differ at byte " << (first - expected_moments.begin()) << " of "
                << expected_moments.size();
        }
        for (size_t i = 0; i < expected.size(); ++i) {
            ASSERT_EQ(expected[i], actual[i])
                << "frame " << f << " texel " << i % (512 * 512) << " of layer " << i / (512 * 512);
        }
        ASSERT_EQ(expected_visibility.values.size(), actual_visibility.values.size());
        for (size_t i = 0; i < expected_visibility.values.size(); ++i) {
            ASSERT_EQ(expected_visibility.values[i], actual_visibility.values[i]) << "frame " << f << " pixel " << i;
        }
    }
    // The cache did the work it exists for: reused in most cascade-frames, drawing a
    // part of the texels an uncached renderer draws (the orbit turns the view fastest).
    EXPECT_GE(reused, static_cast<uint64_t>(kFrames - 4) * 4) << "cascade-frames that reused the cache";
    EXPECT_LT(rendered, full / (param.path == CameraPath::Walk ? 4 : 2))
        << "texels drawn: " << rendered << " of " << full;
    std::printf("cached cascades: %llu of %llu texels drawn, %llu copied, %llu of %d cascade-frames reused\n",
                static_cast<unsigned long long>(rendered), static_cast<unsigned long long>(full),
                static_cast<unsigned long long>(copied), static_cast<unsigned long long>(reused), kFrames * 4);
}

// Every filter on every path with the per-cascade passes; the layered strategy (the same
// planning, its casters culled on the GPU) with every filter on one path each, the paths
// taken in turn.
std::vector<CacheCase> every_filter_and_path() {
    std::vector<CacheCase> cases;
    constexpr CameraPath kPaths[] = {CameraPath::Walk, CameraPath::Orbit, CameraPath::Flythrough};
    for (const auto& filter : kShadowFilterChoices) {
        for (const CameraPath path : kPaths) cases.push_back({filter.value, path});
    }
    for (size_t f = 0; f < std::size(kShadowFilterChoices); ++f)
        cases.push_back({kShadowFilterChoices[f].value, kPaths[f % 3], ShadowStrategy::Layered});
    return cases;
}

std::string case_name(const ::testing::TestParamInfo<CacheCase>& info) {
    static constexpr const char* kPathNames[] = {"walk", "orbit", "flythrough"};
    const bool layered = info.param.strategy == ShadowStrategy::Layered;
    return std::string(choice_name(kShadowFilterChoices, info.param.filter)) + "_" +
           kPathNames[static_cast<int>(info.param.path)] + (layered ? "_layered" : "");
}

INSTANTIATE_TEST_SUITE_P(EveryFilterAndPath, ShadowCacheTest, ::testing::ValuesIn(every_filter_and_path()), case_name);

// Cached spot and point shadows: a spot over static boxes keeps its layer while nothing in
// its reach changes, and renders it again when a static box in its cone moves, when the
// spot moves and when a bias changes; a point light with a dynamic box circling inside its
// range renders every frame. The visibility of both equals the uncached frames bit for bit.
class LocalShadowCacheTest : public LibraryTest, public ::testing::WithParamInterface<ShadowFilter> {};

struct LocalCacheScene {
    MeshArrays box = box_mesh();
    MeshArrays ground = ground_mesh();
    std::vector<InstanceId> statics;
    InstanceId mover;
};

LocalCacheScene add_local_cache_scene(ShadowSystem& shadows) {
    LocalCacheScene scene;
    const MeshId ground_id = shadows.add_mesh(scene.ground.data());
    const MeshId box_id = shadows.add_mesh(scene.box.data());
    shadows.add_instance({ground_id, Mat4{}});
    scene.statics.push_back(shadows.add_instance({box_id, translation({-3.0f, 1.0f, 1.0f})}));   // under the spot
    scene.statics.push_back(shadows.add_instance({box_id, translation({-4.5f, 0.5f, -2.0f})}));  // under the spot
    scene.statics.push_back(shadows.add_instance({box_id, translation({5.0f, 1.0f, 3.0f})}));    // by the point light
    scene.mover =
        shadows.add_instance({box_id, translation({3.5f, 2.0f, 0.0f}), kInstanceCastsShadows | kInstanceDynamic});
    return scene;
}

LightDesc spot_light(float x) {
    LightDesc spot{LightType::Spot, {0.0f, -1.0f, 0.0f}, {x, 8.0f, 0.0f}};
    spot.outer_angle_degrees = 20.0f;
    spot.inner_angle_degrees = 15.0f;
    spot.range = 20.0f;
    return spot;
}

TEST_P(LocalShadowCacheTest, CachedSpotAndPointShadowsAreBitIdenticalToUncached) {
    Settings settings = test_settings();
    settings.shadow.filter.mode = GetParam();
    // Small maps: the moment filters' conversion is slow on lavapipe (no sun: the cascades are unused).
    settings.local_shadows.resolution = 256;
    settings.shadow.cascades.resolution = 512;
    settings.shadow.cascades.count = 1;
    ShadowSystem uncached(system_desc(settings));
    ShadowSystem cached(system_desc(with_cache(settings)));
    LocalCacheScene uncached_scene = add_local_cache_scene(uncached);
    LocalCacheScene cached_scene = add_local_cache_scene(cached);
    LightDesc point{LightType::Point, {0.0f, -1.0f, 0.0f}, {3.5f, 6.0f, 0.0f}};
    point.range = 12.0f;
    constexpr int kFrames = 16;
    int spot_kept = 0, point_kept = 0;
    for (int f = 0; f < kFrames; ++f) {
        const float t = static_cast<float>(f);
        const LightDesc lights[] = {spot_light(f < 10 ? -3.0f : -2.5f), point};
        for (ShadowSystem* system : {&uncached, &cached}) {
            LocalCacheScene& scene = system == &cached ? cached_scene : uncached_scene;
            system->set_lights(lights);
            system->set_instance_transform(
                scene.mover, translation({3.5f + 1.5f * std::cos(0.7f * t), 2.0f, 1.5f * std::sin(0.7f * t)}));
            if (f == 6) system->set_instance_transform(scene.statics[1], translation({-4.0f, 0.5f, -3.0f}));
            if (f == 12) {  // a bias changes every depth the layers hold
                Settings changed = system->settings();
                changed.shadow.bias.slope = 3.5f;
                system->update_settings(changed);
            }
        }
        uncached.prepare(top_down_view());
        const FrameInfo& info = cached.prepare(top_down_view());
        ASSERT_EQ(info.local_shadows.size(), 2u);
        const bool spot_expected_kept = f != 0 && f != 6 && f != 10 && f != 12;
        EXPECT_EQ(info.local_shadows[0].layers_kept, spot_expected_kept ? 1u : 0u) << "frame " << f;
        EXPECT_EQ(info.local_shadows[0].draws, spot_expected_kept ? 0u : 3u) << "frame " << f;
        spot_kept += static_cast<int>(info.local_shadows[0].layers_kept);
        point_kept += static_cast<int>(info.local_shadows[1].layers_kept);
        for (ShadowSystem* system : {&uncached, &cached}) {
            submit([&](VkCommandBuffer cmd) {
                system->record_shadow_maps(cmd);
                record_ground_visibility(cmd, *system, nullptr, NormalEncoding::SignedFloat);
            });
        }
        for (uint32_t slot = 1; slot <= 2; ++slot) {
            const VisibilityImage2D expected = read_visibility(uncached, slot);
            const VisibilityImage2D actual = read_visibility(cached, slot);
            ASSERT_EQ(expected.values.size(), actual.values.size());
            size_t shadowed = 0;
            for (size_t i = 0; i < expected.values.size(); ++i) {
                ASSERT_EQ(expected.values[i], actual.values[i]) << "frame " << f << " slot " << slot << " pixel " << i;
                shadowed += expected.values[i] < 0.5f ? 1 : 0;
            }
            EXPECT_GT(shadowed, 0u) << "frame " << f << " slot " << slot << ": the boxes shadow the ground";
        }
    }
    // The point light's nearest caster is the circling box: its near plane, and so every
    // face, changes every frame.
    EXPECT_EQ(point_kept, 0);
    std::printf("cached local shadows: the spot kept its layer in %d of %d frames\n", spot_kept, kFrames);
}

std::string filter_name(const ::testing::TestParamInfo<ShadowFilter>& param) {
    return std::string(choice_name(kShadowFilterChoices, param.param));
}

INSTANTIATE_TEST_SUITE_P(EveryFilter, LocalShadowCacheTest,
                         ::testing::Values(ShadowFilter::Hard, ShadowFilter::Pcf, ShadowFilter::Poisson,
                                           ShadowFilter::Pcss, ShadowFilter::Vsm, ShadowFilter::Evsm,
                                           ShadowFilter::Msm),
                         filter_name);

// An engine that uploads every transform every frame, changed or not: setting the matrix an
// instance already has keeps every cache (no cascade texel or spot layer drawn again), and
// a real change among them is still seen.
TEST_F(LibraryTest, SettingAnUnchangedTransformKeepsTheCaches) {
    Settings settings = with_cache(test_settings());
    settings.shadow.cascades.resolution = 512;
    settings.local_shadows.resolution = 256;
    ShadowSystem shadows(system_desc(settings));
    BoxesAndMover scene = add_ground_and_box_mesh(shadows);
    std::vector<std::pair<InstanceId, Mat4>> placed;
    for (int i = 0; i < 4; ++i) {
        const Mat4 world = translation({-3.0f + 2.0f * static_cast<float>(i), 1.0f, 0.0f});
        placed.emplace_back(shadows.add_instance({scene.box_id, world}), world);
    }
    const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    const LightDesc lights[] = {sun, spot_light(-3.0f)};
    shadows.set_lights(lights);
    constexpr int kMovedFrame = 4;
    for (int f = 0; f < 7; ++f) {
        if (f == kMovedFrame) placed[0].second = translation({-3.0f, 1.5f, 0.0f});  // under the spot and the sun
        for (const auto& [id, world] : placed) shadows.set_instance_transform(id, world);
        const FrameInfo& info = shadows.prepare(top_down_view());
        ASSERT_EQ(info.local_shadows.size(), 1u);
        uint64_t rendered = 0;
        for (const CascadeInfo& cascade : info.cascades) {
            rendered += cascade.texels_rendered;
            if (f > 0 && f != kMovedFrame) {
                EXPECT_TRUE(cascade.cache_reused) << "frame " << f;
                EXPECT_EQ(cascade.texels_rendered, 0u) << "frame " << f;
            }
        }
        if (f > 0 && f != kMovedFrame) {
            EXPECT_EQ(info.local_shadows[0].layers_kept, 1u) << "frame " << f;
            EXPECT_EQ(info.local_shadows[0].draws, 0u) << "frame " << f;
        } else {
            EXPECT_GT(rendered, 0u) << "frame " << f << ": a moved static caster is drawn again";
            EXPECT_EQ(info.local_shadows[0].layers_kept, 0u) << "frame " << f;
        }
        submit([&](VkCommandBuffer cmd) { shadows.record_shadow_maps(cmd); });
    }
}

}  // namespace
}  // namespace penumbra::library_tests
