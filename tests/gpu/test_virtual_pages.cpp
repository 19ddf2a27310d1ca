// The virtual shadow map's page marking and allocation on the GPU (passes/virtual_pages.*,
// shaders/virtual_mark.comp and virtual_pages.comp), against the clipmap's CPU math
// (core/virtual_clipmap.hpp): a depth buffer of a ground plane seen at a slant requests the
// pages the CPU selects for the same pixels; every requested page gets its own physical
// page; a second frame of the same view draws nothing; a pool too small leaves pages
// unserved and never shares one; pages that leave a moving window are freed while the rest
// keep their texels; the least recently requested pages are evicted first; invalidated
// pages are drawn again. Run on the device with validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <vector>

#include "core/camera_math.hpp"
#include "core/virtual_clipmap.hpp"
#include "passes/virtual_pages.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/resources.hpp"
#include "renderer/app_context.hpp"

namespace penumbra::testing {
namespace {

constexpr uint32_t kWidth = 96;
constexpr uint32_t kHeight = 64;
constexpr float kFov = 1.0f;
constexpr float kRadius = 3.0f;  // texels a receiver's filter reads around it
constexpr float kShadowDistance = 60.0f;
const glm::vec3 kSun = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
const core::Aabb kScene{glm::vec3(-200.0f, -1.0f, -200.0f), glm::vec3(200.0f, 10.0f, 200.0f)};

VirtualClipmapConfig test_config() {
    VirtualClipmapConfig config;
    config.level_resolution = 2048;  // 16 pages per side
    config.level_count = 10;
    config.first_level_extent = 2.0f;
    return config;
}

// A camera at `eye` looking at `target`, and the reverse-Z depth of the ground plane y = 0
// at each pixel centre (0, the background, where the pixel sees sky or lies beyond 200 m).
struct GroundView {
    CameraView camera;
    std::vector<float> depth;
};

GroundView ground_view(glm::vec3 eye, glm::vec3 target) {
    GroundView view;
    view.camera = make_camera_view(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)), kFov,
                                   float(kWidth) / float(kHeight), 0.1f, 200.0f);
    const glm::mat4 inverse = glm::inverse(view.camera.view_projection);
    view.depth.assign(size_t{kWidth} * kHeight, 0.0f);
    for (uint32_t y = 0; y < kHeight; ++y) {
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / glm::vec2(kWidth, kHeight) * 2.0f - 1.0f;
            const glm::vec4 near_point = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::vec4 far_point = inverse * glm::vec4(ndc, 0.5f, 1.0f);
            const glm::vec3 origin = glm::vec3(near_point) / near_point.w;
            const glm::vec3 direction = glm::vec3(far_point) / far_point.w - origin;
            if (direction.y >= 0.0f) continue;
            const glm::vec3 hit = origin - direction * (origin.y / direction.y);
            const glm::vec4 clip = view.camera.view_projection * glm::vec4(hit, 1.0f);
            view.depth[size_t{y} * kWidth + x] = std::max(clip.z / clip.w, 0.0f);
        }
    }
    return view;
}

// The entries the CPU's math requests for the view's pixels (the marking pass's steps).
std::set<uint32_t> cpu_requests(const GroundView& view, const VirtualClipmap& clipmap) {
    const glm::mat4 inverse = glm::inverse(view.camera.view_projection);
    const float per_metre = pixel_footprint_per_metre(kFov, kHeight);
    const uint32_t per_level = clipmap.pages_per_side * clipmap.pages_per_side;
    std::set<uint32_t> entries;
    for (uint32_t y = 0; y < kHeight; ++y) {
        for (uint32_t x = 0; x < kWidth; ++x) {
            const float depth = view.depth[size_t{y} * kWidth + x];
            if (depth == 0.0f) continue;
            const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / glm::vec2(kWidth, kHeight) * 2.0f - 1.0f;
            const glm::vec4 world = inverse * glm::vec4(ndc, depth, 1.0f);
            const glm::vec3 position = glm::vec3(world) / world.w;
            if (-(view.camera.view * glm::vec4(position, 1.0f)).z > kShadowDistance) continue;
            const int level = select_virtual_level(clipmap, view.camera.eye, per_metre, 0.0f, position, kRadius);
            if (level < 0) continue;
            // The pixel's level, and the next coarser one (its fallback).
            const int last = std::min(level + 1, static_cast<int>(clipmap.levels.size()) - 1);
            for (int l = level; l <= last; ++l) {
                const PageRect rect = pages_around(clipmap, virtual_texel_of(clipmap, l, position), kRadius);
                for (int py = rect.min.y; py < rect.max.y; ++py) {
                    for (int px = rect.min.x; px < rect.max.x; ++px) {
                        entries.insert(uint32_t(l) * per_level + page_table_slot(clipmap, l, glm::ivec2(px, py)));
                    }
                }
            }
        }
    }
    return entries;
}

