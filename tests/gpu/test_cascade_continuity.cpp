// Shadows across cascade boundaries and from alpha-masked casters.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

#include "../unit/scene_to_core.hpp"
#include "analytic_shadow.hpp"
#include "core/camera_math.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/primitives.hpp"
#include "render_fixture.hpp"

namespace penumbra::testing {
namespace {

// Pixel coordinates of a world point, or nothing when it is off-screen.
std::optional<glm::ivec2> world_to_pixel(const Camera& camera, uint32_t width, uint32_t height,
                                         const glm::vec3& point) {
    const CameraView view = make_camera_view(camera, static_cast<float>(width) / static_cast<float>(height));
    const glm::vec4 clip = view.view_projection * glm::vec4(point, 1.0f);
    if (clip.w <= 0.0f) return std::nullopt;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const glm::ivec2 pixel(static_cast<int>((ndc.x * 0.5f + 0.5f) * width),
                           static_cast<int>((ndc.y * 0.5f + 0.5f) * height));  // clip +Y is down the image
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= static_cast<int>(width) || pixel.y >= static_cast<int>(height)) {
        return std::nullopt;
    }
    return pixel;
}

constexpr const char* kLongShadowPole = R"(
[camera]
eye = [4.0, 6.0, 4.0]
target = [0.0, 0.0, -12.0]
fov = 55.0
near = 0.1
far = 100.0

[[lights]]
type = "directional"
direction = [0.0, -1.0, -2.0]

[[objects]]
type = "plane"
size = [60.0, 80.0]

[[objects]]
type = "cylinder"
radius = 0.2
height = 10.0
translation = [0.0, 5.0, -2.0]
)";

// The pole at z = -2 throws a 20 m shadow along -Z (z from -2 to -22); cascade 0 ends at a
// view distance of 12 m, in the middle of it.
TEST(CascadeContinuity, PoleShadowCrossingACascadeBoundaryHasNoGapAndNoDouble) {
    const Scene scene = scene_from_toml(kLongShadowPole);
    for (const float blend_width : {0.0f, 0.1f}) {
        RenderSettings settings = small_settings(320, 240);
        settings.shadow.cascades.count = 3;
        settings.shadow.cascades.scheme = SplitScheme::Manual;
        settings.shadow.cascades.manual_splits = {12.0f, 30.0f};
        settings.shadow.cascades.max_distance = 80.0f;
        settings.shadow.blend_width = blend_width;
        const RenderedFrame frame = render_with_validation(scene, settings);
        ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();

        std::set<int> cascades_seen;
        int samples = 0;
        for (float z = -2.5f; z > -21.5f; z -= 0.1f) {
            const auto centre = world_to_pixel(scene.camera, settings.width, settings.height, {0.0f, 0.0f, z});
            const auto beside = world_to_pixel(scene.camera, settings.width, settings.height, {0.9f, 0.0f, z});
            ASSERT_TRUE(centre && beside);
            ++samples;
            cascades_seen.insert(frame.images.cascade[centre->y * settings.width + centre->x]);
            EXPECT_LT(visibility_at(frame.images, centre->x, centre->y), 0.5f)
                << "gap in the shadow at z=" << z << " (blend " << blend_width << ")";
            EXPECT_EQ(visibility_at(frame.images, beside->x, beside->y), 1.0f)
                << "stray or doubled shadow beside the pole's shadow at z=" << z << " (blend " << blend_width << ")";
        }
        EXPECT_GT(samples, 150);
        EXPECT_GE(cascades_seen.size(), 2u) << "the shadow must cross a cascade boundary";
    }
}

// The virtual shadow map: the same shadow crosses clipmap levels (the receiver's level
// follows its distance, the "cascade" AOV is the level) and the page edges of each level
// (128 texels of 1.5 to 12 cm here), with the kernel filters that read across them.
TEST(VirtualContinuity, PoleShadowCrossingLevelsAndPagesHasNoGapAndNoDouble) {
    const Scene scene = scene_from_toml(kLongShadowPole);
    for (const ShadowFilter filter : {ShadowFilter::Pcf, ShadowFilter::Pcss}) {
        RenderSettings settings = small_settings(320, 240);
        settings.shadow.technique = ShadowTechnique::Virtual;
        settings.shadow.virtual_maps.pool_mib = 16;
        settings.shadow.cascades.max_distance = 80.0f;
        settings.shadow.filter.mode = filter;
        const RenderedFrame frame = render_with_validation(scene, settings);
        ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
        std::set<int> levels_seen;
        int samples = 0;
        for (float z = -2.5f; z > -21.5f; z -= 0.1f) {
            const auto centre = world_to_pixel(scene.camera, settings.width, settings.height, {0.0f, 0.0f, z});
            const auto beside = world_to_pixel(scene.camera, settings.width, settings.height, {0.9f, 0.0f, z});
            ASSERT_TRUE(centre && beside);
            ++samples;
            levels_seen.insert(frame.images.cascade[centre->y * settings.width + centre->x]);
            const char* name = choice_name(kShadowFilterChoices, filter);
            EXPECT_LT(visibility_at(frame.images, centre->x, centre->y), 0.5f) << name << ": gap at z=" << z;
            EXPECT_EQ(visibility_at(frame.images, beside->x, beside->y), 1.0f)
                << name << ": stray or doubled shadow beside the pole's shadow at z=" << z;
        }
        EXPECT_GT(samples, 150);
        EXPECT_GE(levels_seen.size(), 2u) << "the shadow must cross a level boundary";
    }
}

