// Shadow filters (docs/filters.md) on lavapipe with the validation layer: every filter
// renders the default scene, and each one's defining property is measured on the
// `--aov shadow` visibility image against the scene's analytic geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/shadow_filters.hpp"
#include "filter_measurements.hpp"
#include "penumbra/scene/loader.hpp"

namespace penumbra::testing {
namespace {

renderer::FrameImages render_clean(const Scene& scene, const RenderSettings& settings) {
    const RenderedFrame frame = render_with_validation(scene, settings);
    EXPECT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
    return frame.images;
}

// --- Every filter renders the default scene, with 1 and 4 blended cascades. ---

struct DefaultSceneCase {
    ShadowFilter filter;
    int cascades;
    friend void PrintTo(const DefaultSceneCase& c, std::ostream* os) {
        PrintTo(c.filter, os);
        *os << ", " << c.cascades << " cascades";
    }
};

class FilterRendersDefaultScene : public ::testing::TestWithParam<DefaultSceneCase> {};

TEST_P(FilterRendersDefaultScene, ValidationCleanAndAgreesWithHard) {
    const Scene scene = load_scene(std::string(kDefaultSceneName));
    RenderSettings settings = small_settings(200, 112);
    settings.shadow.cascades.count = GetParam().cascades;
    settings.shadow.blend_width = 0.2f;
    const renderer::FrameImages hard = render_clean(scene, settings);
    settings.shadow.filter.mode = GetParam().filter;
    const renderer::FrameImages filtered = render_clean(scene, settings);

    // The same shadows as the hard filter, softened: about as many shadowed pixels, and few
    // pixels that flip between lit and shadowed.
    size_t hard_shadowed = 0, shadowed = 0, flipped = 0;
    for (size_t i = 0; i < filtered.visibility.size(); ++i) {
        const float hard_visibility = hard.visibility[i] / 65535.0f;
        const float visibility = filtered.visibility[i] / 65535.0f;
        hard_shadowed += hard_visibility < 0.5f;
        shadowed += visibility < 0.5f;
        flipped += std::abs(visibility - hard_visibility) > 0.5f;
    }
    const double pixels = static_cast<double>(filtered.visibility.size());
    std::printf("%s: %.2f%% shadowed (hard %.2f%%), %.2f%% differ from hard by > 0.5\n",
                ::testing::UnitTest::GetInstance()->current_test_info()->name(), 100.0 * shadowed / pixels,
                100.0 * hard_shadowed / pixels, 100.0 * flipped / pixels);
    EXPECT_GT(hard_shadowed / pixels, 0.003) << "the default scene should show shadows";
    EXPECT_GT(shadowed, hard_shadowed / 2);
    EXPECT_LT(shadowed, hard_shadowed * 3 / 2);
    EXPECT_LT(flipped / pixels, 0.005) << "the filtered shadows should match the hard ones away from edges";
}

std::vector<DefaultSceneCase> default_scene_cases() {
    std::vector<DefaultSceneCase> cases;
    for (const auto& [name, filter] : shadow_filter_names()) {
        for (const int cascades : {1, 4}) cases.push_back({filter, cascades});
    }
    return cases;
}

std::string case_name(const ::testing::TestParamInfo<DefaultSceneCase>& info) {
    for (const auto& [name, filter] : shadow_filter_names()) {
        if (filter == info.param.filter) return name + "_" + std::to_string(info.param.cascades) + "_cascades";
    }
    return "unknown";
}

INSTANTIATE_TEST_SUITE_P(AllFilters, FilterRendersDefaultScene, ::testing::ValuesIn(default_scene_cases()), case_name);

// --- hard is sharp; pcf widens the edge monotonically with its radius. ---

// A 3 x 3 m box 2 m above the ground, the sun straight overhead: the shadow's edge is the
// box's outline, |x| = 1.5 or |z| = 1.5.
constexpr char kFloatingBoxScene[] = R"(
[camera]
eye = [0.0, 6.0, 3.0]
target = [0.0, 0.0, 0.0]
fov = 60.0
near = 0.1
far = 12.0

[[lights]]
type = "directional"
direction = [0.0, -1.0, 0.0]

[[objects]]
type = "plane"
size = [16.0, 16.0]

[[objects]]
type = "box"
size = [3.0, 0.3, 3.0]
translation = [0.0, 2.0, 0.0]
)";

// The lit-to-shadow transition width across the floating box's shadow edge, in texels.
float floating_box_edge_texels(ShadowFilter filter, int pcf_radius) {
    const Scene scene = scene_from_toml(kFloatingBoxScene);
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.cascades.count = 1;
    settings.shadow.cascades.resolution = 512;
    settings.shadow.filter.mode = filter;
    settings.shadow.filter.pcf_radius = pcf_radius;
    const RenderedFrame frame = render_with_validation(scene, settings);
    EXPECT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
    const float texel = frame.info.cascades[0].texel_world_size;
    const Aabb box{{-1.5f, 1.85f, -1.5f}, {1.5f, 2.15f, 1.5f}};
    const auto samples = ground_samples(scene, frame.images, 8.0f, {box});
    // Signed distance to the outline, in texels, away from the corners (where two edges meet).
    const auto distance = [texel](glm::vec2 p) -> std::optional<float> {
        const glm::vec2 outside = glm::abs(p) - glm::vec2(1.5f);
        if (outside.x > -0.3f && outside.y > -0.3f) return std::nullopt;
        return std::max(outside.x, outside.y) / texel;
    };
    const Profile profile = visibility_profile(samples, distance, -16.0f, 16.0f, 0.25f);
    const std::optional<float> width = transition_width(profile);
    EXPECT_TRUE(width.has_value()) << "no complete lit-to-shadow transition found";
    return width.value_or(1e9f);
}

TEST(ShadowFilters, HardEdgeSpansAtMostTwoTexels) {
    const float width = floating_box_edge_texels(ShadowFilter::Hard, 0);
    std::printf("hard: edge transition %.2f texels\n", width);
    EXPECT_LE(width, 2.0f);
}

TEST(ShadowFilters, PcfWidensTheEdgeMonotonicallyWithItsRadius) {
    float previous = floating_box_edge_texels(ShadowFilter::Hard, 0);
    for (int radius = 0; radius <= 5; ++radius) {
        const float width = floating_box_edge_texels(ShadowFilter::Pcf, radius);
        std::printf("pcf radius %d: edge transition %.2f texels\n", radius, width);
        if (radius > 0) {
            EXPECT_GT(width, previous + 1.0f) << "radius " << radius;
        }
        EXPECT_LE(width, 2.0f * radius + 2.0f) << "radius " << radius;
        previous = width;
    }
}

// --- pcss hardens at contact; a larger sun softens more. ---

// A 0.3 x 4 x 0.3 m pole on the ground; the sun travels along +x and down (1, -1.5, 0), so
// the pole's shadow runs along +x from x = 0.15 to 2.82 m between z = -0.15 and 0.15, and
// a point of it at x lies (x - 0.15) * 1.8 m from the pole along the light.
std::string pole_scene(float angular_diameter) {
    char text[1024];
    std::snprintf(text, sizeof(text), R"(
[camera]
eye = [1.5, 4.0, 2.5]
target = [1.5, 0.0, 0.0]
fov = 40.0
near = 0.1
far = 10.0

[[lights]]
type = "directional"
direction = [1.0, -1.5, 0.0]
angular_diameter = %f

[[objects]]
type = "plane"
size = [12.0, 12.0]

[[objects]]
type = "box"
size = [0.3, 4.0, 0.3]
translation = [0.0, 2.0, 0.0]
)",
                  angular_diameter);
    return text;
}