class VirtualPages : public ::testing::Test {
protected:
    VirtualPages() : context_(validating()) {
        gpu::ImageDesc desc;
        desc.format = VK_FORMAT_D32_SFLOAT;
        desc.width = kWidth;
        desc.height = kHeight;
        desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
        depth_ = gpu::create_image(context_, desc);
        staging_ = gpu::create_buffer(context_, sizeof(float) * kWidth * kHeight, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                      gpu::MemoryKind::HostUpload);
    }

    ~VirtualPages() override {
        EXPECT_TRUE(options_.validation_log->messages.empty()) << options_.validation_log->messages.front();
    }

    static VulkanContextOptions validating() {
        VulkanContextOptions options;
        options.validation = true;
        return options;
    }

    passes::VirtualPagesDesc pages_desc(uint32_t pool_pages) const {
        passes::VirtualPagesDesc desc;
        desc.level_count = test_config().level_count;
        desc.pages_per_side = test_config().level_resolution / kVirtualPageTexels;
        desc.pool_pages = pool_pages;
        return desc;
    }

    // One frame: marking from the view's depth and the allocation; returns the GPU's state.
    passes::VirtualPageState run_frame(passes::VirtualPages& pages, const GroundView& view,
                                       const VirtualClipmap& clipmap, const VirtualClipmap& previous,
                                       const std::vector<shader::VirtualInvalidation>& invalidations = {},
                                       bool invalidate_all = false) {
        frame_ += 1;
        passes::VirtualFrameView frame_view;
        frame_view.camera_view = view.camera.view;
        frame_view.camera_position = view.camera.eye;
        frame_view.footprint_per_metre = pixel_footprint_per_metre(kFov, kHeight);
        frame_view.mark_radius_texels = kRadius;
        frame_view.shadow_distance = kShadowDistance;
        frame_view.frame = static_cast<uint32_t>(frame_);
        shader::PenumbraVirtualClipmap block = passes::virtual_clipmap_block(clipmap, previous, frame_view);
        block.invalidate_all = invalidate_all ? 1u : 0u;
        pages.prepare(frame_, block, invalidations);
        std::memcpy(staging_.mapped, view.depth.data(), view.depth.size() * sizeof(float));
        shader::VirtualMarkPushConstants screen{};
        screen.inverse_view_projection = glm::inverse(view.camera.view_projection);
        screen.width = kWidth;
        screen.height = kHeight;
        screen.background_depth = 0.0f;
        context_.submit_and_wait([&](VkCommandBuffer cmd) {
            gpu::transition(context_, cmd, depth_, gpu::ImageState::Undefined, gpu::ImageState::TransferDst);
            const VkBufferImageCopy region{
                0, 0, 0, {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1}, {0, 0, 0}, {kWidth, kHeight, 1}};
            context_->vkCmdCopyBufferToImage(cmd, staging_.get(), depth_.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                             &region);
            gpu::transition(context_, cmd, depth_, gpu::ImageState::TransferDst, gpu::ImageState::ShaderSampled);
            pages.record(cmd, frame_, depth_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, screen);
            pages.copy_counters(cmd, frame_);
        });
        return pages.read_back(context_.one_time());
    }

    VulkanContextOptions options_;
    renderer::AppContext context_;
    gpu::Image depth_;
    gpu::Buffer staging_;
    uint64_t frame_ = 0;
};

std::set<uint32_t> requested_entries(const passes::VirtualPageState& state) {
    std::set<uint32_t> entries;
    for (uint32_t e = 0; e < state.requests.size(); ++e) {
        if (state.requests[e] != 0) entries.insert(e);
    }
    return entries;
}

bool allocated(uint32_t value) { return (value & PENUMBRA_PAGE_ALLOCATED) != 0; }
uint32_t physical_of(uint32_t value) { return value & PENUMBRA_PAGE_PHYSICAL_MASK; }