// ---- Alpha-masked casters: the Khronos AlphaBlendModeTest quads ------------------------

const std::filesystem::path kAlphaModel =
    std::filesystem::path(PENUMBRA_SHARED_ASSETS_DIR) / "AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf";

// Bilinear, repeating alpha lookup matching the renderer's texture sampler.
float sample_alpha(const Texture& texture, glm::vec2 uv) {
    const glm::vec2 position = uv * glm::vec2(texture.width, texture.height) - 0.5f;
    const glm::ivec2 base(std::floor(position.x), std::floor(position.y));
    const glm::vec2 f = position - glm::vec2(base);
    const auto texel = [&](int x, int y) {
        x = ((x % static_cast<int>(texture.width)) + texture.width) % texture.width;
        y = ((y % static_cast<int>(texture.height)) + texture.height) % texture.height;
        return texture.rgba8[(size_t{static_cast<uint32_t>(y)} * texture.width + x) * 4 + 3] / 255.0f;
    };
    const float top = glm::mix(texel(base.x, base.y), texel(base.x + 1, base.y), f.x);
    const float bottom = glm::mix(texel(base.x, base.y + 1), texel(base.x + 1, base.y + 1), f.x);
    return glm::mix(top, bottom, f.y);
}

struct MaskedHit {
    float alpha_minus_cutoff;  // > 0: opaque at this point, < 0: a hole
};

// Alpha of the first masked triangle on the ray from `origin` along `direction`.
std::optional<MaskedHit> trace_masked(const Scene& scene, const glm::vec3& origin, const glm::vec3& direction) {
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.mesh];
        const Material& material = scene.materials[mesh.material];
        if (material.alpha_mode == AlphaMode::Opaque) continue;
        const float cutoff = material.alpha_mode == AlphaMode::Blend ? 0.5f : material.alpha_cutoff;
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            const Vertex* v[3] = {&mesh.vertices[mesh.indices[i]], &mesh.vertices[mesh.indices[i + 1]],
                                  &mesh.vertices[mesh.indices[i + 2]]};
            const glm::vec3 p0 = glm::vec3(instance.world * glm::vec4(v[0]->position, 1.0f));
            const glm::vec3 e1 = glm::vec3(instance.world * glm::vec4(v[1]->position, 1.0f)) - p0;
            const glm::vec3 e2 = glm::vec3(instance.world * glm::vec4(v[2]->position, 1.0f)) - p0;
            // Moller-Trumbore.
            const glm::vec3 p = glm::cross(direction, e2);
            const float det = glm::dot(e1, p);
            if (std::abs(det) < 1e-9f) continue;
            const glm::vec3 s = origin - p0;
            const float u = glm::dot(s, p) / det;
            const glm::vec3 q = glm::cross(s, e1);
            const float w = glm::dot(direction, q) / det;
            if (u < 0.0f || w < 0.0f || u + w > 1.0f || glm::dot(e2, q) / det <= 0.0f) continue;
            const glm::vec2 uv = v[0]->uv * (1.0f - u - w) + v[1]->uv * u + v[2]->uv * w;
            float alpha = material.base_color.a;
            if (material.base_color_texture >= 0)
                alpha *= sample_alpha(scene.textures[material.base_color_texture], uv);
            return MaskedHit{alpha - cutoff};
        }
    }
    return std::nullopt;
}

