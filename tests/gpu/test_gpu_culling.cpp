// The layered strategy's GPU culling (shaders/caster_cull.comp) must submit exactly the
// casters the CPU's culling selects, per layer: per tile of a toroidal cascade (the static
// casters whose caster_footprint meets one of the tile's rectangles, the dynamic ones whose
// footprint meets its piece) on random cameras, sun directions and rectangles, and per spot or point light layer (the
// frustum, and a cube face's range: as cull_local_casters tests) on random lights; with random boxes (small, large,
// crossing the layers' edges, empty, and beyond the float range), culling on and off, layers left out, and again after
// the scene changes (the draws are uploaded anew). Run on the device with validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/camera_math.hpp"
#include "core/cascades.hpp"
#include "core/local_lights.hpp"
#include "core/shadow_cache.hpp"
#include "passes/caster_culling.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "renderer/app_context.hpp"

namespace penumbra::testing {
namespace {

constexpr uint32_t kResolution = 1024;

struct Case {
    CascadeSet cascades;
    passes::CasterScene scene;
};

// Boxes over a 200 m square: most small (trees), some large, a few empty or enormous.
passes::CasterScene random_scene(std::mt19937& random, uint32_t draws, uint64_t version) {
    std::uniform_real_distribution<float> place(-100.0f, 100.0f);
    std::uniform_real_distribution<float> size(0.1f, 6.0f);
    std::uniform_int_distribution<int> kind(0, 99);
    passes::CasterScene scene;
    scene.version = version;
    scene.meshes.resize(3);
    scene.meshes[1].index_type = VK_INDEX_TYPE_UINT16;
    for (passes::CasterMesh& mesh : scene.meshes) mesh.index_count = 36;
    for (uint32_t d = 0; d < draws; ++d) {
        passes::CasterDraw draw;
        draw.mesh = d % 3;
        draw.masked = d % 5 == 0;
        draw.double_sided = d % 7 == 0;
        draw.mirrored = d % 11 == 0;
        draw.dynamic = d % 13 == 0;
        const glm::vec3 centre(place(random), place(random) * 0.1f + 5.0f, place(random));
        const glm::vec3 half(size(random), size(random) * 2.0f, size(random));
        draw.world_bounds = {centre - half, centre + half};
        const int k = kind(random);
        if (k < 3) draw.world_bounds = {centre - half * 20.0f, centre + half * 20.0f};  // large
        if (k == 3) draw.world_bounds = core::Aabb{};                                   // empty
        if (k == 4) draw.world_bounds = {glm::vec3(-3e38f), glm::vec3(3e38f)};          // inf once projected
        draw.model = glm::translate(glm::mat4(1.0f), centre);
        scene.draws.push_back(draw);
    }
    return scene;
}

CascadeSet random_cascades(std::mt19937& random, FitMode fit) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const glm::vec3 eye(unit(random) * 60.0f, 2.0f + (unit(random) + 1.0f) * 10.0f, unit(random) * 60.0f);
    const glm::vec3 target = eye + glm::vec3(unit(random), unit(random) * 0.5f - 0.2f, unit(random));
    const glm::mat4 view = glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    const CameraView camera = make_camera_view(view, glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 120.0f);
    const glm::vec3 sun = glm::normalize(glm::vec3(unit(random), -0.3f - (unit(random) + 1.0f), unit(random)));
    CascadeSettings settings;
    settings.resolution = kResolution;
    settings.fit = fit;
    settings.max_distance = 100.0f;
    CascadeSet set = compute_cascades(camera, sun, settings,
                                      core::Aabb{glm::vec3(-120.0f, -1.0f, -120.0f), glm::vec3(120.0f, 30.0f, 120.0f)});
    place_in_layers(set, kResolution, true);
    return set;
}

// Each cascade's four tiles, with what a frame draws in them: the whole window (a cascade
// drawn anew), random rectangles (a cached cascade's exposed strips and changed casters,
// split at the layer's wrap lines as the library splits them), or nothing (only dynamic
// casters are drawn).
passes::CascadeTiles random_tiles(std::mt19937& random, const CascadeSet& set) {
    std::uniform_int_distribution<int32_t> texel(0, static_cast<int32_t>(kResolution));
    std::uniform_int_distribution<int> count(1, 6);
    passes::CascadeTiles tiles{kResolution, std::vector<passes::CullTileRects>(4 * set.cascades.size())};
    for (size_t c = 0; c < set.cascades.size(); ++c) {
        const glm::ivec2 origin = set.cascades[c].layer_origin;
        for (const LayerPiece& piece : layer_pieces(whole_map(kResolution), origin, kResolution))
            tiles.tiles[4 * c + piece.tile].piece = piece.window;
        std::vector<TexelRect> rects;
        if (c % 3 == 0) rects.push_back(whole_map(kResolution));
        for (int r = 0, n = c % 3 == 1 ? count(random) : 0; r < n; ++r) {
            const glm::ivec2 a(texel(random), texel(random));
            const glm::ivec2 b(texel(random), texel(random));
            rects.push_back({glm::min(a, b), glm::max(a, b) + 1});
        }
        for (const TexelRect& rect : rects) {
            const TexelRect inside = intersect(rect, whole_map(kResolution));
            if (inside.empty()) continue;
            for (const LayerPiece& piece : layer_pieces(inside, origin, kResolution))
                tiles.tiles[4 * c + piece.tile].rects.push_back(piece.window);
        }
    }
    return tiles;
}

// Per tile, the draws the CPU's culling selects (a footprint of the whole window without
// culling).
std::vector<std::vector<uint32_t>> cpu_selection(const Case& test, const passes::CascadeTiles& tiles, bool cull) {
    std::vector<std::vector<uint32_t>> selected(tiles.tiles.size());
    for (size_t layer = 0; layer < selected.size(); ++layer) {
        const Cascade& cascade = test.cascades.cascades[layer / 4];
        const passes::CullTileRects& tile = tiles.tiles[layer];
        for (uint32_t d = 0; d < test.scene.draws.size(); ++d) {
            const passes::CasterDraw& draw = test.scene.draws[d];
            const TexelRect footprint =
                cull ? caster_footprint(cascade, draw.world_bounds, kResolution) : whole_map(kResolution);
            const auto meets = [&](const TexelRect& rect) { return !intersect(footprint, rect).empty(); };
            const bool drawn =
                draw.dynamic ? meets(tile.piece) : std::any_of(tile.rects.begin(), tile.rects.end(), meets);
            if (drawn) selected[layer].push_back(d);
        }
    }
    return selected;
}

class GpuCulling : public ::testing::Test {
protected:
    GpuCulling() : options_(validating()), context_(options_) {
        const VkDescriptorSetLayoutBinding bindings[] = {
            {PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
             nullptr},
            {PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
             nullptr}};
        frame_layout_ = gpu::create_descriptor_set_layout(context_, bindings);
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
        pool_ = gpu::create_descriptor_pool(context_, 1, sizes);
        frame_set_ = gpu::allocate_descriptor_set(context_, pool_, frame_layout_);
        uniforms_ = gpu::create_buffer(context_, sizeof(shader::PenumbraShadowUniforms),
                                       VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryKind::HostUpload);
        local_ = gpu::create_buffer(context_, sizeof(shader::PenumbraLocalShadows), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    gpu::MemoryKind::HostUpload);
        gpu::write_uniform_buffer(context_, frame_set_, PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS, uniforms_.get(),
                                  uniforms_.size);
        gpu::write_storage_buffer(context_, frame_set_, PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS, local_.get(),
                                  local_.size);
    }

