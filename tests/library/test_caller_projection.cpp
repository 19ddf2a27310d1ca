// The caller's projection (ViewDesc::projection): the same frustum as a field of view gives
// the same cascades and shadows in either depth convention; an infinite far plane, a TAA
// jitter and an orthographic top-down camera give the box's analytic shadow (the
// orthographic one with the virtual shadow map too, whose page levels follow the pixel
// footprint); a projection that is no camera's is an InputError naming it.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

constexpr float kNear = 0.1f;
constexpr float kFar = 100.0f;  // top_down_view()'s

// The same frustum as top_down_view() with depth 0 at the near plane and 1 at the far plane.
Mat4 forward_z_projection() {
    const float focal = 1.0f / std::tan(glm::radians(30.0f));
    glm::mat4 m(0.0f);
    m[0][0] = focal;
    m[1][1] = -focal;
    m[2][2] = kFar / (kNear - kFar);
    m[2][3] = -1.0f;
    m[3][2] = kNear * kFar / (kNear - kFar);
    return to_mat4(m);
}

// Looking straight down, the ground's square that top_down_view() sees, orthographic (Y
// flipped like Penumbra's perspective: row 0 towards -Z), reverse Z.
Mat4 orthographic_projection(float half_extent) {
    glm::mat4 m(1.0f);
    m[0][0] = 1.0f / half_extent;
    m[1][1] = -1.0f / half_extent;
    m[2][2] = 1.0f / (kFar - kNear);
    m[3][2] = kFar / (kFar - kNear);
    return to_mat4(m);
}

class CallerProjectionTest : public LibraryTest {
protected:
    // Reverse Z with no far plane: depth = near / distance.
    static Mat4 infinite_projection() {
        glm::mat4 m = to_glm(reverse_z_projection(top_down_view()));
        m[2][2] = 0.0f;
        m[3][2] = kNear;
        return to_mat4(m);
    }

    // `projection` moved by `pixels` across the kScreen-pixel image.
    static Mat4 jittered(const Mat4& projection, glm::vec2 pixels) {
        glm::mat4 shift(1.0f);
        shift[3][0] = 2.0f * pixels.x / kScreen;
        shift[3][1] = 2.0f * pixels.y / kScreen;
        return to_mat4(shift * to_glm(projection));
    }

    ViewDesc with_projection(const Mat4& projection) const {
        ViewDesc view = top_down_view();
        view.projection = projection;
        view.sampling_frame = 0;
        return view;
    }
};

// The caller's cascades are padded for a TAA jitter of up to 2 pixels: on this 160-pixel
// image that is 1.25 % of the frustum per side, which widens the far cascades by ~2.5 %.
void expect_same_cascades(const std::vector<CascadeInfo>& a, const std::vector<CascadeInfo>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t c = 0; c < a.size(); ++c) {
        EXPECT_NEAR(a[c].split_far, b[c].split_far, 1e-4f * a[c].split_far) << "cascade " << c;
        EXPECT_GE(b[c].texel_world_size, a[c].texel_world_size * 0.999f) << "cascade " << c;
        EXPECT_LE(b[c].texel_world_size, a[c].texel_world_size * 1.03f) << "cascade " << c;
    }
}

TEST_F(CallerProjectionTest, TheSameFrustumGivesTheSameCascadesInEitherDepthConvention) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    ShadowSystem own(system_desc());
    add_scene(own, box, ground);
    ViewDesc fov_view = top_down_view();
    fov_view.sampling_frame = 0;
    const VisibilityImage2D expected = render_visibility_from(own, fov_view);
    const std::vector<CascadeInfo> expected_cascades = own.prepare(fov_view).cascades;
    for (const Mat4& projection : {reverse_z_projection(top_down_view()), forward_z_projection()}) {
        ShadowSystem caller(system_desc());
        add_scene(caller, box, ground);
        const VisibilityImage2D image = render_visibility_from(caller, with_projection(projection));
        expect_same_cascades(expected_cascades, caller.prepare(with_projection(projection)).cascades);
        const FootprintCheck check = check_footprint(image, kBoxCentre, kSunDirection, 0.3f);
        EXPECT_EQ(check.wrong, 0u);
        EXPECT_GE(check.iou, 0.97);
        size_t differing = 0;
        for (size_t i = 0; i < image.values.size(); ++i)
            differing += std::abs(image.values[i] - expected.values[i]) > 0.02f;
        EXPECT_LE(differing, image.values.size() / 200) << "pixels unlike the field-of-view camera's";
    }
}

