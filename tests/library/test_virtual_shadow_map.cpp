// The sun's virtual shadow map (Settings::shadow.technique = virtual) through the public
// API: the box's shadow on the ground against its analytic footprint with every comparison
// filter; the same shadows as the cascades; cached pages bit-identical to pages drawn anew
// every frame while the camera moves, a dynamic box moves and static boxes change; a pool
// too small for the frame's pages serves coarser levels and says so; the statistics; and
// the errors of bad settings and calls out of order.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

void add_sun(ShadowSystem& shadows) {
    const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    shadows.set_lights({&sun, 1});
}

// Frames of a system whose page-draw buffer holds `room` draws, until one drops and defers
// none (at most `frame_limit`); then the image of the frame after it. One frame in flight:
// FrameInfo counts the frame before.
struct CatchUp {
    int frames = 0;
    uint32_t dropped = 0;        // the last frame counted
    uint32_t deferred = 0;       // the last frame counted
    uint32_t first_asked = 0;    // page draws the first frame asked for
    uint32_t first_dropped = 0;  // and dropped
    uint32_t most_deferred = 0;  // pages one frame left for later
    VisibilityImage2D image;
};

class VirtualShadowMapTest : public LibraryTest {
protected:
    // A prepared frame's marking and shadow maps from the ground's depth under `view`, with
    // no resolve (a frame whose FrameInfo was read, recorded so that the next one may start).
    void record_frame_without_resolve(ShadowSystem& shadows, const ViewDesc& view) {
        submit([&](VkCommandBuffer cmd) {
            const ScreenInputs screen = record_ground_depth(cmd, view, nullptr, NormalEncoding::SignedFloat, nullptr);
            shadows.record_page_marking(cmd, screen);
            shadows.record_shadow_maps(cmd);
        });
    }

    static Settings virtual_settings(ShadowFilter filter = ShadowFilter::Hard) {
        Settings settings = test_settings();
        settings.shadow.technique = ShadowTechnique::Virtual;
        settings.shadow.virtual_maps.pool_mib = 16;  // 256 pages: plenty for a 160 x 160 view
        settings.shadow.filter.mode = filter;
        return settings;
    }

    CatchUp catch_up(Settings settings, uint32_t room, int frame_limit);
};

class VirtualFilterTest : public VirtualShadowMapTest, public ::testing::WithParamInterface<ShadowFilter> {};

TEST_P(VirtualFilterTest, TheBoxShadowMatchesItsAnalyticFootprint) {
    ShadowSystem shadows(system_desc(virtual_settings(GetParam())));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(shadows, box, ground);
    add_sun(shadows);
    const VisibilityImage2D image = render_visibility(shadows);
    ASSERT_EQ(shadows.prepare(top_down_view()).virtual_map->texel_world_size[8], 0.0625f);
    // The pixels (6.8 cm) sample level 8, whose texels are 6.25 cm: the edge band is the
    // filter's reach there (pcf: 1 texel, Poisson: 2.5; pcss: the sun's penumbra, 0.53
    // degrees over 3 m, is about 3 cm), the bilinear tap's texel and the rasteriser's half
    // texel, stretched on the ground by the sun's slant (|direction| / |direction.y| = 1.12).
    const float reach = GetParam() == ShadowFilter::Pcf ? 1.0f : GetParam() == ShadowFilter::Poisson ? 2.5f : 0.0f;
    const float slant = glm::length(kSunDirection) / std::abs(kSunDirection.y);
    const FootprintCheck check =
        check_footprint(image, kBoxCentre, kSunDirection, 0.0625f * (reach + 1.5f) * slant + 0.01f);
    EXPECT_GE(check.iou, 0.97);
    EXPECT_EQ(check.wrong, 0u) << "of " << check.judged << " pixels away from the edge";
    EXPECT_GT(check.shadowed, 700u);
    record_frame_without_resolve(shadows, top_down_view());
}