// Whether the ground point is shadowed, or nothing where the answer depends on filtering:
// outside every quad's shadow, alpha within 0.15 of the cutoff, or a mask edge within
// `edge_band` metres along X or Z. The band is sampled every 2 mm (a texel of the quads'
// texture is 2 mm on the ground), so thin lines in the mask are not jumped over.
std::optional<bool> expected_shadow(const Scene& scene, const glm::vec3& point, const glm::vec3& to_light,
                                    float edge_band) {
    std::optional<bool> answer;
    const int steps = static_cast<int>(std::ceil(edge_band / 0.002f));
    for (int axis = 0; axis < 2; ++axis) {
        for (int step = -steps; step <= steps; ++step) {
            glm::vec3 offset(0.0f);
            offset[axis == 0 ? 0 : 2] = edge_band * static_cast<float>(step) / static_cast<float>(steps);
            const auto hit = trace_masked(scene, point + offset, to_light);
            if (!hit || std::abs(hit->alpha_minus_cutoff) < 0.15f) return std::nullopt;
            const bool opaque = hit->alpha_minus_cutoff > 0.0f;
            if (answer && *answer != opaque) return std::nullopt;
            answer = opaque;
        }
    }
    return answer;
}

TEST(AlphaMaskedCasters, KhronosAlphaQuadsCastShadowsWithHolesWhereAlphaIsBelowTheCutoff) {
    if (!std::filesystem::exists(kAlphaModel)) GTEST_SKIP() << "../shared/assets is absent: " << kAlphaModel;
    // The model's masked and blended quads stand in the XY plane; lay them flat 3 m above a
    // ground plane and light them along -Y/+Z so that each quad's shadow falls beside it.
    Scene model;
    append_gltf(model, kAlphaModel, {glm::mat4(1.0f)});
    Scene scene;
    scene.textures = model.textures;
    scene.materials = model.materials;
    const glm::mat4 lay_flat = glm::translate(glm::mat4(1.0f), {0.0f, 3.0f, 0.0f}) *
                               glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
    for (const Instance& instance : model.instances) {
        const Mesh& mesh = model.meshes[instance.mesh];
        if (model.materials[mesh.material].alpha_mode == AlphaMode::Opaque) continue;
        scene.meshes.push_back(mesh);
        scene.instances.push_back({static_cast<uint32_t>(scene.meshes.size() - 1), lay_flat * instance.world});
    }
    ASSERT_GE(scene.instances.size(), 4u) << "three MASK quads and a BLEND quad";
    Mesh ground = make_plane(16.0f, 16.0f);
    ground.material = static_cast<uint32_t>(scene.materials.size());
    scene.materials.emplace_back();
    scene.meshes.push_back(ground);
    scene.instances.push_back({static_cast<uint32_t>(scene.meshes.size() - 1), glm::mat4(1.0f)});
    Light sun;
    sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, 1.0f));
    scene.lights.push_back(sun);
    scene.camera.eye = {0.5f, 14.0f, 3.0f};
    scene.camera.target = {0.5f, 0.0f, 3.0f};
    scene.camera.up = {0.0f, 0.0f, -1.0f};
    scene.camera.fov_y_degrees = 40.0f;
    scene.camera.far_plane = 20.0f;  // one cascade over 20 m: shadow texels of about 1 cm

    RenderSettings settings = small_settings(256, 256);
    settings.shadow.cascades.count = 1;
    settings.shadow.cascades.resolution = 2048;
    const RenderedFrame frame = render_with_validation(scene, settings);
    ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();

    // Shadow edges may sit up to ~4 shadow texels from the geometric edge: 1 for the normal
    // offset, 2 for the slope-scaled bias on the quads (lit at 45 degrees), 1 for bilinear
    // comparison; plus half a pixel's footprint on the ground (2 cm).
    const float edge_band = 0.02f + 4.0f * frame.info.cascades[0].texel_world_size;
    size_t agree = 0, decided = 0, holes = 0, solid = 0;
    for (uint32_t y = 0; y < settings.height; ++y) {
        for (uint32_t x = 0; x < settings.width; ++x) {
            const PixelRay ray = pixel_ray(scene.camera, settings.width, settings.height, x, y);
            const auto ground_distance = intersect_ground(ray, 8.0f);
            if (!ground_distance) continue;
            const glm::vec3 point = ray.origin + ray.direction * *ground_distance;
            if (trace_masked(scene, ray.origin, ray.direction)) continue;  // the camera sees a quad here
            const auto expected = expected_shadow(scene, point, -sun.direction, edge_band);
            if (!expected) continue;  // outside the quads' shadows, or too close to a mask edge
            const bool expect_shadow = *expected;
            const bool shadowed = visibility_at(frame.images, x, y) < 0.5f;
            ++decided;
            agree += expect_shadow == shadowed;
            holes += !expect_shadow;
            solid += expect_shadow;
        }
    }
    EXPECT_GT(holes, 500u) << "the quads' shadows must contain holes";
    EXPECT_GT(solid, 500u) << "the quads must cast shadows";
    EXPECT_GE(static_cast<double>(agree) / decided, 0.99) << agree << " of " << decided << " pixels agree";
}

}  // namespace
}  // namespace penumbra::testing
