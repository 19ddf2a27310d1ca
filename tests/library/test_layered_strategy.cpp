// The layered strategy (the GPU culls every caster against every cascade, one layered pass
// draws them) against the per-cascade passes (the CPU culls, one pass per cascade), along
// an orbit with a box moving every frame and static boxes moved, added and removed, in
// several state buckets (mirrored, double-sided), with culling on and off: every
// cascade's depth map equals the per-cascade one (read through its toroidal layer origin)
// up to the rasteriser's rounding, and so does the ground's visibility. Equal maps need
// equal draw sets: a caster the GPU dropped, or drew into the wrong layer, changes
// thousands of texels. (Multiview is not compared texel by texel: on lavapipe, triangles
// covering whole raster tiles land in view 0 — docs/techniques.md, known driver issues.)
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

constexpr uint32_t kResolution = 512;

using LayeredScene = BoxesAndMover;

LayeredScene add_layered_scene(ShadowSystem& shadows) {
    LayeredScene scene = add_ground_and_box_mesh(shadows);
    for (int i = 0; i < 6; ++i) {
        const glm::vec3 at(-12.0f + 5.0f * static_cast<float>(i), 1.0f + 0.5f * static_cast<float>(i % 3),
                           -4.0f + 3.0f * static_cast<float>(i % 2));
        // Every other box mirrored and one double-sided: they go into other buckets.
        const glm::mat4 world = glm::scale(glm::translate(glm::mat4(1.0f), at),
                                           glm::vec3(i % 2 ? -1.0f : 1.0f, 1.0f, 1.0f + 0.2f * static_cast<float>(i)));
        const uint32_t flags = kInstanceCastsShadows | (i == 4 ? kInstanceDoubleSided : 0u);
        scene.statics.push_back(shadows.add_instance({scene.box_id, to_mat4(world), flags}));
    }
    scene.mover =
        shadows.add_instance({scene.box_id, translation({0.0f, 2.0f, 0.0f}), kInstanceCastsShadows | kInstanceDynamic});
    const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    shadows.set_lights({&sun, 1});
    return scene;
}