INSTANTIATE_TEST_SUITE_P(ComparisonFilters, VirtualFilterTest,
                         ::testing::Values(ShadowFilter::Hard, ShadowFilter::Pcf, ShadowFilter::Poisson,
                                           ShadowFilter::Pcss),
                         [](const ::testing::TestParamInfo<ShadowFilter>& filter) {
                             return std::string(choice_name(kShadowFilterChoices, filter.param));
                         });

TEST_F(VirtualShadowMapTest, CastsTheSameShadowsAsTheCascades) {
    Settings cascade_settings = test_settings();
    ShadowSystem cascades(system_desc(cascade_settings));
    ShadowSystem virtual_map(system_desc(virtual_settings()));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    for (ShadowSystem* system : {&cascades, &virtual_map}) {
        add_scene(*system, box, ground);
        add_sun(*system);
    }
    const VisibilityImage2D expected = render_visibility(cascades);
    const VisibilityImage2D actual = render_visibility(virtual_map);
    size_t differ = 0, shadowed = 0;
    for (size_t i = 0; i < expected.values.size(); ++i) {
        differ += (expected.values[i] < 0.5f) != (actual.values[i] < 0.5f) ? 1 : 0;
        shadowed += actual.values[i] < 0.5f ? 1 : 0;
    }
    // Both resolve the box's shadow; they differ only along its edge, where the cascades'
    // texels (2.3 cm here) and the virtual level's (6.3 cm) round differently.
    EXPECT_GT(shadowed, 1000u);
    EXPECT_LT(differ, shadowed / 20) << differ << " pixels differ of " << shadowed << " shadowed";
}

// Static boxes, one that moves every frame, a camera that slides sideways (the windows move
// by whole pages); frames 4, 7 and 9 move, add and remove static boxes in view, within the
// static boxes' first bounds (a new depth range would redraw every page). Bit for bit: the
// allocation's order (GPU atomics, different in any two runs) picks each page's place in the
// pool, but a caster's clip space is the page's own and the place enters only as a whole-texel
// viewport offset, so a page's texels are the same wherever it lies. A page not drawn again
// after a change would differ over a whole box's shadow edge.
TEST_F(VirtualShadowMapTest, CachedPagesEqualPagesDrawnEveryFrame) {
    Settings settings = virtual_settings(ShadowFilter::Pcf);
    // Texels four times finer than the pixels: pages of 2 m, so that the moving box's pages
    // (redrawn every frame with everything in them) leave the static boxes' pages cached.
    settings.shadow.virtual_maps.lod_bias = -2.0f;
    settings.shadow.cache_static_casters = true;
    ShadowSystem cached(system_desc(settings));
    settings.shadow.cache_static_casters = false;
    ShadowSystem uncached(system_desc(settings));
    BoxesAndMover scenes[2] = {add_ground_and_box_mesh(cached), add_ground_and_box_mesh(uncached)};
    ShadowSystem* systems[2] = {&cached, &uncached};
    for (int s = 0; s < 2; ++s) {
        for (int i = 0; i < 4; ++i) {
            const glm::vec3 at(-4.0f + 3.0f * static_cast<float>(i), 1.0f + 0.5f * static_cast<float>(i % 2), -3.0f);
            scenes[s].statics.push_back(systems[s]->add_instance({scenes[s].box_id, translation(at)}));
        }
        scenes[s].mover = systems[s]->add_instance(
            {scenes[s].box_id, translation({0.0f, 2.0f, 2.0f}), kInstanceCastsShadows | kInstanceDynamic});
        add_sun(*systems[s]);
    }
    uint32_t cached_pages = 0, redrawn_cached = 0, redrawn_uncached = 0;
    for (int f = 0; f < 12; ++f) {
        const float t = static_cast<float>(f);
        for (int s = 0; s < 2; ++s) {
            ShadowSystem& shadows = *systems[s];
            shadows.set_instance_transform(scenes[s].mover, translation({2.0f * std::sin(0.7f * t), 2.0f, 2.0f}));
            if (f == 4) shadows.set_instance_transform(scenes[s].statics[1], translation({-1.0f, 1.2f, -3.5f}));
            if (f == 7)
                scenes[s].statics.push_back(shadows.add_instance({scenes[s].box_id, translation({4.0f, 1.0f, -3.5f})}));
            if (f == 9) shadows.remove_instance(scenes[s].statics[2]);
        }
        const ViewDesc view = top_down_view_at(0.31f * t, -0.17f * t);
        const VisibilityImage2D expected = render_visibility_from(uncached, view);
        const VisibilityImage2D actual = render_visibility_from(cached, view);
        ASSERT_EQ(expected.values.size(), actual.values.size());
        EXPECT_EQ(differing_pixels(expected, actual), 0u) << "frame " << f;
    }
    // After the frames in flight, the GPU's counts: the cache drew a fraction of the pages.
    for (int f = 0; f < 4; ++f) {
        const ViewDesc view = top_down_view_at(3.72f, -2.04f);
        for (ShadowSystem* system : systems) {
            const FrameInfo& info = system->prepare(view);
            ASSERT_TRUE(info.virtual_map.has_value());
            if (f == 3) {
                EXPECT_GT(info.virtual_map->counted_frame, 0u);
                if (system == &cached) {
                    cached_pages = info.virtual_map->pages_cached;
                    redrawn_cached = info.virtual_map->pages_rendered;
                } else {
                    redrawn_uncached = info.virtual_map->pages_rendered;
                    EXPECT_TRUE(info.virtual_map->invalidated_all);
                    // Each page draw is a box (12 triangles) or the ground (2).
                    const VirtualShadowInfo& map = *info.virtual_map;
                    EXPECT_GE(map.page_draws, map.pages_rendered) << "the ground reaches every page";
                    EXPECT_GE(map.page_draw_triangles, uint64_t{2} * map.page_draws);
                    EXPECT_LE(map.page_draw_triangles, uint64_t{12} * map.page_draws);
                    EXPECT_GT(map.page_draw_triangles, uint64_t{2} * map.page_draws) << "boxes were drawn too";
                }
            }
            record_frame_without_resolve(*system, view);
        }
    }
    EXPECT_GT(cached_pages, 0u);
    EXPECT_LT(redrawn_cached, redrawn_uncached) << "the dynamic box's pages only";
    EXPECT_GT(redrawn_uncached, 0u);
}