// The list of pages drawn this frame holds each of them once, each in its level's part (as
// the casters' culling reads it), and each level's clear draw covers its part: 6 vertices a
// page, instances from the level's first place on.
void expect_render_list_grouped_by_level(const passes::VirtualPageState& state) {
    const uint32_t per_level = static_cast<uint32_t>(state.page_table.size()) / test_config().level_count;
    const auto pool_pages = static_cast<uint32_t>(state.physical.size());
    ASSERT_EQ(state.rendered.size(), state.counters.rendered);
    EXPECT_EQ(std::set<uint32_t>(state.rendered.begin(), state.rendered.end()).size(), state.rendered.size());
    uint32_t first = 0;
    for (uint32_t level = 0; level < PENUMBRA_MAX_VIRTUAL_LEVELS; ++level) {
        const shader::VirtualClearDraw& clear = state.counters.level_clears[level];
        const uint32_t count = clear.instance_count;
        if (level < test_config().level_count) {
            EXPECT_EQ(clear.vertex_count, 6u) << "level " << level;
            EXPECT_EQ(clear.first_instance, level * pool_pages) << "level " << level;
        } else {
            EXPECT_EQ(count, 0u) << "level " << level;
        }
        for (uint32_t i = first; i < first + count && i < state.rendered.size(); ++i) {
            EXPECT_EQ(state.rendered[i] / per_level, level) << "list position " << i;
            EXPECT_NE(state.page_table[state.rendered[i]] & PENUMBRA_PAGE_RENDER, 0u) << "entry " << state.rendered[i];
        }
        first += count;
    }
    EXPECT_EQ(first, state.counters.rendered);
}

// Every allocated entry holds its own physical page, and that page names it as its owner.
void expect_consistent(const passes::VirtualPageState& state) {
    std::set<uint32_t> pages;
    uint32_t resident = 0;
    for (uint32_t e = 0; e < state.page_table.size(); ++e) {
        if (!allocated(state.page_table[e])) {
            EXPECT_EQ(state.page_table[e], 0u) << "entry " << e << " holds bits without a page";
            continue;
        }
        const uint32_t page = physical_of(state.page_table[e]);
        ASSERT_LT(page, state.physical.size());
        EXPECT_TRUE(pages.insert(page).second) << "physical page " << page << " held twice";
        EXPECT_EQ(state.physical[page].owner, e);
        ++resident;
    }
    for (uint32_t p = 0; p < state.physical.size(); ++p) {
        if (state.physical[p].owner != PENUMBRA_PAGE_NO_OWNER) {
            EXPECT_TRUE(pages.count(p)) << "orphan page " << p;
        }
    }
    EXPECT_EQ(state.counters.resident, resident);
    expect_render_list_grouped_by_level(state);
}

TEST_F(VirtualPages, MarkingRequestsThePagesTheCpuSelects) {
    passes::VirtualPages pages(context_, pages_desc(4096));
    const GroundView view = ground_view(glm::vec3(3.0f, 4.0f, 2.0f), glm::vec3(10.0f, 0.0f, -30.0f));
    const VirtualClipmap clipmap = compute_virtual_clipmap(view.camera.eye, kSun, test_config(), kScene);
    const passes::VirtualPageState state = run_frame(pages, view, clipmap, clipmap);
    const std::set<uint32_t> expected = cpu_requests(view, clipmap);
    const std::set<uint32_t> gpu = requested_entries(state);
    std::vector<uint32_t> differing;
    std::set_symmetric_difference(expected.begin(), expected.end(), gpu.begin(), gpu.end(),
                                  std::back_inserter(differing));
    // The GPU's float rounding may put a pixel on the other side of a level or page edge.
    EXPECT_LE(differing.size(), std::max<size_t>(2, expected.size() / 100))
        << differing.size() << " of " << expected.size() << " entries differ";
    std::set<uint32_t> levels;
    for (const uint32_t entry : gpu) levels.insert(entry / (16 * 16));
    EXPECT_GE(levels.size(), 4u) << "a slanted ground plane spans several levels";
    EXPECT_EQ(state.counters.requested, gpu.size());
    // The first frame draws every requested page into a page of its own.
    EXPECT_EQ(state.counters.rendered, gpu.size());
    EXPECT_EQ(state.counters.cached, 0u);
    EXPECT_EQ(state.counters.unserved, 0u);
    EXPECT_EQ(std::set<uint32_t>(state.rendered.begin(), state.rendered.end()), gpu);
    for (const uint32_t entry : gpu) EXPECT_TRUE(allocated(state.page_table[entry]));
    expect_consistent(state);
    const std::optional<shader::VirtualCounters> host = pages.counters(frame_);
    ASSERT_TRUE(host.has_value());
    EXPECT_EQ(host->requested, state.counters.requested);
    EXPECT_EQ(host->rendered, state.counters.rendered);
}

