// The virtual shadow map clipmap's math (core/virtual_clipmap.hpp): levels that double,
// windows centred on the camera and snapped to whole pages of a world-fixed grid, the
// toroidal page table, the level a receiver takes, the pages a filter reads, and depth
// mappings that do not follow the camera.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>

#include "core/virtual_clipmap.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

const glm::vec3 kSun = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
const core::Aabb kScene{glm::vec3(-500.0f, -5.0f, -500.0f), glm::vec3(500.0f, 40.0f, 500.0f)};

VirtualClipmapConfig small_config() {
    VirtualClipmapConfig config;
    config.level_resolution = 2048;
    config.level_count = 12;
    config.first_level_extent = 4.0f;
    return config;
}

TEST(VirtualClipmap, LevelsDoubleInExtentAndShareOnePageSize) {
    const VirtualClipmapConfig config = small_config();
    const VirtualClipmap clipmap = compute_virtual_clipmap(glm::vec3(3.0f, 2.0f, -7.0f), kSun, config, kScene);
    ASSERT_EQ(clipmap.levels.size(), 12u);
    EXPECT_EQ(clipmap.pages_per_side, 2048u / kVirtualPageTexels);
    for (size_t l = 0; l < clipmap.levels.size(); ++l) {
        const VirtualLevel& level = clipmap.levels[l];
        EXPECT_FLOAT_EQ(level.extent, 4.0f * std::exp2(static_cast<float>(l)));
        EXPECT_FLOAT_EQ(level.texel_world_size * 2048.0f, level.extent);
        EXPECT_FLOAT_EQ(level.texels_per_metre * level.texel_world_size, 1.0f);
    }
}

TEST(VirtualClipmap, EveryWindowHoldsTheCameraInItsCentrePage) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> place(-20000.0f, 20000.0f);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 eye(place(random), place(random) * 0.01f, place(random));
        const VirtualClipmap clipmap = compute_virtual_clipmap(eye, kSun, small_config(), kScene);
        const float half = 0.5f * static_cast<float>(clipmap.level_resolution);
        for (int l = 0; l < static_cast<int>(clipmap.levels.size()); ++l) {
            const glm::vec2 texel = virtual_texel_of(clipmap, l, eye);
            // The camera's page is page pages_per_side / 2 (up to float rounding of far
            // positions at the finest levels: a texel's width).
            const float slack = 1.0f + std::abs(place.max()) * 1e-6f * clipmap.levels[l].texels_per_metre;
            EXPECT_GE(texel.x, half - slack) << "level " << l;
            EXPECT_LE(texel.x, half + kVirtualPageTexels + slack) << "level " << l;
            EXPECT_GE(texel.y, half - slack) << "level " << l;
            EXPECT_LE(texel.y, half + kVirtualPageTexels + slack) << "level " << l;
        }
    }
}

TEST(VirtualClipmap, WindowsMoveByWholePagesAndKeepAWorldPointsSlot) {
    const VirtualClipmapConfig config = small_config();
    const glm::vec3 point(10.0f, 0.0f, 4.0f);
    glm::vec3 eye(0.0f, 5.0f, 0.0f);
    const VirtualClipmap first = compute_virtual_clipmap(eye, kSun, config, kScene);
    for (int step = 1; step <= 40; ++step) {
        eye += glm::vec3(0.37f, 0.0f, 0.21f);
        const VirtualClipmap moved = compute_virtual_clipmap(eye, kSun, config, kScene);
        for (int l = 0; l < static_cast<int>(moved.levels.size()); ++l) {
            const glm::ivec2 shift = moved.levels[l].first_page - first.levels[l].first_page;
            // The point's texel within the window moves by the pages the window moved (up to
            // the float rounding of subtracting a different whole number of pages).
            const glm::vec2 before = virtual_texel_of(first, l, point);
            const glm::vec2 after = virtual_texel_of(moved, l, point);
            const glm::vec2 expected(shift * static_cast<int>(kVirtualPageTexels));
            EXPECT_NEAR(before.x - after.x, expected.x, 1e-3f) << "level " << l;
            EXPECT_NEAR(before.y - after.y, expected.y, 1e-3f) << "level " << l;
            // Its page keeps its table slot while both windows hold it.
            const glm::ivec2 page_before(glm::floor(before / float(kVirtualPageTexels)));
            const glm::ivec2 page_after(glm::floor(after / float(kVirtualPageTexels)));
            const int side = static_cast<int>(moved.pages_per_side);
            const auto inside = [side](glm::ivec2 p) { return p.x >= 0 && p.y >= 0 && p.x < side && p.y < side; };
            if (inside(page_before) && inside(page_after)) {
                EXPECT_EQ(page_table_slot(first, l, page_before), page_table_slot(moved, l, page_after));
            }
        }
    }
}

