// Screen-space contact shadows (Settings::contact) through the public API: a thin slab
// hovering a few millimetres over the ground under a low sun, seen from 0.6 m above. The
// cascade's texels and its normal offset lose the slab's shadow entirely; the trace through
// the depth buffer finds it. The depth buffer is the scene's analytic depth, written by the
// test, so every pixel's answer is known: in the shadow, out of it, and on the open ground
// (no contact shadow where nothing is near).
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// The slab: 10 x 10 cm, from 4 to 10 mm above the ground, centred on the origin.
constexpr glm::vec3 kSlabMin{-0.05f, 0.004f, -0.05f};
constexpr glm::vec3 kSlabMax{0.05f, 0.010f, 0.05f};
// A low sun along +X: the slab's shadow falls 13 to 33 mm toward -X of it.
const glm::vec3 kLowSun = glm::normalize(glm::vec3(-1.0f, -0.3f, 0.0f));

ViewDesc close_view() {
    return look_at_view({0.0f, 0.6f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, glm::radians(60.0f), 0.05f, 50.0f,
                        160, 160);
}

// The ray parameter where `origin + t * direction` enters the box, if it does for t > 0.
std::optional<float> enter_box(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& low,
                               const glm::vec3& high) {
    float near = 0.0f, far = 1e30f;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(direction[axis]) < 1e-12f) {
            if (origin[axis] < low[axis] || origin[axis] > high[axis]) return std::nullopt;
            continue;
        }
        float a = (low[axis] - origin[axis]) / direction[axis];
        float b = (high[axis] - origin[axis]) / direction[axis];
        if (a > b) std::swap(a, b);
        near = std::max(near, a);
        far = std::min(far, b);
    }
    if (near > far) return std::nullopt;
    return near;
}

// What each pixel of close_view() sees: the slab or the ground.
struct PixelHit {
    glm::vec3 point;
    bool on_ground = false;
};

class ContactShadowTest : public LibraryTest {
protected:
    void SetUp() override {
        LibraryTest::SetUp();
        const ViewDesc view = close_view();
        const glm::mat4 view_projection = to_glm(reverse_z_projection(view)) * to_glm(view.view);
        const glm::mat4 inverse = glm::inverse(view_projection);
        for (uint32_t y = 0; y < kScreen; ++y) {
            for (uint32_t x = 0; x < kScreen; ++x) {
                const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / float(kScreen) * 2.0f - 1.0f;
                const glm::vec4 a = inverse * glm::vec4(ndc, 1.0f, 1.0f);  // the near plane (reverse Z)
                const glm::vec4 b = inverse * glm::vec4(ndc, 0.5f, 1.0f);
                const glm::vec3 origin = glm::vec3(a) / a.w;
                const glm::vec3 direction = glm::normalize(glm::vec3(b) / b.w - origin);
                const std::optional<float> slab = enter_box(origin, direction, kSlabMin, kSlabMax);
                const float ground = -origin.y / direction.y;
                PixelHit hit{origin + direction * (slab ? *slab : ground), !slab.has_value()};
                const glm::vec4 clip = view_projection * glm::vec4(hit.point, 1.0f);
                depths_.push_back(clip.z / clip.w);
                hits_.push_back(hit);
            }
        }
    }

    // Whether the sun's ray from ground point `p` meets the slab.
    static bool slab_shadows(const glm::vec3& p) { return enter_box(p, -kLowSun, kSlabMin, kSlabMax).has_value(); }

    // A ground pixel whose neighbourhood (3 mm each way) has its answer: judged.
    static std::optional<bool> judged_shadow(const PixelHit& hit) {
        if (!hit.on_ground) return std::nullopt;
        const bool here = slab_shadows(hit.point);
        for (const glm::vec3 step :
             {glm::vec3(0.003f, 0, 0), glm::vec3(-0.003f, 0, 0), glm::vec3(0, 0, 0.003f), glm::vec3(0, 0, -0.003f)}) {
            if (slab_shadows(hit.point + step) != here) return std::nullopt;
        }
        return here;
    }

    Settings contact_settings(bool enabled) const {
        Settings settings = test_settings();
        // One cascade over 50 m: texels of some 14 cm whose normal offset lifts every
        // receiver above the slab, as a kilometre-scale shadow distance would.
        settings.shadow.cascades.count = 1;
        settings.shadow.cascades.resolution = 512;
        settings.shadow.cascades.max_distance = 50.0f;
        settings.contact.enabled = enabled;
        settings.contact.length = 0.05f;  // 3 mm steps: the slab is 6 mm thick
        settings.contact.steps = 16;
        settings.contact.thickness = 0.05f;
        settings.contact.bias = 0.001f;
        return settings;
    }