TEST_F(VirtualPages, ASecondFrameOfTheSameViewDrawsNothing) {
    passes::VirtualPages pages(context_, pages_desc(4096));
    const GroundView view = ground_view(glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(-5.0f, 0.0f, -20.0f));
    const VirtualClipmap clipmap = compute_virtual_clipmap(view.camera.eye, kSun, test_config(), kScene);
    const passes::VirtualPageState first = run_frame(pages, view, clipmap, clipmap);
    const passes::VirtualPageState second = run_frame(pages, view, clipmap, clipmap);
    EXPECT_GT(first.counters.rendered, 5u);
    EXPECT_EQ(second.counters.rendered, 0u);
    EXPECT_EQ(second.counters.cached, first.counters.requested);
    // The same pages hold the same entries; only last frame's drawing flag is gone.
    std::vector<uint32_t> drawn_then = first.page_table;
    for (uint32_t& value : drawn_then) value &= ~PENUMBRA_PAGE_RENDER;
    EXPECT_EQ(second.page_table, drawn_then);
    for (const uint32_t entry : second.rendered) ADD_FAILURE() << "entry " << entry << " drawn again";
    expect_consistent(second);
}

TEST_F(VirtualPages, APoolTooSmallLeavesPagesUnservedAndNeverSharesOne) {
    constexpr uint32_t kPool = 4;  // the view requests 9 pages
    passes::VirtualPages pages(context_, pages_desc(kPool));
    const GroundView view = ground_view(glm::vec3(0.0f, 3.0f, 0.0f), glm::vec3(8.0f, 0.0f, -25.0f));
    const VirtualClipmap clipmap = compute_virtual_clipmap(view.camera.eye, kSun, test_config(), kScene);
    for (int frame = 0; frame < 2; ++frame) {
        const passes::VirtualPageState state = run_frame(pages, view, clipmap, clipmap);
        const std::set<uint32_t> requested = requested_entries(state);
        ASSERT_GT(requested.size(), kPool);
        EXPECT_EQ(state.counters.resident, kPool);
        EXPECT_EQ(state.counters.unserved, requested.size() - kPool) << "frame " << frame;
        EXPECT_EQ(state.counters.evicted, 0u) << "requested pages are never evicted for other requested ones";
        uint32_t served = 0, finest_served = ~0u, coarsest_unserved = 0;
        for (const uint32_t entry : requested) {
            const uint32_t level = entry / (16 * 16);
            if (allocated(state.page_table[entry])) {
                ++served;
                finest_served = std::min(finest_served, level);
            } else {
                coarsest_unserved = std::max(coarsest_unserved, level);
            }
        }
        EXPECT_EQ(served, kPool);
        // Coarser levels are served first: they are the unserved pages' fallback.
        EXPECT_GE(finest_served, coarsest_unserved) << "frame " << frame;
        expect_consistent(state);
    }
}

// Entries keyed by what they hold: (level, world page).
std::map<std::pair<uint32_t, glm::ivec2>, uint32_t,
         bool (*)(const std::pair<uint32_t, glm::ivec2>&, const std::pair<uint32_t, glm::ivec2>&)>
entries_by_world_page(const passes::VirtualPageState& state, const VirtualClipmap& clipmap, bool requested_only) {
    const auto less = [](const std::pair<uint32_t, glm::ivec2>& a, const std::pair<uint32_t, glm::ivec2>& b) {
        return std::tie(a.first, a.second.x, a.second.y) < std::tie(b.first, b.second.x, b.second.y);
    };
    std::map<std::pair<uint32_t, glm::ivec2>, uint32_t,
             bool (*)(const std::pair<uint32_t, glm::ivec2>&, const std::pair<uint32_t, glm::ivec2>&)>
        result(less);
    const uint32_t per_level = clipmap.pages_per_side * clipmap.pages_per_side;
    for (uint32_t e = 0; e < state.page_table.size(); ++e) {
        if (!allocated(state.page_table[e]) || (requested_only && state.requests[e] == 0)) continue;
        const uint32_t level = e / per_level;
        const glm::ivec2 page =
            world_page_of_slot(clipmap.levels[level].first_page, clipmap.pages_per_side, e % per_level);
        result[{level, page}] = e;
    }
    return result;
}