TEST(VirtualClipmap, SlotsAndWorldPagesAreInverse) {
    const uint32_t side = 16;
    VirtualClipmap clipmap;
    clipmap.pages_per_side = side;
    clipmap.level_resolution = side * kVirtualPageTexels;
    for (const glm::ivec2 first : {glm::ivec2(0, 0), glm::ivec2(-37, 5), glm::ivec2(1000, -1000), glm::ivec2(-1, -1)}) {
        clipmap.levels = {VirtualLevel{}};
        clipmap.levels[0].first_page = first;
        std::set<uint32_t> slots;
        for (int y = 0; y < static_cast<int>(side); ++y) {
            for (int x = 0; x < static_cast<int>(side); ++x) {
                const uint32_t slot = page_table_slot(clipmap, 0, glm::ivec2(x, y));
                ASSERT_LT(slot, side * side);
                slots.insert(slot);
                EXPECT_EQ(world_page_of_slot(first, side, slot), first + glm::ivec2(x, y));
            }
        }
        EXPECT_EQ(slots.size(), side * side) << "every window page has its own slot";
    }
}

TEST(VirtualClipmap, ReceiversTakeTheFinestLevelNoCoarserThanTheirPixel) {
    const VirtualClipmapConfig config = small_config();
    const glm::vec3 eye(12.0f, 3.0f, -4.0f);
    const VirtualClipmap clipmap = compute_virtual_clipmap(eye, kSun, config, kScene);
    const float per_metre = pixel_footprint_per_metre(glm::radians(60.0f), 270);
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_real_distribution<float> log_distance(-2.0f, 3.5f);
    for (float bias : {-1.0f, 0.0f, 1.5f}) {
        for (int i = 0; i < 2000; ++i) {
            const glm::vec3 direction = glm::normalize(glm::vec3(unit(random), unit(random) * 0.3f, unit(random)));
            const float distance = std::pow(10.0f, log_distance(random));
            const glm::vec3 point = eye + direction * distance;
            const int level = select_virtual_level(clipmap, eye, per_metre, bias, point, 2.0f);
            const float footprint = distance * per_metre * std::exp2(bias);
            const float finest = clipmap.levels.front().texel_world_size;
            if (level < 0) {
                // Outside even the coarsest window.
                const glm::vec2 texel = virtual_texel_of(clipmap, static_cast<int>(clipmap.levels.size()) - 1, point);
                EXPECT_TRUE(texel.x < 2.0f || texel.y < 2.0f || texel.x > 2046.0f || texel.y > 2046.0f);
                continue;
            }
            const float texel = clipmap.levels[level].texel_world_size;
            // Never coarser than the pixel (relative slack for log2 rounding at level edges),
            // unless the point lies beyond the finer levels' windows or is finer than level 0.
            if (footprint > finest && level > 0) {
                const bool finer_holds_it = [&] {
                    const glm::vec2 t = virtual_texel_of(clipmap, level - 1, point);
                    return t.x >= 2.0f && t.y >= 2.0f && t.x <= 2046.0f && t.y <= 2046.0f;
                }();
                // ... and the next finer level would be finer than needed (texel > footprint / 2),
                // unless even the coarsest level is finer than the pixel.
                const bool coarsest = level + 1 == static_cast<int>(clipmap.levels.size());
                if (finer_holds_it) {
                    EXPECT_LE(texel, footprint * 1.0001f) << distance;
                    if (!coarsest) {
                        EXPECT_GT(texel, 0.5f * footprint * 0.9999f) << distance;
                    }
                }
            }
            const glm::vec2 t = virtual_texel_of(clipmap, level, point);
            EXPECT_GE(std::min(t.x, t.y), 2.0f);
            EXPECT_LE(std::max(t.x, t.y), 2046.0f);
        }
    }
}