TEST_F(VirtualShadowMapTest, APoolTooSmallServesACoarserLevelAndSaysSo) {
    Settings settings = virtual_settings();
    settings.shadow.virtual_maps.lod_bias = -4.0f;  // 16 times finer: hundreds of pages for this view
    ShadowSystem shadows(system_desc(settings));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(shadows, box, ground);
    add_sun(shadows);
    VisibilityImage2D image;
    for (int f = 0; f < 3; ++f) image = render_visibility(shadows);
    const FrameInfo& info = shadows.prepare(top_down_view());
    ASSERT_TRUE(info.virtual_map.has_value());
    EXPECT_EQ(info.virtual_map->pool_pages, 256u);
    EXPECT_GT(info.virtual_map->pages_requested, 256u);
    EXPECT_GT(info.virtual_map->pages_unserved, 0u);
    EXPECT_EQ(info.virtual_map->pages_resident, 256u);
    // Never another page's texels: the shadow is still the box's, from coarser texels.
    const FootprintCheck check = check_footprint(image, kBoxCentre, kSunDirection, 0.3f);
    EXPECT_GE(check.iou, 0.95);
    EXPECT_EQ(check.wrong, 0u) << "of " << check.judged;
    record_frame_without_resolve(shadows, top_down_view());
}

CatchUp VirtualShadowMapTest::catch_up(Settings settings, uint32_t room, int frame_limit) {
    settings.shadow.virtual_maps.page_draws = room;
    ShadowSystem tight(system_desc(settings, 1));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(tight, box, ground);
    add_sun(tight);
    render_visibility(tight);  // the first frame
    CatchUp result;
    for (result.frames = 1; result.frames < frame_limit; ++result.frames) {
        const FrameInfo& info = tight.prepare(top_down_view());
        const VirtualShadowInfo& map = info.virtual_map.value();
        if (result.frames == 1) {
            result.first_asked = map.page_draws;
            result.first_dropped = map.dropped_page_draws;
        }
        result.dropped = map.dropped_page_draws;
        result.deferred = map.pages_deferred;
        result.most_deferred = std::max(result.most_deferred, map.pages_deferred);
        submit([&](VkCommandBuffer cmd) {
            const ScreenInputs screen =
                record_ground_depth(cmd, top_down_view(), nullptr, NormalEncoding::SignedFloat, nullptr);
            tight.record_page_marking(cmd, screen);
            tight.record_shadow_maps(cmd);
            tight.record_visibility(cmd, screen);
        });
        if (result.dropped == 0 && result.deferred == 0 && result.frames > 1) break;
    }
    // The frame after the last one that dropped draws everything it needs.
    result.image = render_visibility(tight);
    return result;
}

