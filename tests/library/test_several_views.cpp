// Several views in one ShadowSystem (prepare() with a list of views): each view's sun
// shadow is exactly what a system with that view alone renders, frame after frame with the
// caches on, a dynamic box moving and a static box moved (cascades drawn per cascade and
// layered, and the virtual shadow map); views that come and go keep the first view's cache
// and release their memory; each view's passes are timed under their own names; misuse is
// named.
#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// The sun's technique, and for the cascades the strategy that draws them (the layered one
// culls every caster on the GPU per cascade tile with the cache).
struct SunCase {
    ShadowTechnique technique;
    ShadowStrategy strategy;
    const char* name;
};

class SeveralViewsTest : public LibraryTest, public ::testing::WithParamInterface<SunCase> {
protected:
    static ShadowTechnique technique() { return GetParam().technique; }

    // The top-down camera over (x, 0, z), with a still sampling pattern.
    static ViewDesc top_down_at(float x, float z) {
        ViewDesc view = top_down_view_at(x, z);
        view.sampling_frame = 0;
        return view;
    }

    Settings technique_settings() const {
        Settings settings = test_settings();
        settings.shadow.technique = GetParam().technique;
        settings.shadow.strategy = GetParam().strategy;
        settings.shadow.virtual_maps.pool_mib = 16;
        settings.shadow.cache_static_casters = true;
        return settings;
    }

    // Static boxes across the ground, a dynamic box, and the sun.
    static BoxesAndMover add_boxes(ShadowSystem& shadows) {
        BoxesAndMover scene = add_box_row_and_mover(shadows);
        const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
        shadows.set_lights({&sun, 1});
        return scene;
    }

    // One frame of every view in `views`: the ground's depth (the same for every top-down
    // view at this height), each view's page marking, the maps, each view's resolve; then
    // each view's sun visibility.
    std::vector<VisibilityImage2D> render_views(ShadowSystem& shadows, std::span<const ViewDesc> views) {
        shadows.prepare(views);
        submit([&](VkCommandBuffer cmd) {
            record_ground_depth(cmd, views[0], nullptr, NormalEncoding::SignedFloat, nullptr);
            for (uint32_t v = 0; v < views.size(); ++v) {
                shadows.record_page_marking(cmd, depth_screen(view_projection_of(views[v])), v);
            }
            shadows.record_shadow_maps(cmd);
            for (uint32_t v = 0; v < views.size(); ++v) {
                shadows.record_visibility(cmd, depth_screen(view_projection_of(views[v])), v);
            }
        });
        std::vector<VisibilityImage2D> images;
        for (uint32_t v = 0; v < views.size(); ++v) images.push_back(read_visibility(shadows, 0, v));
        return images;
    }
};

TEST_P(SeveralViewsTest, EachViewShadowsAsIfItWereAlone) {
    ShadowSystem both(system_desc(technique_settings()));
    ShadowSystem first_alone(system_desc(technique_settings()));
    ShadowSystem second_alone(system_desc(technique_settings()));
    ShadowSystem* systems[3] = {&both, &first_alone, &second_alone};
    std::vector<BoxesAndMover> scenes;
    for (ShadowSystem* system : systems) scenes.push_back(add_boxes(*system));
    for (int f = 0; f < 6; ++f) {
        const float t = static_cast<float>(f);
        for (size_t s = 0; s < 3; ++s) {
            systems[s]->set_instance_transform(scenes[s].mover, translation({2.0f * std::sin(0.7f * t), 2.0f, 2.0f}));
            if (f == 3) systems[s]->set_instance_transform(scenes[s].statics[3], translation({5.0f, 1.2f, -1.0f}));
        }
        const ViewDesc views[2] = {top_down_at(0.3f * t, -0.2f * t), top_down_at(6.0f - 0.25f * t, 1.0f + 0.2f * t)};
        const std::vector<VisibilityImage2D> together = render_views(both, views);
        const VisibilityImage2D alone[2] = {render_visibility_from(first_alone, views[0]),
                                            render_visibility_from(second_alone, views[1])};
        for (size_t v = 0; v < 2; ++v) {
            EXPECT_GT(shadowed_pixels(alone[v]), 300u) << "view " << v << " sees shadows, frame " << f;
            EXPECT_EQ(differing_pixels(together[v], alone[v]), 0u) << "view " << v << ", frame " << f;
        }
        EXPECT_NE(differing_pixels(together[0], together[1]), 0u) << "the views see different ground";
    }
}