struct PolePenumbra {
    float base = 0.0f;  // penumbra width (m) 0.3 .. 0.6 m from the pole's base
    float tip = 0.0f;   // ... and 2.35 .. 2.65 m, near the shadow of its tip
};

PolePenumbra measure_pole_penumbra(float angular_diameter, ShadowFilter filter = ShadowFilter::Pcss,
                                   uint32_t resolution = 2048) {
    const Scene scene = scene_from_toml(pole_scene(angular_diameter));
    RenderSettings settings = small_settings(400, 300);
    settings.shadow.cascades.count = 1;
    settings.shadow.cascades.resolution = resolution;
    settings.shadow.filter.mode = filter;
    settings.shadow.filter.pcss_quality = PcssQuality::High;
    settings.shadow.filter.pcss_blocker_taps = 32;
    settings.shadow.filter.pcss_max_penumbra = 64.0f;
    const renderer::FrameImages images = render_clean(scene, settings);
    const Aabb pole{{-0.15f, 0.0f, -0.15f}, {0.15f, 4.0f, 0.15f}};
    const auto samples = ground_samples(scene, images, 6.0f, {pole});
    // Distance outside the shadow's long edges |z| = 0.15, in a slice of x.
    const auto penumbra_in = [&](float x_min, float x_max) {
        const auto distance = [=](glm::vec2 p) -> std::optional<float> {
            if (p.x < x_min || p.x > x_max) return std::nullopt;
            return std::abs(p.y) - 0.15f;
        };
        // Both edges fold onto one profile, so the partial width is one edge's penumbra.
        return partial_width(visibility_profile(samples, distance, -0.15f, 0.4f, 0.005f));
    };
    return {penumbra_in(0.45f, 0.75f), penumbra_in(2.35f, 2.65f)};
}