// Page-draw buffers with room for 3/8 and 1/8 of a first frame's draws (less than the
// ground's pages in its finest level) and for 2, the most one page needs (the ground's and a
// box's draw): that frame drops draws and says so; the next frames draw only as many pages
// as the buffer holds all the draws of (the rest deferred), until nothing is dropped and the
// image is the one a buffer with room for every draw gives. Before the frames' pages were budgeted,
// a buffer under a third of the draws never caught up: the same first draws won every frame
// and the pages they completed were never whole.
TEST_F(VirtualShadowMapTest, ADrawBufferTooSmallCatchesUpOverFrames) {
    Settings settings = virtual_settings();
    settings.shadow.virtual_maps.lod_bias = -1.0f;  // finer pages: more draws
    settings.shadow.cache_static_casters = true;    // uncached, every frame draws (and drops) them all
    ShadowSystem roomy(system_desc(settings, 1));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(roomy, box, ground);
    add_sun(roomy);
    const VisibilityImage2D expected = render_visibility(roomy);
    const FrameInfo& first = roomy.prepare(top_down_view());
    ASSERT_TRUE(first.virtual_map.has_value());
    const uint32_t needed = first.virtual_map->page_draws;
    ASSERT_GT(needed, 20u) << "the first frame draws every page it needs";
    EXPECT_EQ(first.virtual_map->dropped_page_draws, 0u);
    EXPECT_EQ(first.virtual_map->pages_deferred, 0u);
    record_frame_without_resolve(roomy, top_down_view());

    for (const uint32_t room : {needed * 3 / 8, needed / 8, 2u}) {
        SCOPED_TRACE("room for " + std::to_string(room) + " of " + std::to_string(needed) + " page draws");
        const CatchUp tight = catch_up(settings, room, 60);
        EXPECT_EQ(tight.first_asked, needed) << "the draws asked for";
        EXPECT_GT(tight.first_dropped, 0u);
        EXPECT_EQ(tight.first_asked - tight.first_dropped, room) << "the buffer full";
        EXPECT_GT(tight.most_deferred, 0u) << "pages waited for a later frame";
        EXPECT_EQ(tight.dropped + tight.deferred, 0u) << "still dropping after " << tight.frames << " frames";
        EXPECT_EQ(differing_pixels(tight.image, expected), 0u);
    }
}

TEST_F(VirtualShadowMapTest, ReportsItsLevelsAndMemory) {
    Settings settings = virtual_settings();
    settings.shadow.virtual_maps.pool_mib = 32;
    ShadowSystem shadows(system_desc(settings));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(shadows, box, ground);
    add_sun(shadows);
    const FrameInfo& info = shadows.prepare(top_down_view());
    ASSERT_TRUE(info.virtual_map.has_value());
    EXPECT_TRUE(info.cascades.empty());
    ASSERT_EQ(info.virtual_map->levels, 16u);
    EXPECT_FLOAT_EQ(info.virtual_map->texel_world_size[0], 4.0f / 16384.0f);
    EXPECT_FLOAT_EQ(info.virtual_map->texel_world_size[15], 4.0f * 32768.0f / 16384.0f);
    EXPECT_EQ(info.virtual_map->pool_pages, 32u * 16u);
    EXPECT_TRUE(info.virtual_map->invalidated_all) << "the first frame draws every page it needs";
    EXPECT_GE(shadows.memory().virtual_pool, uint64_t{32} << 20);
    const MapImage pool = shadows.shadow_maps().virtual_pool;
    EXPECT_EQ(pool.format, VK_FORMAT_D32_SFLOAT);
    EXPECT_EQ(pool.resolution, 512u) << "4 x 4 pages a layer";
    EXPECT_EQ(pool.layers, 32u) << "512 pages";
    record_frame_without_resolve(shadows, top_down_view());
    // The cascades report no virtual map.
    ShadowSystem cascades(system_desc(test_settings()));
    EXPECT_FALSE(cascades.prepare(top_down_view()).virtual_map.has_value());
    EXPECT_EQ(cascades.memory().virtual_pool, 0u);
    submit([&](VkCommandBuffer cmd) { cascades.record_shadow_maps(cmd); });
}