void change_scene(ShadowSystem& shadows, LayeredScene& scene, int f) {
    const float t = static_cast<float>(f);
    const glm::mat4 spin = glm::rotate(glm::mat4(1.0f), 0.5f * t, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
    const glm::mat4 slide = glm::translate(glm::mat4(1.0f), {3.0f * std::sin(0.3f * t), 2.0f, 0.8f * t - 4.0f});
    shadows.set_instance_transform(scene.mover, to_mat4(slide * spin));
    if (f == 3) shadows.set_instance_transform(scene.statics[1], translation({-5.0f, 1.5f, 2.0f}));
    if (f == 5) scene.statics.push_back(shadows.add_instance({scene.box_id, translation({4.0f, 3.0f, -6.0f})}));
    if (f == 7) shadows.remove_instance(scene.statics[3]);
}

ViewDesc orbit_view(int f) {
    const float angle = glm::radians(17.0f) * static_cast<float>(f);
    return look_at_view({14.0f * std::cos(angle), 5.0f + 0.5f * static_cast<float>(f), 14.0f * std::sin(angle)},
                        {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, glm::radians(60.0f), 0.1f, 100.0f, 320, 180);
}

class LayeredStrategyTest : public LibraryTest, public ::testing::WithParamInterface<bool> {
protected:
    // 512-texel cascades, culling as the parameter says.
    Settings strategy_settings(ShadowStrategy strategy) const {
        Settings settings = test_settings();
        settings.shadow.cascades.resolution = kResolution;
        settings.shadow.cull_casters = GetParam();
        settings.shadow.strategy = strategy;
        return settings;
    }

    // Frame f: the scene's changes, prepare, the shadow maps and the ground's visibility.
    const FrameInfo& render_frame(ShadowSystem& shadows, LayeredScene& scene, int f) {
        change_scene(shadows, scene, f);
        const FrameInfo& info = shadows.prepare(orbit_view(f));
        submit([&](VkCommandBuffer cmd) {
            shadows.record_shadow_maps(cmd);
            record_ground_visibility(cmd, shadows, nullptr, NormalEncoding::SignedFloat);
        });
        return info;
    }
};

// Both strategies place the cascades toroidally in their layers and draw each tile through
// the same vertex math, so every texel of every cascade and the visibility are bit-identical
// (a caster the GPU dropped, or sent to the wrong cascade or tile, changes texels inside its
// footprint).
TEST_P(LayeredStrategyTest, DepthMapsAndVisibilityEqualThePerCascadePasses) {
    ShadowSystem per_cascade(system_desc(strategy_settings(ShadowStrategy::PerCascade)));
    ShadowSystem layered(system_desc(strategy_settings(ShadowStrategy::Layered)));
    ShadowSystem* systems[] = {&per_cascade, &layered};
    std::vector<LayeredScene> scenes;
    for (ShadowSystem* system : systems) scenes.push_back(add_layered_scene(*system));
    constexpr int kFrames = 9;
    size_t covered = 0, texels = 0, wrapped = 0;
    for (int f = 0; f < kFrames; ++f) {
        std::vector<std::vector<float>> depths;
        std::vector<VisibilityImage2D> visibility;
        for (size_t s = 0; s < 2; ++s) {
            const FrameInfo& info = render_frame(*systems[s], scenes[s], f);
            depths.push_back(read_cascade_depths(*systems[s]));
            visibility.push_back(read_visibility(*systems[s], 0));
            for (const CascadeInfo& cascade : info.cascades)
                wrapped += cascade.layer_origin_x != 0 || cascade.layer_origin_y != 0;
        }
        const std::vector<float>& expected = depths[0];
        const std::vector<float>& actual = depths[1];
        ASSERT_EQ(actual.size(), expected.size());
        texels += expected.size();
        for (size_t i = 0; i < expected.size(); ++i) {
            covered += expected[i] > 0.0f;
            ASSERT_EQ(actual[i], expected[i]) << "frame " << f << ": texel " << i % (kResolution * kResolution)
                                              << " of cascade " << i / (kResolution * kResolution);
        }
        ASSERT_EQ(visibility[1].values.size(), visibility[0].values.size());
        for (size_t i = 0; i < visibility[0].values.size(); ++i)
            ASSERT_EQ(visibility[1].values[i], visibility[0].values[i]) << "frame " << f << " pixel " << i;
    }
    EXPECT_GT(covered, texels / 2) << "casters and ground cover the cascades";
    EXPECT_GT(wrapped, 0u) << "some cascades wrap around their layers' edges";
    // The culled draws' buffers are counted: room for every caster in every tile of every
    // cascade, 20 bytes of command and 8 of record each.
    const uint64_t commands = uint64_t{8} * 4 * 4;
    EXPECT_GE(layered.memory().buffers, per_cascade.memory().buffers + commands * 28);
}

// Spot and point lights with the layered strategy: their layers are culled on the GPU and
// drawn per layer from the culled commands, through the same viewport and vertex math as
// the CPU-culled passes, so their visibility is bit-identical, frame after frame, with the
// box moving through the spot's cone and the point light's cube faces.
TEST_P(LayeredStrategyTest, SpotAndPointShadowsEqualTheCpuCulledPasses) {
    ShadowSystem per_cascade(system_desc(strategy_settings(ShadowStrategy::PerCascade)));
    ShadowSystem layered(system_desc(strategy_settings(ShadowStrategy::Layered)));
    ShadowSystem* systems[] = {&per_cascade, &layered};
    std::vector<LayeredScene> scenes;
    const LightDesc spot{LightType::Spot, {0.2f, -1.0f, 0.1f}, {-4.0f, 9.0f, 0.0f}};
    const LightDesc point{LightType::Point, {0.0f, -1.0f, 0.0f}, {3.5f, 6.0f, -1.0f}};
    const LightDesc lights[] = {spot, point};
    for (ShadowSystem* system : systems) {
        scenes.push_back(add_layered_scene(*system));
        system->set_lights(lights);
    }
    size_t shadowed = 0;
    for (int f = 0; f < 6; ++f) {
        std::vector<std::vector<VisibilityImage2D>> visibility(2);
        for (size_t s = 0; s < 2; ++s) {
            render_frame(*systems[s], scenes[s], f);
            for (uint32_t slot = 1; slot <= 2; ++slot) visibility[s].push_back(read_visibility(*systems[s], slot));
        }
        for (size_t light = 0; light < 2; ++light) {
            ASSERT_EQ(visibility[1][light].values, visibility[0][light].values) << "light " << light << ", frame " << f;
            shadowed +=
                static_cast<size_t>(std::count_if(visibility[0][light].values.begin(),
                                                  visibility[0][light].values.end(), [](float v) { return v < 0.5f; }));
        }
    }
    EXPECT_GT(shadowed, size_t{1000}) << "the lights' shadows fall on the ground";
}

// The layered strategy's FrameInfo reports what the GPU culled in the last frame known
// complete (frames in flight earlier): per cascade the draws and triangles that the
// per-cascade passes' CPU culling lists for that frame (both toroidal: a caster across the
// layer's wrap lines is drawn, and counted, once in each tile it reaches), per spot or
// point light the sum over its layers; 0 for the first frames.
TEST_P(LayeredStrategyTest, FrameInfoCountsWhatTheGpuCulledFramesInFlightEarlier) {
    constexpr uint32_t kInFlight = 2;
    ShadowSystem per_cascade(system_desc(strategy_settings(ShadowStrategy::PerCascade), kInFlight));
    ShadowSystem layered(system_desc(strategy_settings(ShadowStrategy::Layered), kInFlight));
    ShadowSystem* systems[] = {&per_cascade, &layered};
    std::vector<LayeredScene> scenes;
    const LightDesc lights[] = {{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                                {LightType::Spot, {0.2f, -1.0f, 0.1f}, {-4.0f, 9.0f, 0.0f}},
                                {LightType::Point, {0.0f, -1.0f, 0.0f}, {3.5f, 6.0f, -1.0f}}};
    for (ShadowSystem* system : systems) {
        scenes.push_back(add_layered_scene(*system));
        system->set_lights(lights);
    }
    std::vector<FrameInfo> expected;  // the per-cascade passes', per frame
    uint64_t counted = 0;
    for (int f = 0; f < 7; ++f) {
        std::vector<FrameInfo> infos;
        for (size_t s = 0; s < 2; ++s) {
            change_scene(*systems[s], scenes[s], f);
            infos.push_back(systems[s]->prepare(orbit_view(f)));
            submit([&](VkCommandBuffer cmd) { systems[s]->record_shadow_maps(cmd); });
        }
        expected.push_back(infos[0]);
        const FrameInfo& actual = infos[1];
        ASSERT_EQ(actual.cascades.size(), infos[0].cascades.size());
        ASSERT_EQ(actual.local_shadows.size(), 2u);
        for (size_t c = 0; c < actual.cascades.size(); ++c) {
            const CascadeInfo* then = f >= static_cast<int>(kInFlight) ? &expected[f - kInFlight].cascades[c] : nullptr;
            EXPECT_EQ(actual.cascades[c].draws, then ? then->draws : 0u) << "frame " << f << " cascade " << c;
            EXPECT_EQ(actual.cascades[c].triangles, then ? then->triangles : 0u) << "frame " << f << " cascade " << c;
            counted += actual.cascades[c].draws;
        }
        for (size_t l = 0; l < actual.local_shadows.size(); ++l) {
            const LocalShadowInfo* then =
                f >= static_cast<int>(kInFlight) ? &expected[f - kInFlight].local_shadows[l] : nullptr;
            EXPECT_EQ(actual.local_shadows[l].draws, then ? then->draws : 0u) << "frame " << f << " light " << l;
            EXPECT_EQ(actual.local_shadows[l].triangles, then ? then->triangles : 0u) << "frame " << f;
            counted += actual.local_shadows[l].draws;
        }
    }
    EXPECT_GT(counted, 20u) << "the casters are counted";
}

// 32 point lights (192 layers) over 349,526 instances need more than the 2^26 indirect
// commands the GPU culling makes room for on any device: prepare() refuses with the numbers
// before anything is recorded; with one point light (2.1 M commands) the frame goes through.
TEST_F(LibraryTest, LayeredStrategyRefusesMoreCommandsThanItMakesRoomFor) {
    Settings settings = test_settings();
    settings.shadow.strategy = ShadowStrategy::Layered;
    settings.local_shadows.budget = kMaxLocalShadowBudget;
    settings.local_shadows.resolution = 64;
    ShadowSystem shadows(system_desc(settings));
    const MeshArrays box = box_mesh();
    const MeshId mesh = shadows.add_mesh(box.data());
    for (int i = 0; i < 349526; ++i) {
        const float x = static_cast<float>(i % 600) * 3.0f - 900.0f, z = static_cast<float>(i / 600) * 3.0f - 900.0f;
        shadows.add_instance({mesh, translation({x, 1.0f, z})});
    }
    std::vector<LightDesc> lights;
    for (uint32_t l = 0; l < kMaxLocalShadowBudget; ++l) {
        lights.push_back({LightType::Point, {0.0f, -1.0f, 0.0f}, {static_cast<float>(l) * 4.0f, 5.0f, 0.0f}});
    }
    shadows.set_lights(lights);
    try {
        shadows.prepare(orbit_view(0));
        ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("349526 casting instances in 192 layers"), std::string::npos)
            << error.what();
    }
    lights.resize(1);
    shadows.set_lights(lights);
    shadows.prepare(orbit_view(0));
    submit([&](VkCommandBuffer cmd) { shadows.record_shadow_maps(cmd); });
}

INSTANTIATE_TEST_SUITE_P(CullingOnAndOff, LayeredStrategyTest, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& param) {
                             return std::string(param.param ? "culled" : "unculled");
                         });

}  // namespace
}  // namespace penumbra::library_tests