TEST(ShadowFilters, PcssHardensAtContactAndSoftensWithTheSunsSize) {
    const PolePenumbra sun = measure_pole_penumbra(0.53f);
    const PolePenumbra large = measure_pole_penumbra(3.0f);
    std::printf("pcss 0.53 deg: penumbra %.3f m near the base, %.3f m near the tip\n", sun.base, sun.tip);
    std::printf("pcss 3 deg: penumbra %.3f m near the base, %.3f m near the tip\n", large.base, large.tip);
    EXPECT_GT(sun.tip, 2.0f * sun.base) << "the penumbra should widen away from the contact";
    EXPECT_GT(large.tip, 2.0f * large.base);
    EXPECT_GT(large.tip, 3.0f * sun.tip) << "a larger sun should give a wider penumbra";
    // Physically, a sun disk of diameter theta blurs the edge over (distance along the
    // light) * 2 tan(theta / 2): 0.21-0.24 m at the tip slice for 3 degrees, of which the
    // 5-95 % part is about 0.74, 0.16 m. The estimate must be of that order.
    const float tip_distance = (2.5f - 0.15f) * std::sqrt(1.0f + 1.0f / 2.25f);
    const float expected = 0.74f * tip_distance * 2.0f * std::tan(glm::radians(1.5f));
    EXPECT_GT(large.tip, 0.5f * expected);
    EXPECT_LT(large.tip, 1.5f * expected);
}

// Near the pole's base the sun's penumbra is 5-10 mm wide (0.54-1.08 m along the light
// times 0.53 degrees), under one texel at 512 and 1024 texels (about 22 and 11 mm on the
// ground). Every comparison tap is a bilinear ramp one texel wide, which is the hard
// filter's edge; PCSS narrows that ramp to the light's footprint (issue 16: sub-texel
// penumbrae rendered a texel wide). Near the tip's shadow (4-4.5 m along the light) the
// footprint is wider than a texel at 512 and PCSS is wider than hard.
TEST(ShadowFilters, PcssSubTexelPenumbraIsNarrowerThanTheBilinearComparison) {
    for (const uint32_t resolution : {512u, 1024u}) {
        const PolePenumbra hard = measure_pole_penumbra(0.53f, ShadowFilter::Hard, resolution);
        const PolePenumbra pcss = measure_pole_penumbra(0.53f, ShadowFilter::Pcss, resolution);
        std::printf("%u texels: hard %.4f / %.4f m, pcss %.4f / %.4f m (base / tip)\n", resolution, hard.base, hard.tip,
                    pcss.base, pcss.tip);
        EXPECT_LT(pcss.base, 0.75f * hard.base) << resolution << " texels";
        // The 5-95 % part of a 10 mm disk's edge, plus one 5 mm bin of the profile.
        EXPECT_LE(pcss.base, 0.0125f) << resolution << " texels";
    }
    const PolePenumbra hard = measure_pole_penumbra(0.53f, ShadowFilter::Hard, 512);
    const PolePenumbra pcss = measure_pole_penumbra(0.53f, ShadowFilter::Pcss, 512);
    EXPECT_GT(pcss.tip, hard.tip) << "wider than a texel, the light's footprint is PCSS's width";
}