TEST_P(SeveralViewsTest, FrameInfoReportsEveryViewAndTheFirstAtTheTop) {
    ShadowSystem shadows(system_desc(technique_settings()));
    add_boxes(shadows);
    const ViewDesc views[2] = {top_down_at(0.0f, 0.0f), top_down_at(40.0f, 0.0f)};
    const FrameInfo& info = shadows.prepare(views);
    ASSERT_EQ(info.views.size(), 2u);
    EXPECT_EQ(info.descriptor_set, info.views[0].descriptor_set);
    EXPECT_NE(info.views[0].descriptor_set, info.views[1].descriptor_set);
    EXPECT_EQ(info.shadow_distance, info.views[0].shadow_distance);
    EXPECT_EQ(info.cascades.size(), info.views[0].cascades.size());
    EXPECT_EQ(info.virtual_map.has_value(), technique() == ShadowTechnique::Virtual);
    if (technique() == ShadowTechnique::Cascades) {
        ASSERT_EQ(info.views[1].cascades.size(), info.cascades.size());
        for (size_t c = 0; c < info.cascades.size(); ++c) {
            EXPECT_EQ(info.cascades[c].split_far, info.views[1].cascades[c].split_far) << "the same frustum";
            EXPECT_NE(info.cascades[c].view_projection.m, info.views[1].cascades[c].view_projection.m)
                << "fitted 40 m apart, cascade " << c;
        }
    } else {
        ASSERT_TRUE(info.views[1].virtual_map.has_value());
        EXPECT_EQ(info.views[1].virtual_map->levels, info.virtual_map->levels);
    }
    const ShadowMaps first = shadows.shadow_maps(0);
    const ShadowMaps second = shadows.shadow_maps(1);
    EXPECT_NE(first.cascades.image, second.cascades.image);
    EXPECT_EQ(first.local.image, second.local.image) << "the local lights' maps are shared";
    if (technique() == ShadowTechnique::Virtual) {
        EXPECT_NE(first.virtual_pool.image, second.virtual_pool.image);
    }
}

TEST_P(SeveralViewsTest, ViewsThatComeAndGoKeepTheFirstViewsCacheAndTheirMemory) {
    ShadowSystem shadows(system_desc(technique_settings(), 1));
    add_boxes(shadows);
    const ViewDesc first = top_down_at(0.0f, 0.0f);
    const ViewDesc second = top_down_at(5.0f, 3.0f);
    const ViewDesc pair[2] = {first, second};
    render_views(shadows, pair);
    const MemoryStats two = shadows.memory();
    render_views(shadows, pair);
    render_visibility_from(shadows, first);
    const MemoryStats one = shadows.memory();
    if (technique() == ShadowTechnique::Cascades) {
        EXPECT_EQ(two.cascade_maps, 2 * one.cascade_maps);
    } else {
        EXPECT_EQ(two.virtual_pool, 2 * one.virtual_pool);
        EXPECT_EQ(one.virtual_pool, uint64_t{16} << 20);
    }
    EXPECT_EQ(two.visibility, 2 * one.visibility);
    EXPECT_THROW(static_cast<void>(shadows.visibility_image(1)), UsageError) << "view 1 is gone";
    // The first view's cache survived the second view's coming and going; the second view
    // starts anew.
    const FrameInfo& info = shadows.prepare(pair);
    ASSERT_EQ(info.views.size(), 2u);
    if (technique() == ShadowTechnique::Cascades) {
        for (const CascadeInfo& cascade : info.views[0].cascades) EXPECT_TRUE(cascade.cache_reused);
        for (const CascadeInfo& cascade : info.views[1].cascades) EXPECT_FALSE(cascade.cache_reused);
    } else {
        EXPECT_FALSE(info.views[0].virtual_map->invalidated_all);
        EXPECT_TRUE(info.views[1].virtual_map->invalidated_all);
    }
}