TEST_F(VirtualPages, PagesThatLeaveAMovingWindowAreFreedAndTheRestKeepTheirTexels) {
    passes::VirtualPages pages(context_, pages_desc(4096));
    const glm::vec3 start(0.0f, 3.0f, 0.0f), step(1.3f, 0.0f, -0.9f);
    GroundView view = ground_view(start, start + glm::vec3(4.0f, -3.0f, -20.0f));
    VirtualClipmap previous = compute_virtual_clipmap(view.camera.eye, kSun, test_config(), kScene);
    passes::VirtualPageState before = run_frame(pages, view, previous, previous);
    int moved_windows = 0;
    for (int frame = 1; frame <= 4; ++frame) {
        const glm::vec3 eye = start + step * float(frame);
        view = ground_view(eye, eye + glm::vec3(4.0f, -3.0f, -20.0f));
        const VirtualClipmap clipmap = compute_virtual_clipmap(eye, kSun, test_config(), kScene);
        const passes::VirtualPageState after = run_frame(pages, view, clipmap, previous);
        expect_consistent(after);
        const auto held_before = entries_by_world_page(before, previous, false);
        const auto requested_after = entries_by_world_page(after, clipmap, true);
        const std::set<uint32_t> rendered(after.rendered.begin(), after.rendered.end());
        uint32_t kept = 0;
        for (const auto& [key, entry] : requested_after) {
            const auto found = held_before.find(key);
            const bool still_in_window = found != held_before.end() && found->second == entry;
            if (still_in_window) {
                // The same world page in the same slot: its physical page and texels stay.
                EXPECT_EQ(physical_of(after.page_table[entry]), physical_of(before.page_table[entry]));
                EXPECT_FALSE(rendered.count(entry)) << "frame " << frame << " redrew a kept page";
                ++kept;
            } else {
                EXPECT_TRUE(rendered.count(entry)) << "frame " << frame << " did not draw a new page";
            }
        }
        EXPECT_GT(kept, 0u);
        // No entry holds a world page outside its level's window (toroidal slots).
        for (size_t l = 0; l < clipmap.levels.size(); ++l) {
            if (clipmap.levels[l].first_page != previous.levels[l].first_page) ++moved_windows;
        }
        previous = clipmap;
        before = after;
    }
    EXPECT_GT(moved_windows, 0) << "the camera moved the finest windows by whole pages";
}

TEST_F(VirtualPages, TheLeastRecentlyRequestedPagesAreEvictedFirst) {
    // One camera position (the windows stay), three directions: A, then C, then B.
    const glm::vec3 eye(0.0f, 2.5f, 0.0f);
    const GroundView a = ground_view(eye, eye + glm::vec3(0.0f, -2.0f, -15.0f));
    const GroundView c = ground_view(eye, eye + glm::vec3(15.0f, -2.0f, 0.0f));
    const GroundView b = ground_view(eye, eye + glm::vec3(0.0f, -2.0f, 15.0f));
    const VirtualClipmap clipmap = compute_virtual_clipmap(eye, kSun, test_config(), kScene);
    const std::set<uint32_t> set_a = cpu_requests(a, clipmap), set_c = cpu_requests(c, clipmap),
                             set_b = cpu_requests(b, clipmap);
    std::set<uint32_t> a_or_c = set_a;
    a_or_c.insert(set_c.begin(), set_c.end());
    passes::VirtualPages pages(context_, pages_desc(static_cast<uint32_t>(a_or_c.size())));
    const passes::VirtualPageState after_a = run_frame(pages, a, clipmap, clipmap);
    const passes::VirtualPageState after_c = run_frame(pages, c, clipmap, clipmap);
    const std::set<uint32_t> gpu_a = requested_entries(after_a), gpu_c = requested_entries(after_c);
    ASSERT_EQ(after_c.counters.unserved, 0u) << "the pool holds A and C";
    const passes::VirtualPageState after_b = run_frame(pages, b, clipmap, clipmap);
    const std::set<uint32_t> gpu_b = requested_entries(after_b);
    expect_consistent(after_b);
    uint32_t new_in_b = 0, only_in_a = 0;
    for (const uint32_t entry : gpu_b) new_in_b += (gpu_a.count(entry) || gpu_c.count(entry)) ? 0 : 1;
    for (const uint32_t entry : gpu_a) only_in_a += (gpu_c.count(entry) || gpu_b.count(entry)) ? 0 : 1;
    ASSERT_GT(new_in_b, 0u);
    ASSERT_LE(new_in_b, only_in_a) << "the test needs A's pages alone to make room for B";
    EXPECT_EQ(after_b.counters.evicted, new_in_b);
    EXPECT_EQ(after_b.counters.unserved, 0u);
    // C was requested more recently than A: every page of C stays.
    for (const uint32_t entry : gpu_c) EXPECT_TRUE(allocated(after_b.page_table[entry])) << "entry " << entry;
}