// --- vsm bleeds light in the classic setup; evsm and msm much less. ---

// A 0.8 m square 4.5 m up above a 4 m table 0.8 m up, the sun straight overhead; the
// camera stands under the table looking down, so everything it sees is in the table's
// umbra (truth: visibility 0). The small square's shadow edge inside that umbra is where
// Chebyshev's bound leaks: the filter region mixes two occluder depths, and the variance
// makes the far receiver look partly lit (Donnelly & Lauritzen 2006, section 5).
constexpr char kBleedingScene[] = R"(
[camera]
eye = [0.0, 0.5, 0.0]
target = [0.0, 0.0, 0.001]
up = [0.0, 0.0, -1.0]
fov = 90.0
near = 0.05
far = 3.0

[[lights]]
type = "directional"
direction = [0.0, -1.0, 0.0]

[[objects]]
type = "plane"
size = [12.0, 12.0]

[[objects]]
type = "box"
size = [4.0, 0.2, 4.0]
translation = [0.0, 0.8, 0.0]

[[objects]]
type = "box"
size = [0.8, 0.2, 0.8]
translation = [0.0, 4.5, 0.0]
)";

struct Bleeding {
    float max = 0.0f;   // the largest visibility in the table's umbra
    float mean = 0.0f;  // its mean
};

Bleeding measure_bleeding(ShadowFilter filter) {
    const Scene scene = scene_from_toml(kBleedingScene);
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.cascades.count = 1;
    settings.shadow.filter.mode = filter;
    settings.shadow.filter.blur_radius = 4;
    settings.shadow.filter.light_bleeding_reduction = 0.0f;  // the raw bound of each technique
    const renderer::FrameImages images = render_clean(scene, settings);
    Bleeding bleeding;
    double sum = 0.0;
    for (const uint16_t value : images.visibility) {
        const float visibility = value / 65535.0f;
        bleeding.max = std::max(bleeding.max, visibility);
        sum += visibility;
    }
    bleeding.mean = static_cast<float>(sum / static_cast<double>(images.visibility.size()));
    return bleeding;
}

TEST(ShadowFilters, EvsmAndMsmBleedLessThanVsm) {
    const Bleeding vsm = measure_bleeding(ShadowFilter::Vsm);
    const Bleeding evsm = measure_bleeding(ShadowFilter::Evsm);
    const Bleeding msm = measure_bleeding(ShadowFilter::Msm);
    std::printf("light bleeding in the umbra (max / mean): vsm %.3f / %.4f, evsm %.3f / %.4f, msm %.3f / %.4f\n",
                vsm.max, vsm.mean, evsm.max, evsm.mean, msm.max, msm.mean);
    EXPECT_GT(vsm.max, 0.15f) << "the classic setup should make VSM bleed";
    EXPECT_LT(evsm.max, 0.5f * vsm.max);
    EXPECT_LT(msm.max, 0.5f * vsm.max);
    EXPECT_LT(evsm.mean, 0.5f * vsm.mean);
    EXPECT_LT(msm.mean, 0.5f * vsm.mean);
}

// --- Receiver-plane bias: no acne on a steep receiver, contact shadows stay attached. ---