TEST_F(CallerProjectionTest, InfiniteAndOrthographicCamerasShadowTheGroundAnalytically) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    const float half_extent = kCameraHeight * std::tan(glm::radians(30.0f));
    struct Case {
        std::string name;
        Mat4 projection;
        ShadowTechnique technique;
    };
    const std::vector<Case> cases = {
        {"infinite far", infinite_projection(), ShadowTechnique::Cascades},
        {"orthographic", orthographic_projection(half_extent), ShadowTechnique::Cascades},
        {"orthographic virtual", orthographic_projection(half_extent), ShadowTechnique::Virtual},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        Settings settings = test_settings();
        settings.shadow.technique = c.technique;
        settings.shadow.virtual_maps.pool_mib = 16;
        ShadowSystem shadows(system_desc(settings));
        add_scene(shadows, box, ground);
        const FootprintCheck check = check_footprint(render_visibility_from(shadows, with_projection(c.projection)),
                                                     kBoxCentre, kSunDirection, 0.3f);
        EXPECT_GT(check.shadowed, 500u);
        EXPECT_EQ(check.wrong, 0u);
        EXPECT_GE(check.iou, 0.97);
    }
}

// A one-pixel jitter moves the image by one pixel and changes nothing else: the cascades
// stay where they are, so each pixel sees the shadow its neighbour saw.
TEST_F(CallerProjectionTest, AOnePixelJitterMovesTheImageByOnePixel) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    const Mat4 projection = reverse_z_projection(top_down_view());
    const VisibilityImage2D still = render_visibility_from(shadows, with_projection(projection));
    // +1 pixel in x and -1 in y of NDC: what pixel (x, y) saw, pixel (x + 1, y - 1) sees.
    const VisibilityImage2D moved =
        render_visibility_from(shadows, with_projection(jittered(projection, {1.0f, -1.0f})));
    float largest = 0.0f;
    size_t shadowed = 0;
    for (uint32_t y = 0; y + 1 < kScreen; ++y) {
        for (uint32_t x = 0; x + 1 < kScreen; ++x) {
            largest = std::max(largest, std::abs(moved.at(x + 1, y) - still.at(x, y + 1)));
            shadowed += still.at(x, y + 1) < 0.5f;
        }
    }
    EXPECT_GT(shadowed, 500u);
    EXPECT_LE(largest, 2.0f / 255.0f);
}

TEST_F(CallerProjectionTest, JitterLeavesTheStableCascadesWhereTheyAre) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    const Mat4 projection = reverse_z_projection(top_down_view());
    const std::vector<CascadeInfo> still = shadows.prepare(with_projection(projection)).cascades;
    for (const glm::vec2 jitter : {glm::vec2(0.5f, 0.5f), glm::vec2(-0.5f, 0.25f), glm::vec2(1.0f, -1.0f)}) {
        const std::vector<CascadeInfo> moved = shadows.prepare(with_projection(jittered(projection, jitter))).cascades;
        ASSERT_EQ(moved.size(), still.size());
        for (size_t c = 0; c < still.size(); ++c) {
            EXPECT_EQ(moved[c].view_projection.m, still[c].view_projection.m) << "cascade " << c;
        }
    }
}

TEST_F(CallerProjectionTest, AProjectionThatIsNoCamerasIsNamed) {
    ShadowSystem shadows(system_desc());
    const auto error_of = [&](const Mat4& projection) {
        try {
            shadows.prepare(with_projection(projection));
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    // The identity puts the near plane behind the eye.
    EXPECT_NE(error_of(Mat4{}).find("ViewDesc::projection: its near plane is at view distance"), std::string::npos)
        << error_of(Mat4{});
    Mat4 singular = reverse_z_projection(top_down_view());
    singular.m[0] = 0.0f;
    EXPECT_EQ(error_of(singular), "ShadowSystem::prepare: ViewDesc::projection: is not invertible");
    Mat4 nan = reverse_z_projection(top_down_view());
    nan.m[5] = std::nanf("");
    EXPECT_EQ(error_of(nan), "ShadowSystem::prepare: ViewDesc::projection: must be finite");
}

}  // namespace
}  // namespace penumbra::library_tests