// The layered strategy still culls the spot and point lights on the GPU; the sun's
// cascades are only a placeholder then, and the GPU's counts of past frames are read
// without them.
TEST_F(VirtualShadowMapTest, WorksBesideTheLayeredStrategy) {
    Settings settings = virtual_settings();
    settings.shadow.strategy = ShadowStrategy::Layered;
    ShadowSystem shadows(system_desc(settings));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(shadows, box, ground);
    add_sun(shadows);
    VisibilityImage2D image;
    for (int f = 0; f < 4; ++f) image = render_visibility(shadows);
    const FootprintCheck check = check_footprint(image, kBoxCentre, kSunDirection, 0.15f);
    EXPECT_GE(check.iou, 0.97);
    EXPECT_TRUE(shadows.prepare(top_down_view()).cascades.empty());
    record_frame_without_resolve(shadows, top_down_view());
}

std::string error_of(const std::function<void()>& call) {
    try {
        call();
    } catch (const Error& error) {
        return error.what();
    }
    return "no error";
}

// A ground of 32 x 32 quads and 64 thin posts over it, as one mesh: clusters of it are
// much smaller than its instance.
MeshArrays ground_and_posts_mesh() {
    MeshArrays mesh;
    const auto quad = [&mesh](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
        const auto base = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    };
    constexpr int kCells = 32;
    constexpr float kCell = 40.0f / kCells;
    for (int z = 0; z < kCells; ++z) {
        for (int x = 0; x < kCells; ++x) {
            const float x0 = -20.0f + kCell * static_cast<float>(x), z0 = -20.0f + kCell * static_cast<float>(z);
            quad({x0, 0, z0}, {x0, 0, z0 + kCell}, {x0 + kCell, 0, z0 + kCell}, {x0 + kCell, 0, z0});
        }
    }
    for (int i = 0; i < 64; ++i) {  // 5 cm posts, 2 m tall, every 1.5 m
        const float cx = -5.25f + 1.5f * static_cast<float>(i % 8), cz = -5.25f + 1.5f * static_cast<float>(i / 8);
        const float r = 0.025f;
        const Vec3 p[8] = {{cx - r, 0, cz + r}, {cx + r, 0, cz + r}, {cx + r, 2, cz + r}, {cx - r, 2, cz + r},
                           {cx + r, 0, cz - r}, {cx - r, 0, cz - r}, {cx - r, 2, cz - r}, {cx + r, 2, cz - r}};
        quad(p[0], p[1], p[2], p[3]);  // +Z
        quad(p[4], p[5], p[6], p[7]);  // -Z
        quad(p[1], p[4], p[7], p[2]);  // +X
        quad(p[5], p[0], p[3], p[6]);  // -X
        quad(p[3], p[2], p[7], p[6]);  // top
    }
    return mesh;
}