    static VulkanContextOptions validating() {
        VulkanContextOptions options;
        options.validation = true;
        return options;
    }

    // Culls `test` into `tiles` on the GPU and returns its selection per tile.
    passes::CulledDraws cull_on_gpu(passes::GpuCasterCulling& culling, const Case& test,
                                    const passes::CascadeTiles& tiles, bool cull) {
        shader::PenumbraShadowUniforms uniforms{};
        for (size_t c = 0; c < test.cascades.cascades.size(); ++c) {
            uniforms.cascades[c].view_projection = test.cascades.cascades[c].view_projection;
        }
        std::memcpy(uniforms_.mapped, &uniforms, sizeof(uniforms));
        const std::vector<bool> enabled(tiles.tiles.size(), true);
        context_.submit_and_wait([&](VkCommandBuffer cmd) {
            culling.record_cull(cmd, frame_set_, test.scene, passes::CullLayers::CascadeTiles, enabled, cull, 0,
                                &tiles);
        });
        return culling.read_back(context_.one_time());
    }

    passes::CulledDraws cull_local_on_gpu(passes::GpuCasterCulling& culling, const shader::PenumbraLocalShadows& local,
                                          const passes::CasterScene& scene, const std::vector<bool>& enabled,
                                          bool cull) {
        std::memcpy(local_.mapped, &local, sizeof(local));
        context_.submit_and_wait([&](VkCommandBuffer cmd) {
            culling.record_cull(cmd, frame_set_, scene, passes::CullLayers::LocalLayers, enabled, cull);
        });
        return culling.read_back(context_.one_time());
    }

