// One set of shadow maps per frame in flight (ShadowSystemDesc::maps_per_frame_in_flight):
// every frame's shadows equal those of a system with one set, frame after frame with the
// caches on, a dynamic box moving and static boxes moved (each set draws each change in
// its turn); frame N + 1's shadow passes may run before frame N's sampling without changing
// what frame N samples (with one set they do change it); the sets alternate and take the
// memory they say.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

class MapsPerFrameTest : public LibraryTest, public ::testing::WithParamInterface<ShadowTechnique> {
protected:
    static ViewDesc still_view_at(float x, float z) {
        ViewDesc view = top_down_view_at(x, z);
        view.sampling_frame = 0;
        return view;
    }

    ShadowSystemDesc desc(bool per_frame, uint32_t frames_in_flight = 2) const {
        Settings settings = test_settings();
        settings.shadow.technique = GetParam();
        settings.shadow.virtual_maps.pool_mib = 16;
        settings.shadow.cache_static_casters = true;
        ShadowSystemDesc made = system_desc(settings, frames_in_flight);
        made.maps_per_frame_in_flight = per_frame;
        return made;
    }

    // Static boxes across the ground, a dynamic box, the sun and two spot lights.
    static BoxesAndMover add_boxes(ShadowSystem& shadows) {
        BoxesAndMover scene = add_box_row_and_mover(shadows);
        // The second spot light reaches static boxes only: its layer is kept between frames.
        LightDesc still_spot{LightType::Spot, {0.0f, -1.0f, 0.0f}, {7.0f, 6.0f, -1.5f}};
        still_spot.inner_angle_degrees = 15.0f;
        still_spot.outer_angle_degrees = 25.0f;
        const LightDesc lights[3] = {{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                                     {LightType::Spot, {0.2f, -1.0f, 0.1f}, {-1.0f, 9.0f, 0.0f}},
                                     still_spot};
        shadows.set_lights(lights);
        return scene;
    }

    // Frame f's changes: the dynamic box moves every frame, a static box moves at frames 3
    // and 6 (one set draws each change first, the others in their turn; the second under
    // the still spot light, whose layer is otherwise kept).
    static void change_scene(ShadowSystem& shadows, const BoxesAndMover& scene, int f) {
        const float t = static_cast<float>(f);
        shadows.set_instance_transform(scene.mover, translation({2.5f * std::sin(0.9f * t), 2.0f, 2.0f}));
        if (f == 3) shadows.set_instance_transform(scene.statics[3], translation({5.0f, 1.2f, -1.0f}));
        if (f == 6) shadows.set_instance_transform(scene.statics[4], translation({6.5f, 1.0f, -0.5f}));
    }

    // Submits `cmds` in this order in one batch, waits and frees them.
    void submit_in_order(const std::vector<VkCommandBuffer>& cmds) const {
        std::vector<VkCommandBufferSubmitInfo> infos;
        for (VkCommandBuffer cmd : cmds) {
            VkCommandBufferSubmitInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
            info.commandBuffer = cmd;
            infos.push_back(info);
        }
        VkSubmitInfo2 submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit_info.commandBufferInfoCount = static_cast<uint32_t>(infos.size());
        submit_info.pCommandBufferInfos = infos.data();
        TEST_VK(vkQueueSubmit2(device_.queue, 1, &submit_info, VK_NULL_HANDLE));
        TEST_VK(vkQueueWaitIdle(device_.queue));
        vkFreeCommandBuffers(device_.device, pool_, static_cast<uint32_t>(cmds.size()), cmds.data());
    }

    // Frame N's shadow passes and resolve are recorded, then frame N + 1 is prepared (after
    // `between`) and its shadow passes recorded; they are submitted in the order N's maps,
    // N + 1's maps, N's resolve: frame N's sun visibility as that resolve saw it.
    VisibilityImage2D resolve_after_the_next_frames_maps(ShadowSystem& shadows, const ViewDesc& view,
                                                         const std::function<void()>& between) {
        const ScreenInputs screen = depth_screen(view_projection_of(view));
        shadows.prepare(view);
        const VkCommandBuffer maps_n = record_commands(pool_, [&](VkCommandBuffer cmd) {
            record_ground_depth(cmd, view, nullptr, NormalEncoding::SignedFloat, nullptr);
            shadows.record_page_marking(cmd, screen);
            shadows.record_shadow_maps(cmd);
        });
        const VkCommandBuffer resolve_n =
            record_commands(pool_, [&](VkCommandBuffer cmd) { shadows.record_visibility(cmd, screen); });
        between();
        shadows.prepare(view);
        const VkCommandBuffer maps_next = record_commands(pool_, [&](VkCommandBuffer cmd) {
            shadows.record_page_marking(cmd, screen);
            shadows.record_shadow_maps(cmd);
        });
        submit_in_order({maps_n, maps_next, resolve_n});
        return read_visibility(shadows, 0);
    }
};

TEST_P(MapsPerFrameTest, EveryFrameEqualsOneSetOfMaps) {
    for (const uint32_t frames_in_flight : {2u, 3u}) {
        ShadowSystem per_frame(desc(true, frames_in_flight));
        ShadowSystem one_set(desc(false, frames_in_flight));
        const BoxesAndMover per_frame_scene = add_boxes(per_frame);
        const BoxesAndMover one_set_scene = add_boxes(one_set);
        for (int f = 0; f < 8; ++f) {
            change_scene(per_frame, per_frame_scene, f);
            change_scene(one_set, one_set_scene, f);
            const ViewDesc view = still_view_at(0.2f * static_cast<float>(f), 0.0f);
            const VisibilityImage2D expected_sun = render_visibility_from(one_set, view);
            const VisibilityImage2D sun = render_visibility_from(per_frame, view);
            EXPECT_GT(shadowed_pixels(expected_sun), 300u) << "frame " << f;
            EXPECT_EQ(differing_pixels(sun, expected_sun), 0u)
                << "the sun, frame " << f << " of " << frames_in_flight << " in flight";
            for (uint32_t spot = 1; spot <= 2; ++spot) {
                const VisibilityImage2D expected = read_visibility(one_set, spot);
                EXPECT_GT(shadowed_pixels(expected), 100u) << "spot " << spot << ", frame " << f;
                EXPECT_EQ(differing_pixels(read_visibility(per_frame, spot), expected), 0u)
                    << "spot " << spot << ", frame " << f << " of " << frames_in_flight << " in flight";
            }
        }
    }
}

TEST_P(MapsPerFrameTest, TheNextFramesMapsDoNotChangeWhatAFrameSamples) {
    const ViewDesc view = still_view_at(0.0f, 0.0f);
    const auto frame_n_as_sampled = [&](bool per_frame) {
        ShadowSystem shadows(desc(per_frame));
        const BoxesAndMover scene = add_boxes(shadows);
        render_visibility_from(shadows, view);  // the caches hold the scene
        change_scene(shadows, scene, 1);
        return resolve_after_the_next_frames_maps(shadows, view, [&] { change_scene(shadows, scene, 3); });
    };
    // Frame N alone, in the usual order.
    ShadowSystem reference(desc(false));
    const BoxesAndMover scene = add_boxes(reference);
    render_visibility_from(reference, view);
    change_scene(reference, scene, 1);
    const VisibilityImage2D expected = render_visibility_from(reference, view);
    ASSERT_GT(shadowed_pixels(expected), 300u);

    EXPECT_EQ(differing_pixels(frame_n_as_sampled(true), expected), 0u) << "frame N + 1 drew its own set of maps";
    EXPECT_GT(differing_pixels(frame_n_as_sampled(false), expected), 100u)
        << "with one set, frame N + 1's passes overwrite what frame N samples (the test can tell)";
}

TEST_P(MapsPerFrameTest, SetsAlternateAndTakeTheirMemory) {
    const ViewDesc view = still_view_at(0.0f, 0.0f);
    ShadowSystem per_frame(desc(true, 3));
    ShadowSystem one_set(desc(false, 3));
    add_boxes(per_frame);
    add_boxes(one_set);
    std::vector<VkImage> sun_maps;
    std::vector<VkImage> spot_maps;
    for (int f = 0; f < 4; ++f) {
        render_visibility_from(one_set, view);
        render_visibility_from(per_frame, view);
        const ShadowMaps maps = per_frame.shadow_maps();
        sun_maps.push_back(GetParam() == ShadowTechnique::Virtual ? maps.virtual_pool.image : maps.cascades.image);
        spot_maps.push_back(maps.local.image);
    }
    for (size_t f = 0; f < 3; ++f) {
        for (size_t g = f + 1; g < 3; ++g) {
            EXPECT_NE(sun_maps[f], sun_maps[g]) << "frames " << f + 1 << " and " << g + 1;
            EXPECT_NE(spot_maps[f], spot_maps[g]) << "frames " << f + 1 << " and " << g + 1;
        }
    }
    EXPECT_EQ(sun_maps[3], sun_maps[0]) << "frame 4 draws frame 1's set again";
    EXPECT_EQ(spot_maps[3], spot_maps[0]);
    const MemoryStats three = per_frame.memory();
    const MemoryStats one = one_set.memory();
    EXPECT_EQ(three.cascade_maps, 3 * one.cascade_maps);
    EXPECT_EQ(three.virtual_pool, 3 * one.virtual_pool);
    EXPECT_EQ(three.local_maps, 3 * one.local_maps);
    EXPECT_GT(one.local_maps, 0u);
    EXPECT_EQ(three.visibility, one.visibility) << "the visibility image is the view's, not a set's";
}

INSTANTIATE_TEST_SUITE_P(Techniques, MapsPerFrameTest,
                         ::testing::Values(ShadowTechnique::Cascades, ShadowTechnique::Virtual),
                         [](const ::testing::TestParamInfo<ShadowTechnique>& technique) {
                             return std::string(technique.param == ShadowTechnique::Cascades ? "Cascades" : "Virtual");
                         });

}  // namespace
}  // namespace penumbra::library_tests