// The same mesh in the caller's buffers, with or without clusters (MeshDesc).
struct CallerMesh {
    HostBuffer vertices;
    HostBuffer indices;
    MeshDesc desc;
    CallerMesh(const DeviceDesc& device, const MeshArrays& mesh, std::span<const MeshCluster> clusters)
        : vertices(device, mesh.positions.size() * sizeof(Vec3), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT),
          indices(device, mesh.indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT) {
        std::memcpy(vertices.mapped, mesh.positions.data(), mesh.positions.size() * sizeof(Vec3));
        std::memcpy(indices.mapped, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
        desc.positions = {vertices.buffer, 0, sizeof(Vec3), VK_FORMAT_R32G32B32_SFLOAT};
        desc.index_buffer = indices.buffer;
        desc.index_count = static_cast<uint32_t>(mesh.indices.size());
        desc.bounds = {{-20, 0, -20}, {20, 2, 20}};
        desc.clusters = clusters;
    }
};

// Clusters are an optimisation only: a mesh drawn whole into every page its instance
// reaches, the same mesh clustered by Penumbra (MeshData) and clustered by the caller
// (build_mesh_clusters, MeshDesc::clusters) cast the same shadows, while the clustered ones
// send a fraction of the triangles through the rasteriser. Bit for bit: the depth test keeps
// the nearest caster whatever the order the triangles come in, and the pages' places in the
// pool do not change their texels (see CachedPagesEqualPagesDrawnEveryFrame).
TEST_F(VirtualShadowMapTest, ClustersCastTheShadowsOfWholeMeshesFromFewerTriangles) {
    Settings settings = virtual_settings(ShadowFilter::Pcf);
    settings.shadow.virtual_maps.lod_bias = -2.0f;  // pages of 2 m: dozens in view
    settings.shadow.cache_static_casters = false;   // every page drawn every frame
    const MeshArrays mesh = ground_and_posts_mesh();
    MeshArrays reordered = mesh;
    const std::vector<MeshCluster> clusters = build_mesh_clusters(reordered.positions, reordered.indices);
    ASSERT_EQ(clusters.size(), (mesh.indices.size() / 3 + 127) / 128);
    const CallerMesh whole(device_, mesh, {});
    const CallerMesh clustered_by_caller(device_, reordered, clusters);
    ShadowSystem systems[3] = {ShadowSystem(system_desc(settings)), ShadowSystem(system_desc(settings)),
                               ShadowSystem(system_desc(settings))};
    const MeshId meshes[3] = {systems[0].add_mesh(whole.desc), systems[1].add_mesh(mesh.data()),
                              systems[2].add_mesh(clustered_by_caller.desc)};
    for (int s = 0; s < 3; ++s) {
        systems[s].add_instance({meshes[s], Mat4{}});
        add_sun(systems[s]);
    }
    uint64_t triangles[3] = {};
    for (int f = 0; f < 4; ++f) {
        const ViewDesc view = top_down_view_at(0.9f * static_cast<float>(f), -0.6f * static_cast<float>(f));
        VisibilityImage2D images[3];
        for (int s = 0; s < 3; ++s) {
            images[s] = render_visibility_from(systems[s], view);
            const FrameInfo& info = systems[s].prepare(view);
            if (info.virtual_map->counted_frame > 0) triangles[s] += info.virtual_map->page_draw_triangles;
            record_frame_without_resolve(systems[s], view);
        }
        for (int s = 1; s < 3; ++s) {
            EXPECT_EQ(differing_pixels(images[0], images[s]), 0u) << "system " << s << " frame " << f;
        }
    }
    ASSERT_GT(triangles[0], 0u);
    EXPECT_LT(2 * triangles[1], triangles[0]) << "clusters drew " << triangles[1] << " of " << triangles[0];
    EXPECT_LT(2 * triangles[2], triangles[0]) << "clusters drew " << triangles[2] << " of " << triangles[0];
}

TEST_F(VirtualShadowMapTest, BadClustersAreNamed) {
    ShadowSystem shadows(system_desc(virtual_settings()));
    MeshArrays mesh = ground_and_posts_mesh();
    const std::vector<MeshCluster> clusters = build_mesh_clusters(mesh.positions, mesh.indices);
    const auto message = [&](std::vector<MeshCluster> changed) {
        const CallerMesh caller(device_, mesh, changed);
        return error_of([&] { shadows.add_mesh(caller.desc); });
    };
    std::vector<MeshCluster> gap = clusters;
    gap[1].first_index += 3;
    EXPECT_EQ(message(gap),
              "ShadowSystem::add_mesh: clusters[1].first_index: 387 is not 384, where the previous cluster ends "
              "(clusters cover the indices in order)");
    std::vector<MeshCluster> short_list(clusters.begin(), clusters.end() - 1);
    EXPECT_NE(message(short_list).find("ShadowSystem::add_mesh: clusters: end at index"), std::string::npos);
    std::vector<MeshCluster> inverted = clusters;
    std::swap(inverted[2].bounds.min, inverted[2].bounds.max);
    EXPECT_EQ(message(inverted), "ShadowSystem::add_mesh: clusters[2].bounds: min exceeds max on an axis");
    std::vector<MeshCluster> ragged = clusters;
    ragged[0].index_count = 4;
    EXPECT_NE(message(ragged).find("clusters[0].index_count: 4 is not a positive multiple of 3"), std::string::npos);
    std::vector<uint32_t> not_triangles(mesh.indices.begin(), mesh.indices.begin() + 4);
    EXPECT_EQ(error_of([&] { build_mesh_clusters(mesh.positions, not_triangles); }),
              "build_mesh_clusters: indices: 4 is not a multiple of 3");
    std::vector<uint32_t> beyond = {0, 1, 99999};
    EXPECT_EQ(error_of([&] { build_mesh_clusters(mesh.positions, beyond); }),
              "build_mesh_clusters: indices[2]: 99999 is out of range (" + std::to_string(mesh.positions.size()) +
                  " positions)");
}

TEST_F(VirtualShadowMapTest, BadSettingsAndCallsOutOfOrderAreNamed) {
    Settings settings = virtual_settings();
    settings.shadow.virtual_maps.pool_mib = 0;
    EXPECT_EQ(error_of([&] { ShadowSystem shadows(system_desc(settings)); }),
              "ShadowSystem settings: virtual_pool_mib: 0 is outside the allowed range [16, 1024]");
    settings = virtual_settings();
    settings.shadow.virtual_maps.lod_bias = 9.0f;
    EXPECT_EQ(error_of([&] { ShadowSystem shadows(system_desc(settings)); }),
              "ShadowSystem settings: virtual_lod_bias: 9 is outside the allowed range [-4, 4]");
    settings = virtual_settings(ShadowFilter::Vsm);
    EXPECT_EQ(error_of([&] { ShadowSystem shadows(system_desc(settings)); }),
              "ShadowSystem settings: filter: vsm is not available with shadow_technique virtual (use hard, pcf, "
              "poisson or pcss)");

    ShadowSystem shadows(system_desc(virtual_settings()));
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(shadows, box, ground);
    add_sun(shadows);
    shadows.prepare(top_down_view());
    std::string message;
    submit([&](VkCommandBuffer cmd) {
        message = error_of([&] { shadows.record_shadow_maps(cmd); });
        const ScreenInputs screen =
            record_ground_depth(cmd, top_down_view(), nullptr, NormalEncoding::SignedFloat, nullptr);
        shadows.record_page_marking(cmd, screen);
        shadows.record_shadow_maps(cmd);
        EXPECT_NE(error_of([&] { shadows.record_page_marking(cmd, screen); }).find("record_shadow_maps() was already"),
                  std::string::npos);
    });
    EXPECT_EQ(message,
              "ShadowSystem::record_shadow_maps: the virtual shadow map needs record_page_marking() earlier in this "
              "frame (the pages the frame's pixels sample)");
    // A live setting is a uniform; the pool's size reallocates it in the same system.
    Settings changed = shadows.settings();
    changed.shadow.virtual_maps.lod_bias = -1.0f;
    EXPECT_EQ(shadows.update_settings(changed).effect, SettingEffect::Live);
    const uint64_t pool_bytes = shadows.memory().shadow_maps();
    changed.shadow.virtual_maps.pool_mib *= 2;
    EXPECT_EQ(shadows.update_settings(changed).effect, SettingEffect::Resource);
    shadows.prepare(top_down_view());
    EXPECT_GT(shadows.memory().shadow_maps(), pool_bytes);
}

}  // namespace
}  // namespace penumbra::library_tests