// A 1 m cube on the ground under a low sun (elevation 20 degrees): in light space the
// ground is a steep slope (tan 70 = 2.7 depth per lateral metre). Depth and normal-offset
// biases are off, so only the receiver-plane bias stands between the ground and acne.
constexpr char kLowSunScene[] = R"(
[camera]
eye = [5.0, 4.0, 3.0]
target = [1.0, 0.0, 0.0]
fov = 50.0
near = 0.1
far = 14.0

[[lights]]
type = "directional"
direction = [0.94, -0.342, 0.0]

[[objects]]
type = "plane"
size = [16.0, 16.0]

[[objects]]
type = "box"
size = [1.0, 1.0, 1.0]
translation = [0.0, 0.5, 0.0]
)";

struct AcneAndContact {
    double lit_exact = 0.0;       // lit ground (away from the edge) with visibility >= 0.99
    double contact_shadow = 0.0;  // shadowed ground next to the cube's base with visibility <= 0.02
};

AcneAndContact measure_acne_and_contact(ShadowFilter filter, bool receiver_plane_bias) {
    const Scene scene = scene_from_toml(kLowSunScene);
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.cascades.count = 1;
    settings.shadow.bias = {0.0f, 0.0f, 0.0f, 0.0f};
    settings.shadow.filter.mode = filter;
    settings.shadow.filter.receiver_plane_bias = receiver_plane_bias;
    const RenderedFrame frame = render_with_validation(scene, settings);
    EXPECT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();

    const Aabb cube{{-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}};
    const glm::vec3 light = glm::normalize(glm::vec3(0.94f, -0.342f, 0.0f));
    const auto polygon = shadow_polygon(cube, light);
    // The edge band: 3 texels, stretched by 1 / sin(elevation) on the ground.
    const float band = 3.0f * frame.info.cascades[0].texel_world_size / std::abs(light.y);
    size_t lit = 0, lit_exact = 0, contact = 0, contact_dark = 0;
    for (const GroundSample& sample : ground_samples(scene, frame.images, 8.0f, {cube})) {
        const float edge_distance = distance_to_polygon_edge(polygon, sample.xz);
        if (edge_distance < band) continue;
        if (!inside_convex_polygon(polygon, sample.xz)) {
            ++lit;
            lit_exact += sample.visibility >= 0.99f;
            continue;
        }
        // Within 0.5 m of the cube's base, on the shadow side.
        const glm::vec2 outside = glm::abs(sample.xz) - glm::vec2(0.5f);
        const float base_distance = glm::length(glm::max(outside, glm::vec2(0.0f)));
        if (base_distance > 0.5f) continue;
        ++contact;
        contact_dark += sample.visibility <= 0.02f;
    }
    EXPECT_GT(lit, 10000u);
    EXPECT_GT(contact, 200u);
    return {static_cast<double>(lit_exact) / std::max<size_t>(lit, 1),
            static_cast<double>(contact_dark) / std::max<size_t>(contact, 1)};
}

TEST(ShadowFilters, ReceiverPlaneBiasRemovesAcneWithoutDetachingContactShadows) {
    for (const ShadowFilter filter : {ShadowFilter::Pcf, ShadowFilter::Poisson, ShadowFilter::Pcss}) {
        const AcneAndContact without = measure_acne_and_contact(filter, false);
        const AcneAndContact with = measure_acne_and_contact(filter, true);
        std::printf("filter %d: lit ground exact %.4f without / %.4f with receiver-plane bias; contact shadow %.4f\n",
                    static_cast<int>(filter), without.lit_exact, with.lit_exact, with.contact_shadow);
        EXPECT_LT(without.lit_exact, 0.5) << "without any bias the steep receiver should show acne";
        EXPECT_GE(with.lit_exact, 0.99) << "receiver-plane bias should remove the acne";
        EXPECT_GE(with.contact_shadow, 0.99) << "the shadow next to the cube's base should stay attached";
    }
}

}  // namespace
}  // namespace penumbra::testing
