// Settings change in a live ShadowSystem (update_settings): every class of change keeps the
// caller's meshes, instances and lights, says what it rebuilt and whether the caller's
// pipelines need the new specialization, and the frames after it are the frames a system
// created with the new settings renders.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

struct SettingsChangeCase {
    std::string name;
    std::function<void(Settings&)> change;
    SettingEffect effect;
    bool specialization_changed;
};

const glm::vec3 kSpotPosition{-4.0f, 6.0f, 3.0f};

// The ground, the box, the sun and a spot light whose map the box shadows too; the box.
InstanceId add_scene_with_spot(ShadowSystem& shadows, const MeshArrays& box, const MeshArrays& ground) {
    const InstanceId moved = add_scene(shadows, box, ground);
    LightDesc spot;
    spot.type = LightType::Spot;
    spot.position = {kSpotPosition.x, kSpotPosition.y, kSpotPosition.z};
    spot.direction = {4.0f, -6.0f, -3.0f};
    spot.outer_angle_degrees = 40.0f;
    spot.inner_angle_degrees = 30.0f;
    const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    const LightDesc lights[] = {sun, spot};
    shadows.set_lights(lights);
    return moved;
}

float largest_difference(const VisibilityImage2D& a, const VisibilityImage2D& b) {
    float largest = 0.0f;
    for (size_t i = 0; i < a.values.size() && i < b.values.size(); ++i) {
        largest = std::max(largest, std::abs(a.values[i] - b.values[i]));
    }
    return a.values.size() == b.values.size() ? largest : 1.0f;
}

class SettingsChanges : public LibraryTest {
protected:
    // The pattern held still: the two systems count different frames.
    static ViewDesc still_view() {
        ViewDesc view = top_down_view();
        view.sampling_frame = 0;
        return view;
    }

    // The sun's and the spot's visibility of one frame.
    std::vector<VisibilityImage2D> render_both(ShadowSystem& shadows) {
        std::vector<VisibilityImage2D> images{render_visibility_from(shadows, still_view(), 0)};
        images.push_back(read_visibility(shadows, 1));
        return images;
    }
};

TEST_F(SettingsChanges, EachClassKeepsTheSceneAndRendersWhatANewSystemRenders) {
    const std::vector<SettingsChangeCase> cases = {
        {"slope_bias", [](Settings& s) { s.shadow.bias.slope = 3.0f; }, SettingEffect::Live, false},
        {"pcf_radius", [](Settings& s) { s.shadow.filter.pcf_radius = 2; }, SettingEffect::Live, false},
        {"receiver_plane_bias", [](Settings& s) { s.shadow.filter.receiver_plane_bias = false; },
         SettingEffect::Pipeline, true},
        {"filter pcss", [](Settings& s) { s.shadow.filter.mode = ShadowFilter::Pcss; }, SettingEffect::Resource, true},
        {"filter evsm", [](Settings& s) { s.shadow.filter.mode = ShadowFilter::Evsm; }, SettingEffect::Resource, true},
        {"shadow_resolution", [](Settings& s) { s.shadow.cascades.resolution = 512; }, SettingEffect::Resource, false},
        {"local_shadow_resolution", [](Settings& s) { s.local_shadows.resolution = 256; }, SettingEffect::Resource,
         false},
        {"strategy layered", [](Settings& s) { s.shadow.strategy = ShadowStrategy::Layered; }, SettingEffect::Resource,
         false},
        {"shadow_technique virtual",
         [](Settings& s) {
             s.shadow.technique = ShadowTechnique::Virtual;
             s.shadow.virtual_maps.pool_mib = 16;
         },
         SettingEffect::Resource, false},
    };
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    Settings base = test_settings();
    base.shadow.cascades.resolution = 1024;  // quick on lavapipe
    for (const SettingsChangeCase& c : cases) {
        SCOPED_TRACE(c.name);
        ShadowSystem live(system_desc(base));
        const InstanceId box_instance = add_scene_with_spot(live, box, ground);
        render_both(live);  // a frame with the old settings
        Settings next = base;
        c.change(next);
        const SettingsChange change = live.update_settings(next);
        EXPECT_EQ(change.effect, c.effect);
        EXPECT_EQ(change.shader_specialization_changed, c.specialization_changed);
        // The instance is still the caller's to move: the scene was kept, not registered again.
        const glm::vec3 moved = kBoxCentre + glm::vec3(1.5f, 0.0f, -1.0f);
        live.set_instance_transform(box_instance, translation(moved));
        const std::vector<VisibilityImage2D> changed = render_both(live);

        ShadowSystem fresh(system_desc(next));
        fresh.set_instance_transform(add_scene_with_spot(fresh, box, ground), translation(moved));
        const std::vector<VisibilityImage2D> expected = render_both(fresh);
        EXPECT_LE(largest_difference(changed[0], expected[0]), 1.0f / 255.0f) << "the sun's visibility";
        EXPECT_LE(largest_difference(changed[1], expected[1]), 1.0f / 255.0f) << "the spot's visibility";
        EXPECT_EQ(live.memory().shadow_maps(), fresh.memory().shadow_maps());
        // And the box's shadow did move there (the comparison is not of two empty images).
        const FootprintCheck footprint = check_footprint(changed[0], moved, kSunDirection, 0.3f);
        EXPECT_GT(footprint.shadowed, 500u);
        EXPECT_GE(footprint.iou, 0.9);
    }
}

// Changes before a prepare() combine; the frame already prepared records with the settings
// it was prepared with, and the next one with the last ones.
TEST_F(SettingsChanges, TakeEffectAtTheNextPrepare) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    ShadowSystem shadows(system_desc());
    add_scene_with_spot(shadows, box, ground);
    shadows.prepare(still_view());
    Settings pcss = test_settings();
    pcss.shadow.filter.mode = ShadowFilter::Pcss;
    EXPECT_EQ(shadows.update_settings(pcss).effect, SettingEffect::Resource);
    Settings back = test_settings();
    back.shadow.bias.slope = 2.5f;
    // Against the settings last given (pcss), not the ones in use.
    const SettingsChange change = shadows.update_settings(back);
    EXPECT_EQ(change.effect, SettingEffect::Resource);
    EXPECT_TRUE(change.shader_specialization_changed);
    EXPECT_EQ(shadows.settings().shadow.bias.slope, 2.5f);
    // The prepared frame records with the old settings' maps (validation would name a
    // mismatch between its plan and the maps).
    submit([&](VkCommandBuffer cmd) {
        const ScreenInputs screen =
            record_ground_depth(cmd, still_view(), nullptr, NormalEncoding::SignedFloat, nullptr);
        shadows.record_shadow_maps(cmd);
        shadows.record_visibility(cmd, screen);
    });
    const std::vector<VisibilityImage2D> after = render_both(shadows);

    ShadowSystem fresh(system_desc(back));
    add_scene_with_spot(fresh, box, ground);
    const std::vector<VisibilityImage2D> expected = render_both(fresh);
    EXPECT_LE(largest_difference(after[0], expected[0]), 1.0f / 255.0f);
    EXPECT_LE(largest_difference(after[1], expected[1]), 1.0f / 255.0f);
}

}  // namespace
}  // namespace penumbra::library_tests