TEST(VirtualClipmap, FilterNeighbourhoodsCoverEveryTexelTheyRead) {
    const VirtualClipmap clipmap = compute_virtual_clipmap(glm::vec3(0.0f), kSun, small_config(), kScene);
    const PageRect inner = pages_around(clipmap, glm::vec2(300.0f, 130.0f), 4.0f);
    EXPECT_EQ(inner.min, glm::ivec2(2, 0));
    EXPECT_EQ(inner.max, glm::ivec2(3, 2));  // 126..134 crosses into page row 1
    const PageRect corner = pages_around(clipmap, glm::vec2(1.0f, 2040.0f), 10.0f);
    EXPECT_EQ(corner.min, glm::ivec2(0, 15));
    EXPECT_EQ(corner.max, glm::ivec2(1, 16));  // clipped to the window
    const PageRect outside = pages_around(clipmap, glm::vec2(-500.0f, 100.0f), 4.0f);
    EXPECT_TRUE(outside.empty());
    std::mt19937 random(11);
    std::uniform_real_distribution<float> place(0.0f, 2048.0f);
    for (int i = 0; i < 500; ++i) {
        const glm::vec2 texel(place(random), place(random));
        const float radius = 0.5f + place(random) / 200.0f;
        const PageRect rect = pages_around(clipmap, texel, radius);
        for (const glm::vec2 corner_offset : {glm::vec2(-1, -1), glm::vec2(1, 1), glm::vec2(-1, 1), glm::vec2(1, -1)}) {
            const glm::vec2 tap = glm::clamp(texel + corner_offset * radius, glm::vec2(0.0f), glm::vec2(2047.99f));
            const glm::ivec2 page(glm::floor(tap / float(kVirtualPageTexels)));
            EXPECT_TRUE(page.x >= rect.min.x && page.x < rect.max.x && page.y >= rect.min.y && page.y < rect.max.y);
        }
    }
}

TEST(VirtualClipmap, DepthMappingHoldsTheSceneAndDoesNotFollowTheCamera) {
    const VirtualClipmapConfig config = small_config();
    const VirtualClipmap a = compute_virtual_clipmap(glm::vec3(0.0f, 2.0f, 0.0f), kSun, config, kScene);
    const VirtualClipmap b = compute_virtual_clipmap(glm::vec3(140.0f, 9.0f, -60.0f), kSun, config, kScene);
    for (size_t l = 0; l < a.levels.size(); ++l) {
        EXPECT_EQ(a.levels[l].depth_scale, b.levels[l].depth_scale);
        EXPECT_EQ(a.levels[l].depth_offset, b.levels[l].depth_offset);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p((corner & 1) ? kScene.max.x : kScene.min.x, (corner & 2) ? kScene.max.y : kScene.min.y,
                              (corner & 4) ? kScene.max.z : kScene.min.z);
            const float z = (a.light_view * glm::vec4(p, 1.0f)).z;
            const float depth = z * a.levels[l].depth_scale + a.levels[l].depth_offset;
            EXPECT_GT(depth, 0.0f);
            EXPECT_LT(depth, 1.0f);
        }
    }
    // Reverse-Z: nearer the sun is larger.
    const glm::vec3 low(0.0f), high = low - 10.0f * kSun;
    const float z_low = (a.light_view * glm::vec4(low, 1.0f)).z, z_high = (a.light_view * glm::vec4(high, 1.0f)).z;
    EXPECT_GT(z_high * a.levels[0].depth_scale, z_low * a.levels[0].depth_scale);
}

TEST(VirtualClipmap, ConfigOutOfRangeNamesTheField) {
    const auto message_of = [](VirtualClipmapConfig config) {
        try {
            validate_virtual_clipmap_config(config, "settings");
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(message_of(small_config()), "accepted");
    VirtualClipmapConfig config = small_config();
    config.level_resolution = 3000;
    EXPECT_EQ(message_of(config), "settings: virtual_resolution: 3000 must be a power of two in 1024..16384");
    config = small_config();
    config.level_count = 0;
    EXPECT_EQ(message_of(config), "settings: virtual_levels: 0 is out of range (1..24)");
    config = small_config();
    config.first_level_extent = std::nanf("");
    EXPECT_NE(message_of(config).find("virtual_first_extent"), std::string::npos);
    config = small_config();
    config.lod_bias = 9.0f;
    EXPECT_NE(message_of(config).find("virtual_lod_bias"), std::string::npos);
}

}  // namespace
}  // namespace penumbra