    void add_slab_scene(ShadowSystem& shadows) {
        ground_id_ = shadows.add_mesh(ground_.data());
        box_id_ = shadows.add_mesh(box_.data());
        shadows.add_instance({ground_id_, Mat4{}});
        const glm::vec3 centre = (kSlabMin + kSlabMax) * 0.5f;
        const glm::vec3 half = (kSlabMax - kSlabMin) * 0.5f;  // the box mesh is 2 m: scale by the half sizes
        const glm::mat4 world = glm::translate(glm::mat4(1.0f), centre) * glm::scale(glm::mat4(1.0f), half);
        shadows.add_instance({box_id_, to_mat4(world)});
        const LightDesc sun{LightType::Directional, {kLowSun.x, kLowSun.y, kLowSun.z}};
        shadows.set_lights({&sun, 1});
    }

    VisibilityImage2D render(ShadowSystem& shadows) { return render(shadows, close_view(), depths_); }

    VisibilityImage2D render(ShadowSystem& shadows, const ViewDesc& view, const std::vector<float>& depths) {
        shadows.prepare(view);
        HostBuffer staging(device_, VkDeviceSize{kScreen} * kScreen * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        submit([&](VkCommandBuffer cmd) {
            const ScreenInputs screen = record_depth_image(cmd, view, depths, staging);
            shadows.record_shadow_maps(cmd);
            shadows.record_visibility(cmd, screen);
        });
        return read_visibility(shadows, 0);
    }

    std::vector<float> depths_;
    std::vector<PixelHit> hits_;
    MeshArrays ground_ = ground_mesh();
    MeshArrays box_ = box_mesh();
    MeshId ground_id_, box_id_;
};

struct Tally {
    size_t shadow_pixels = 0, shadow_found = 0;  // judged pixels in the slab's shadow, and those < 0.5
    size_t lit_pixels = 0, lit_darkened = 0;     // judged pixels out of it, and those < 1
};

Tally tally(const VisibilityImage2D& image, const std::vector<PixelHit>& hits,
            std::optional<bool> (*judge)(const PixelHit&)) {
    Tally t;
    for (size_t i = 0; i < hits.size(); ++i) {
        const std::optional<bool> shadowed = judge(hits[i]);
        if (!shadowed) continue;
        if (*shadowed) {
            ++t.shadow_pixels;
            t.shadow_found += image.values[i] < 0.5f ? 1 : 0;
        } else {
            ++t.lit_pixels;
            t.lit_darkened += image.values[i] < 1.0f ? 1 : 0;
        }
    }
    return t;
}

TEST_F(ContactShadowTest, FindTheShadowTheCascadeLosesAndNoOther) {
    ShadowSystem shadows(system_desc(contact_settings(false)));
    add_slab_scene(shadows);
    const VisibilityImage2D without = render(shadows);
    const Tally off = tally(without, hits_, judged_shadow);
    ASSERT_GT(off.shadow_pixels, 100u) << "the slab's shadow is in view";
    // The cascade loses it: its texels and normal offset are far larger than the gap.
    EXPECT_LT(off.shadow_found, off.shadow_pixels / 10) << "of " << off.shadow_pixels;

    // A live change: the same system, no new one.
    ASSERT_EQ(shadows.update_settings(contact_settings(true)).effect, SettingEffect::Live);
    const VisibilityImage2D with = render(shadows);
    const Tally on = tally(with, hits_, judged_shadow);
    EXPECT_GE(on.shadow_found, on.shadow_pixels * 9 / 10) << "of " << on.shadow_pixels;
    // The open ground and the slab's lit surroundings shadow nothing of themselves, and the
    // contact term only darkens.
    EXPECT_GT(on.lit_pixels, 10000u);
    size_t brighter = 0, darkened_lit = 0;
    for (size_t i = 0; i < with.values.size(); ++i) {
        brighter += with.values[i] > without.values[i] ? 1 : 0;
        const std::optional<bool> shadowed = judged_shadow(hits_[i]);
        darkened_lit += shadowed && !*shadowed && with.values[i] < without.values[i] ? 1 : 0;
    }
    EXPECT_EQ(brighter, 0u);
    EXPECT_EQ(darkened_lit, 0u) << "of " << on.lit_pixels << " lit pixels";
}

// A ball of 1 m radius seen from 10 m (some 50 pixels across), lit from the side by the low
// sun, at the default contact settings: the trace finds nothing of the ball it starts from
// wherever N.L > 0.2. Nearer the terminator a few pixels darken (11 of 776 with N.L > 0):
// their rays run so close over the ball that samples pass behind its own silhouette, where a
// depth buffer cannot tell them from an occluder: the limit of any screen-space trace.
TEST_F(ContactShadowTest, ABallShadowsNothingOfItself) {
    constexpr float kJudgedFacing = 0.2f;
    const ViewDesc view = look_at_view({0.0f, 0.5f, 10.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, glm::radians(40.0f),
                                       0.05f, 50.0f, kScreen, kScreen);
    const glm::mat4 view_projection = to_glm(reverse_z_projection(view)) * to_glm(view.view);
    const glm::mat4 inverse = glm::inverse(view_projection);
    std::vector<float> depths;
    std::vector<float> facing;  // N.L of each ball pixel, -1 elsewhere
    size_t lit_ball_pixels = 0;
    for (uint32_t y = 0; y < kScreen; ++y) {
        for (uint32_t x = 0; x < kScreen; ++x) {
            const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / float(kScreen) * 2.0f - 1.0f;
            const glm::vec4 a = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::vec4 b = inverse * glm::vec4(ndc, 0.5f, 1.0f);
            const glm::vec3 origin = glm::vec3(a) / a.w;
            const glm::vec3 direction = glm::normalize(glm::vec3(b) / b.w - origin);
            // |origin + t direction| = 1, the nearer root.
            const float half_b = glm::dot(origin, direction);
            const float discriminant = half_b * half_b - (glm::dot(origin, origin) - 1.0f);
            if (discriminant <= 0.0f) {
                depths.push_back(0.0f);  // the background (reverse-Z far)
                facing.push_back(-1.0f);
                continue;
            }
            const glm::vec3 point = origin + direction * (-half_b - std::sqrt(discriminant));
            const glm::vec4 clip = view_projection * glm::vec4(point, 1.0f);
            depths.push_back(clip.z / clip.w);
            facing.push_back(glm::dot(point, -kLowSun));  // the unit ball's normal is the point
            lit_ball_pixels += facing.back() > kJudgedFacing ? 1 : 0;
        }
    }
    Settings settings = test_settings();
    ShadowSystem shadows(system_desc(settings));
    const MeshId ground = shadows.add_mesh(ground_.data());  // far below: the map shadows nothing here
    shadows.add_instance({ground, to_mat4(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -5.0f, 0.0f)))});
    const LightDesc sun{LightType::Directional, {kLowSun.x, kLowSun.y, kLowSun.z}};
    shadows.set_lights({&sun, 1});
    const VisibilityImage2D without = render(shadows, view, depths);
    settings.contact.enabled = true;  // every other contact setting at its default
    shadows.update_settings(settings);
    const VisibilityImage2D with = render(shadows, view, depths);
    ASSERT_GT(lit_ball_pixels, 200u);
    size_t darkened = 0;
    for (size_t i = 0; i < depths.size(); ++i) {
        darkened += facing[i] > kJudgedFacing && with.values[i] < without.values[i] ? 1 : 0;
    }
    EXPECT_EQ(darkened, 0u) << "of " << lit_ball_pixels << " lit pixels of the ball";
}

TEST_F(ContactShadowTest, TheSunCanBeLeftOut) {
    Settings settings = contact_settings(true);
    settings.contact.sun = false;  // spot and point lights only
    ShadowSystem shadows(system_desc(settings));
    add_slab_scene(shadows);
    const Tally t = tally(render(shadows), hits_, judged_shadow);
    EXPECT_LT(t.shadow_found, t.shadow_pixels / 10) << "of " << t.shadow_pixels;
}

TEST_F(ContactShadowTest, BadValuesAreNamed) {
    Settings settings = contact_settings(true);
    settings.contact.steps = 2;
    try {
        validate_settings(settings, "test");
        FAIL() << "contact_steps 2 was accepted";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("contact_steps"), std::string::npos) << error.what();
    }
    settings.contact.steps = 16;
    settings.contact.thickness = -1.0f;
    EXPECT_THROW(validate_settings(settings, "test"), InputError);
}

}  // namespace
}  // namespace penumbra::library_tests
