// record_visibility() into an image the caller owns (VisibilityTarget): the caller allocates
// it once, larger than the screen and with layers for more lights than the frame has, and
// binds it in its own descriptors; the resolve must write there exactly what it writes into
// Penumbra's own image, at every screen size that fits.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

using VisibilityTargets = LibraryTest;

constexpr uint32_t kTargetWidth = 184;  // larger than the fixture's 160 x 160 screen
constexpr uint32_t kTargetHeight = 168;
constexpr uint32_t kTargetLayers = 2;  // eight slots: the sun and up to seven local lights

// The sun of add_scene() and a point light beside the box: two slots.
void add_scene_and_point_light(ShadowSystem& shadows, const MeshArrays& box, const MeshArrays& ground) {
    add_scene(shadows, box, ground);
    std::array<LightDesc, 2> lights{};
    lights[0] = LightDesc{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    lights[1] = LightDesc{LightType::Point, {0.0f, -1.0f, 0.0f}, {2.5f, 6.0f, 0.5f}};
    lights[1].range = 30.0f;
    shadows.set_lights(lights);
}

VisibilityTarget target_of(const TestImage& image) {
    VisibilityTarget target;
    target.image = image.image;
    target.view = image.view;
    target.width = kTargetWidth;
    target.height = kTargetHeight;
    target.layers = kTargetLayers;
    return target;
}

class VisibilityTargetFrames : public VisibilityTargets {
protected:
    // One frame of the top-down view over a screen of `size` pixels per side (the corner
    // of the ground depth image), into `target` or, without one, Penumbra's own image.
    std::array<VisibilityImage2D, 2> render(ShadowSystem& shadows, uint32_t size, const TestImage* target) {
        shadows.prepare(top_down_view());
        submit([&](VkCommandBuffer cmd) {
            ScreenInputs screen =
                record_ground_depth(cmd, top_down_view(), nullptr, NormalEncoding::SignedFloat, nullptr);
            screen.width = size;
            screen.height = size;
            shadows.record_page_marking(cmd, screen);
            shadows.record_shadow_maps(cmd);
            if (target) {
                shadows.record_visibility(cmd, screen, target_of(*target));
            } else {
                shadows.record_visibility(cmd, screen);
            }
        });
        return {read_visibility(shadows, 0), read_visibility(shadows, 1)};
    }
};

TEST_F(VisibilityTargetFrames, TheCallersImageHoldsWhatPenumbrasOwnHolds) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene_and_point_light(shadows, box, ground);
    const TestImage target(device_, VK_FORMAT_R8G8B8A8_UNORM, kTargetWidth, kTargetHeight,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                           VK_IMAGE_ASPECT_COLOR_BIT, kTargetLayers);

    for (const uint32_t size : {kScreen, kScreen / 2}) {
        SCOPED_TRACE("screen " + std::to_string(size));
        const auto own = render(shadows, size, nullptr);
        EXPECT_NE(shadows.visibility_image().image, target.image);
        const auto callers = render(shadows, size, &target);
        const VisibilityImage written = shadows.visibility_image();
        EXPECT_EQ(written.image, target.image);
        EXPECT_EQ(written.view, target.view);
        EXPECT_EQ(written.width, size);
        EXPECT_EQ(written.height, size);
        EXPECT_EQ(written.layers, kTargetLayers);
        EXPECT_EQ(written.slots, 2u);
        EXPECT_EQ(shadows.memory().visibility, 0u) << "Penumbra's own image is freed while the caller brings one";
        for (uint32_t slot = 0; slot < 2; ++slot) {
            ASSERT_EQ(callers[slot].values.size(), own[slot].values.size());
            EXPECT_EQ(callers[slot].values, own[slot].values) << "slot " << slot;
            // Both slots see a shadow: the comparison is not of two blank images.
            EXPECT_GT(std::count(own[slot].values.begin(), own[slot].values.end(), 0.0f), 100) << "slot " << slot;
            EXPECT_GT(std::count(own[slot].values.begin(), own[slot].values.end(), 1.0f), 100) << "slot " << slot;
        }
    }
}

TEST_F(VisibilityTargets, VisibilityImageBeforeTheFirstResolveIsAUsageError) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    EXPECT_THROW(shadows.visibility_image(), UsageError);
    shadows.prepare(top_down_view());
    submit([&](VkCommandBuffer cmd) { shadows.record_shadow_maps(cmd); });
    EXPECT_THROW(shadows.visibility_image(), UsageError) << "shadow maps alone resolve nothing";
}

// Each unfit target is one InputError naming the field, recorded nothing, and the frame
// can still resolve.
TEST_F(VisibilityTargets, UnfitTargetsAreInputErrorsNamingTheField) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    std::vector<LightDesc> lights(5, LightDesc{LightType::Spot, {0.0f, -1.0f, 0.0f}, {0.0f, 8.0f, 0.0f}});
    lights[0] = LightDesc{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    for (size_t i = 1; i < lights.size(); ++i) lights[i].position.x = static_cast<float>(i);
    shadows.set_lights(lights);
    const TestImage image(device_, VK_FORMAT_R8G8B8A8_UNORM, kTargetWidth, kTargetHeight,
                          VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                          VK_IMAGE_ASPECT_COLOR_BIT, kTargetLayers);
    ASSERT_EQ(shadows.prepare(top_down_view()).local_shadows.size(), 4u);

    const auto expect_refused = [&](const VisibilityTarget& target, const std::string& needle) {
        submit([&](VkCommandBuffer cmd) {
            const ScreenInputs screen =
                record_ground_depth(cmd, top_down_view(), nullptr, NormalEncoding::SignedFloat, nullptr);
            try {
                shadows.record_visibility(cmd, screen, target);
                ADD_FAILURE() << "no error; expected one mentioning \"" << needle << "\"";
            } catch (const InputError& error) {
                EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
            }
        });
    };
    submit([&](VkCommandBuffer cmd) { shadows.record_shadow_maps(cmd); });
    VisibilityTarget target = target_of(image);
    target.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    expect_refused(target, "VisibilityTarget::format is VK_FORMAT_R16G16B16A16_SFLOAT");
    target = target_of(image);
    target.width = kScreen - 1;
    expect_refused(target, "VisibilityTarget::width/height: 159x168 is smaller than the screen's 160x160");
    target = target_of(image);
    target.view = VK_NULL_HANDLE;
    expect_refused(target, "VisibilityTarget::view is VK_NULL_HANDLE");
    target = target_of(image);
    target.layers = 1;
    expect_refused(target,
                   "VisibilityTarget::layers: 1 hold 4 slots; this frame has 5 (the sun and 4 shadowed "
                   "local lights): 2 layers are needed");
    EXPECT_THROW(shadows.visibility_image(), UsageError);

    // Nothing was recorded: the frame resolves into the target that fits.
    submit([&](VkCommandBuffer cmd) {
        shadows.record_visibility(
            cmd, record_ground_depth(cmd, top_down_view(), nullptr, NormalEncoding::SignedFloat, nullptr),
            target_of(image));
    });
    EXPECT_EQ(shadows.visibility_image().slots, 5u);
    expect_box_shadow_of_the_sun(read_visibility(shadows, 0));
}

}  // namespace
}  // namespace penumbra::library_tests
