// The deferred resolve (`--resolve deferred`: a depth and normal pre-pass, Penumbra's
// compute resolve once per pixel, lighting over the pre-pass's depth) against forward
// shading, the reference: for every filter and every light type the visibility AOVs agree
// within one step of the resolve's 8-bit image on at least 99.9 % of the pixels with
// geometry, and the cascade AOVs are identical. The sun's virtual shadow map too, with the
// filters it takes: the forward shader's page-table reads and receiver-plane gradients
// equal the compute resolve's (forward shading differentiates the light view's coordinates,
// which no level boundary breaks, where it once dropped the gradient of every quad whose
// fwidth() of the level was not 0: on lavapipe, lines of quads inside a level, whose acne
// made pcf and poisson differ).
//
// Where they may differ: the pre-pass hands the resolve each pixel's face normal, and the
// resolve puts the neighbours it takes the receiver-plane gradients from on that plane,
// where forward shading differentiates over its 2 x 2 quad (coarse derivatives on
// lavapipe); both agree on a plane up to the perspective change across one pixel. The
// normals pass through 16-bit floats. Hence the 0.1 % allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "render_fixture.hpp"

namespace penumbra::testing {
namespace {

// A sun, a spot and a point light over a box, a sphere and a thin pole on a plane: flat and
// curved receivers and casters, contact shadows, every light's penumbra on screen.
constexpr char kScene[] = R"(
[camera]
eye = [7.0, 6.0, 9.0]
target = [0.0, 0.5, 0.0]
fov = 50.0
far = 60.0

[[lights]]
type = "directional"
direction = [0.4, -1.0, 0.5]
angular_diameter = 2.0
intensity = 3.0

[[lights]]
type = "spot"
position = [-2.0, 5.0, 1.5]
direction = [0.35, -1.0, -0.3]
inner_angle = 30.0
outer_angle = 40.0
range = 20.0
radius = 0.15
intensity = 30.0

[[lights]]
type = "point"
position = [2.5, 2.0, -1.0]
range = 12.0
radius = 0.1
intensity = 20.0

[[objects]]
type = "plane"
size = [20.0, 20.0]

[[objects]]
type = "box"
size = [1.5, 1.0, 1.0]
translation = [-0.5, 0.5, 0.0]

[[objects]]
type = "sphere"
radius = 0.7
translation = [1.5, 1.2, 1.2]

[[objects]]
type = "box"
size = [0.1, 2.5, 0.1]
translation = [0.5, 1.25, -1.5]
)";

struct ResolveCase {
    ShadowFilter filter;
    int32_t light;  // -1 the sun, else the index in the scene's [[lights]] (1 the spot, 2 the point light)
    ShadowTechnique technique = ShadowTechnique::Cascades;
};

const char* light_name(int32_t light) { return light < 0 ? "sun" : light == 1 ? "spot" : "point"; }

// gtest prints a case by its names rather than as raw bytes.
void PrintTo(const ResolveCase& c, std::ostream* os) {
    *os << choice_name(kShadowFilterChoices, c.filter) << " " << light_name(c.light) << " "
        << choice_name(kShadowTechniqueChoices, c.technique);
}

class DeferredResolve : public ::testing::TestWithParam<ResolveCase> {};

RenderedFrame render_clean(const Scene& scene, const RenderSettings& settings) {
    RenderedFrame frame = render_with_validation(scene, settings);
    EXPECT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
    return frame;
}

TEST_P(DeferredResolve, VisibilityEqualsForwardShading) {
    const Scene scene = scene_from_toml(kScene);
    RenderSettings settings = small_settings(192, 144);
    settings.shadow.filter.mode = GetParam().filter;
    settings.visibility_light = GetParam().light;
    settings.shadow.technique = GetParam().technique;
    settings.shadow.virtual_maps.pool_mib = 16;
    settings.geometry_aovs = true;  // which pixels have geometry
    settings.resolve = ShadowResolve::Forward;
    const RenderedFrame forward = render_clean(scene, settings);
    settings.resolve = ShadowResolve::Deferred;
    settings.geometry_aovs = false;
    const RenderedFrame deferred = render_clean(scene, settings);
    ASSERT_EQ(forward.images.visibility.size(), deferred.images.visibility.size());

    // One 8-bit step, plus the rounding of the forward value to 16 bits.
    const float tolerance = 1.0f / 255.0f + 1.0f / 65535.0f;
    size_t evaluated = 0, differing = 0, shadowed = 0, cascade_differs = 0;
    float largest = 0.0f;
    for (size_t i = 0; i < forward.images.visibility.size(); ++i) {
        cascade_differs += forward.images.cascade[i] != deferred.images.cascade[i];
        if (forward.images.world_position[i].w == 0.0f) continue;
        ++evaluated;
        const float expected = forward.images.visibility[i] / 65535.0f;
        const float difference = std::abs(deferred.images.visibility[i] / 65535.0f - expected);
        shadowed += expected < 0.5f;
        differing += difference > tolerance;
        largest = std::max(largest, difference);
    }
    std::printf("%zu of %zu pixels differ by more than 1/255 (largest %.3f); %zu shadowed\n", differing, evaluated,
                largest, shadowed);
    EXPECT_GT(shadowed, evaluated / 50) << "the light should shadow part of the image";
    EXPECT_LE(differing, evaluated / 1000) << "the deferred visibility should equal forward shading's";
    EXPECT_EQ(cascade_differs, 0u);
}

std::vector<ResolveCase> resolve_cases() {
    std::vector<ResolveCase> cases;
    for (const ChoiceName<ShadowFilter>& filter : kShadowFilterChoices) {
        for (const int32_t light : {-1, 1, 2}) cases.push_back({filter.value, light});
        if (!is_moment_filter(filter.value)) cases.push_back({filter.value, -1, ShadowTechnique::Virtual});
    }
    return cases;
}

std::string case_name(const ::testing::TestParamInfo<ResolveCase>& info) {
    const bool virtual_map = info.param.technique == ShadowTechnique::Virtual;
    return std::string(choice_name(kShadowFilterChoices, info.param.filter)) + "_" + light_name(info.param.light) +
           (virtual_map ? "_virtual" : "");
}

INSTANTIATE_TEST_SUITE_P(EveryFilterAndLight, DeferredResolve, ::testing::ValuesIn(resolve_cases()), case_name);

}  // namespace
}  // namespace penumbra::testing