TEST_F(VirtualPages, InvalidatedPagesAreDrawnAgainAndUnrequestedOnesAreFreed) {
    passes::VirtualPages pages(context_, pages_desc(4096));
    const glm::vec3 eye(0.0f, 2.0f, 0.0f);
    const GroundView north = ground_view(eye, eye + glm::vec3(0.0f, -2.0f, -15.0f));
    const GroundView south = ground_view(eye, eye + glm::vec3(0.0f, -2.0f, 15.0f));
    const VirtualClipmap clipmap = compute_virtual_clipmap(eye, kSun, test_config(), kScene);
    run_frame(pages, south, clipmap, clipmap);
    const passes::VirtualPageState first = run_frame(pages, north, clipmap, clipmap);
    // A long box under the camera changed, reaching pages of both views in every level.
    const core::Aabb changed{glm::vec3(-1.0f, 0.0f, -9.0f), glm::vec3(1.0f, 2.0f, 9.0f)};
    std::vector<shader::VirtualInvalidation> invalidations;
    std::set<uint32_t> inside;
    const uint32_t per_level = clipmap.pages_per_side * clipmap.pages_per_side;
    for (int level = 0; level < static_cast<int>(clipmap.levels.size()); ++level) {
        const PageRect rect = world_pages_of_box(clipmap, level, changed);
        invalidations.push_back({glm::ivec4(rect.min, rect.max), uint32_t(level), 0, 0, 0});
        for (uint32_t e = level * per_level; e < (level + 1) * per_level; ++e) {
            const glm::ivec2 page =
                world_page_of_slot(clipmap.levels[level].first_page, clipmap.pages_per_side, e % per_level);
            if (glm::all(glm::greaterThanEqual(page, rect.min)) && glm::all(glm::lessThan(page, rect.max))) {
                inside.insert(e);
            }
        }
    }
    const passes::VirtualPageState second = run_frame(pages, north, clipmap, clipmap, invalidations);
    expect_consistent(second);
    const std::set<uint32_t> requested = requested_entries(second);
    std::set<uint32_t> expected_rendered;
    for (const uint32_t entry : requested) {
        if (inside.count(entry)) expected_rendered.insert(entry);
    }
    ASSERT_FALSE(expected_rendered.empty());
    EXPECT_EQ(std::set<uint32_t>(second.rendered.begin(), second.rendered.end()), expected_rendered);
    EXPECT_EQ(second.counters.cached, requested.size() - expected_rendered.size());
    uint32_t freed = 0;
    for (const uint32_t entry : inside) {
        if (requested.count(entry)) continue;
        if (allocated(first.page_table[entry])) ++freed;
        EXPECT_FALSE(allocated(second.page_table[entry])) << "a stale unrequested page stays allocated";
    }
    EXPECT_GT(freed, 0u) << "the south view's pages inside the box are stale and unrequested";

    // Invalidating everything (a new sun direction) draws every requested page again.
    const passes::VirtualPageState third = run_frame(pages, north, clipmap, clipmap, {}, true);
    EXPECT_EQ(third.counters.rendered, third.counters.requested);
    EXPECT_EQ(third.counters.cached, 0u);
}

}  // namespace
}  // namespace penumbra::testing