    VulkanContextOptions options_;
    renderer::AppContext context_;
    gpu::UniqueDescriptorSetLayout frame_layout_;
    gpu::UniqueDescriptorPool pool_;
    VkDescriptorSet frame_set_ = VK_NULL_HANDLE;
    gpu::Buffer uniforms_;
    gpu::Buffer local_;
};

TEST_F(GpuCulling, SelectsExactlyTheCastersTheCpuSelectsPerCascadeTile) {
    ASSERT_TRUE(context_.features().gpu_driven) << "the test device lacks the layered strategy's features";
    passes::GpuCasterCulling culling(context_, frame_layout_, 2);
    std::mt19937 random(20261125);
    size_t compared = 0, selected = 0;
    Case test;
    for (int trial = 0; trial < 12; ++trial) {
        test.cascades = random_cascades(random, trial % 2 ? FitMode::Tight : FitMode::Stable);
        // The scene changes every other trial (a new version is uploaded), and grows; in
        // between only the cascades move (the uploaded draws are reused).
        if (trial % 2 == 0) {
            test.scene =
                random_scene(random, 400u + 150u * static_cast<uint32_t>(trial / 2), static_cast<uint64_t>(trial / 2));
        }
        const passes::CascadeTiles tiles = random_tiles(random, test.cascades);
        for (const bool cull : {true, false}) {
            const std::vector<std::vector<uint32_t>> expected = cpu_selection(test, tiles, cull);
            const passes::CulledDraws gpu = cull_on_gpu(culling, test, tiles, cull);
            ASSERT_EQ(gpu.draws_per_layer.size(), expected.size());
            for (size_t layer = 0; layer < expected.size(); ++layer) {
                EXPECT_EQ(gpu.draws_per_layer[layer], expected[layer])
                    << "trial " << trial << " cull " << cull << " cascade " << layer / 4 << " tile " << layer % 4;
                if (!cull || tiles.tiles[layer].rects.empty()) continue;
                compared += test.scene.draws.size();
                selected += expected[layer].size();
            }
        }
        EXPECT_GT(culling.buckets().size(), 4u) << "the draws' flags make several buckets";
    }
    // Culling must have mattered: some casters in, many out.
    EXPECT_GT(selected, compared / 20);
    EXPECT_LT(selected, compared * 3 / 4);
    EXPECT_TRUE(options_.validation_log->messages.empty()) << options_.validation_log->messages.front();
}

// Spot and point lights over the boxes: the layers as the library lays them out (a spot one,
// a point six), some left out (kept or unreachable layers are not culled).
TEST_F(GpuCulling, SelectsExactlyTheCastersTheCpuSelectsPerLocalLayer) {
    ASSERT_TRUE(context_.features().gpu_driven) << "the test device lacks the layered strategy's features";
    passes::GpuCasterCulling culling(context_, frame_layout_, 2);
    std::mt19937 random(1126);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    size_t compared = 0, selected = 0;
    for (int trial = 0; trial < 6; ++trial) {
        const passes::CasterScene scene = random_scene(random, 500, static_cast<uint64_t>(trial));
        shader::PenumbraLocalShadows local{};
        std::vector<glm::mat4> layers;
        std::vector<std::pair<core::Light, uint32_t>> lights;  // and the first layer
        for (uint32_t l = 0; l < 6; ++l) {
            core::Light light;
            light.type = l % 2 ? LightType::Point : LightType::Spot;
            light.position = glm::vec3(unit(random) * 60.0f, 3.0f + (unit(random) + 1.0f) * 4.0f, unit(random) * 60.0f);
            light.direction = glm::normalize(glm::vec3(unit(random), -1.0f, unit(random)));
            light.range = 15.0f + (unit(random) + 1.0f) * 15.0f;
            light.outer_angle_degrees = 35.0f;
            const float near = 0.1f;
            shader::PenumbraLocalShadow& out = local.lights[l];
            out.position = light.position;
            out.range = light.range;
            out.first_layer = static_cast<int32_t>(layers.size());
            out.cube = light.type == LightType::Point ? 1u : 0u;
            lights.emplace_back(light, static_cast<uint32_t>(layers.size()));
            if (out.cube) {
                for (const glm::mat4& face : point_shadow_view_projections(light.position, near, light.range))
                    layers.push_back(face);
            } else {
                layers.push_back(spot_shadow_view_projection(light, near));
            }
        }
        local.light_count = static_cast<uint32_t>(lights.size());
        for (size_t i = 0; i < layers.size(); ++i) local.layer_view_projection[i] = layers[i];
        std::vector<bool> enabled(layers.size(), true);
        enabled[static_cast<size_t>(trial) % layers.size()] = false;  // a kept layer
        for (const bool cull : {true, false}) {
            const passes::CulledDraws gpu = cull_local_on_gpu(culling, local, scene, enabled, cull);
            ASSERT_EQ(gpu.draws_per_layer.size(), layers.size());
            for (const auto& [light, first_layer] : lights) {
                const bool cube = light.type == LightType::Point;
                for (uint32_t face = 0; face < (cube ? 6u : 1u); ++face) {
                    const uint32_t layer = first_layer + face;
                    std::vector<uint32_t> expected;
                    for (uint32_t d = 0; enabled[layer] && d < scene.draws.size(); ++d) {
                        const core::Aabb& box = scene.draws[d].world_bounds;
                        const bool casts = caster_may_shadow_frustum(layers[layer], box) &&
                                           (!cube || caster_may_shadow_sphere(light.position, light.range, box));
                        if (!cull || casts) expected.push_back(d);
                    }
                    EXPECT_EQ(gpu.draws_per_layer[layer], expected)
                        << "trial " << trial << " cull " << cull << " layer " << layer;
                    if (!cull || !enabled[layer]) continue;
                    compared += scene.draws.size();
                    selected += expected.size();
                }
            }
        }
    }
    EXPECT_GT(selected, compared / 100) << "some casters reach the lights";
    EXPECT_LT(selected, compared / 2) << "most do not";
    EXPECT_TRUE(options_.validation_log->messages.empty()) << options_.validation_log->messages.front();
}

// Room for every caster in every layer: 2^26 commands at most, and no more than one storage
// buffer of the device holds (20 bytes each); refused with the numbers.
TEST_F(GpuCulling, TooManyCastersInTooManyLayersAreRefusedWithTheNumbers) {
    constexpr uint32_t kLayers = 192;
    const uint64_t range = context_.properties().limits.maxStorageBufferRange;
    const uint64_t most = std::min<uint64_t>(uint64_t{1} << 26, range / 20);
    const size_t fits = most / kLayers;
    EXPECT_NO_THROW(passes::check_gpu_culling_room(context_, fits, kLayers));
    try {
        passes::check_gpu_culling_room(context_, fits + 1, kLayers);
        ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& error) {
        const std::string expected = std::to_string(fits + 1) + " casting instances in 192 layers";
        EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
    // The virtual shadow map's culling of clusters says so.
    try {
        passes::check_gpu_culling_room(context_, fits + 1, kLayers, passes::CullUnit::Clusters);
        ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& error) {
        const std::string expected =
            "virtual shadow map: " + std::to_string(fits + 1) + " caster clusters in 192 levels";
        EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("use the cascades"), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace penumbra::testing