TEST_P(SeveralViewsTest, EachViewsPassesAreTimedUnderItsOwnName) {
    ShadowSystem shadows(system_desc(technique_settings()));
    add_boxes(shadows);
    const ViewDesc views[2] = {top_down_at(0.0f, 0.0f), top_down_at(5.0f, 3.0f)};
    render_views(shadows, views);
    const std::optional<GpuTimes> times = shadows.gpu_times(1);
    if (!times) GTEST_SKIP() << "the queue has no timestamps";
    const auto has = [&](const std::string& name) {
        return std::any_of(times->passes.begin(), times->passes.end(),
                           [&](const PassTime& pass) { return pass.name == name; });
    };
    const std::string sun_pass = technique() == ShadowTechnique::Virtual          ? "shadow_virtual_raster"
                                 : GetParam().strategy == ShadowStrategy::Layered ? "shadow_layered"
                                                                                  : "shadow_cascade_0";
    EXPECT_TRUE(has(sun_pass));
    EXPECT_TRUE(has(sun_pass + "_view1"));
    EXPECT_TRUE(has("visibility"));
    EXPECT_TRUE(has("visibility_view1"));
    EXPECT_FALSE(has("shadow_local_view1")) << "the local lights are the frame's, not a view's";
}

TEST_P(SeveralViewsTest, MisuseIsNamed) {
    ShadowSystem shadows(system_desc(technique_settings()));
    add_boxes(shadows);
    expect_error<InputError>([&] { shadows.prepare(std::span<const ViewDesc>()); },
                             "ShadowSystem::prepare: 0 views; it takes 1..8");
    const std::vector<ViewDesc> nine(9, top_down_at(0.0f, 0.0f));
    expect_error<InputError>([&] { shadows.prepare(nine); }, "9 views; it takes 1..8");
    ViewDesc bad = top_down_at(1.0f, 0.0f);
    bad.fov_y_radians = 4.0f;
    const ViewDesc with_bad[2] = {top_down_at(0.0f, 0.0f), bad};
    expect_error<InputError>([&] { shadows.prepare(with_bad); },
                             "ShadowSystem::prepare: views[1]: ViewDesc::fov_y_radians");
    EXPECT_THROW(static_cast<void>(shadows.shadow_maps(1)), UsageError) << "no view 1 yet";

    const ViewDesc views[2] = {top_down_at(0.0f, 0.0f), top_down_at(5.0f, 3.0f)};
    shadows.prepare(views);
    submit([&](VkCommandBuffer cmd) {
        record_ground_depth(cmd, views[0], nullptr, NormalEncoding::SignedFloat, nullptr);
        const ScreenInputs screens[2] = {depth_screen(view_projection_of(views[0])),
                                         depth_screen(view_projection_of(views[1]))};
        expect_error<UsageError>(
            [&] { shadows.record_page_marking(cmd, screens[0], 2); },
            "ShadowSystem::record_page_marking: view 2 is not a view of the last prepare(), which had 2");
        shadows.record_page_marking(cmd, screens[0], 0);
        if (technique() == ShadowTechnique::Virtual) {
            expect_error<UsageError>([&] { shadows.record_shadow_maps(cmd); }, "record_page_marking() of view 1");
        }
        shadows.record_page_marking(cmd, screens[1], 1);
        expect_error<UsageError>([&] { shadows.record_page_marking(cmd, screens[1], 1); }, "once per frame and view");
        shadows.record_shadow_maps(cmd);
        shadows.record_visibility(cmd, screens[1], 1);
        expect_error<UsageError>([&] { shadows.record_visibility(cmd, screens[1], 1); }, "once per frame and view");
        expect_error<UsageError>([&] { shadows.record_visibility(cmd, screens[1], 3); }, "view 3 is not a view");
    });
    expect_error<UsageError>([&] { static_cast<void>(shadows.visibility_image(0)); },
                             "record_visibility() has not been recorded yet");
    EXPECT_EQ(shadows.visibility_image(1).width, kScreen);
}

INSTANTIATE_TEST_SUITE_P(Techniques, SeveralViewsTest,
                         ::testing::Values(SunCase{ShadowTechnique::Cascades, ShadowStrategy::PerCascade, "Cascades"},
                                           SunCase{ShadowTechnique::Cascades, ShadowStrategy::Layered,
                                                   "LayeredCascades"},
                                           SunCase{ShadowTechnique::Virtual, ShadowStrategy::PerCascade, "Virtual"}),
                         [](const ::testing::TestParamInfo<SunCase>& sun) { return std::string(sun.param.name); });

}  // namespace
}  // namespace penumbra::library_tests
