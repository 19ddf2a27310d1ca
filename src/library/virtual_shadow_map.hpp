#pragma once
// The sun's virtual shadow map of a ShadowSystem (Settings::shadow.technique = virtual):
// the clipmap placed around the camera each frame (core/virtual_clipmap.hpp), what
// invalidates cached pages (static casters that changed, dynamic casters, a new light
// direction or depth range, settings), the page bookkeeping and its passes
// (passes/virtual_pages.hpp, passes/virtual_shadow_pass.hpp), and what FrameInfo reports.
//
// A frame: prepare() on the CPU, then record_marking() from the caller's depth, then
// record_pages() (allocation already ran in the marking's commands; this culls, clears and
// draws the pages to draw), then sampling through the descriptor set's virtual bindings.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/camera_math.hpp"
#include "core/virtual_clipmap.hpp"
#include "passes/casters.hpp"
#include "passes/virtual_pages.hpp"
#include "passes/virtual_shadow_pass.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/timestamps.hpp"
#include "penumbra/settings.hpp"
#include "penumbra/shadow_system.hpp"

namespace penumbra::library {

// The clipmap's configuration from the settings.
VirtualClipmapConfig virtual_clipmap_config(const VirtualShadowSettings& settings);

// Texels a receiver's filter reads around it, its normal offset included: the pages the
// marking requests around each pixel.
float virtual_mark_radius_texels(const ShadowSettings& settings);

// What prepare() needs of the frame besides the settings.
struct VirtualFrameInputs {
    uint64_t frame = 0;
    const CameraView* camera = nullptr;
    float footprint_per_metre = 0.0f;  // pixel_footprint_per_metre() of the caller's view
    float footprint_base = 0.0f;       // metres of pixel footprint at distance 0 (orthographic views)
    float shadow_distance = 0.0f;
    glm::vec3 light_direction{0.0f, -1.0f, 0.0f};
    float sun_angular_diameter_degrees = 0.0f;
    bool casts = false;  // the sun casts shadows this frame
    const passes::CasterScene* scene = nullptr;
    std::span<const core::Aabb> static_changes;  // world bounds of static casters changed since the last frame drawn
    core::Aabb depth_range_bounds;               // the static instances' (Geometry::depth_range_bounds)
};

class VirtualShadowMap {
public:
    VirtualShadowMap(const gpu::Device& device, VkDescriptorSetLayout caster_frame_layout,
                     VkDescriptorSetLayout alpha_mask_layout, const ShadowSettings& settings,
                     uint32_t frames_in_flight);

    void prepare_pipelines(const passes::VertexFormats& formats) { pass_.prepare_pipelines(formats); }

    // Every page's texels are stale from the next frame on (a setting that changes depths).
    void invalidate() { invalidate_all_ = true; }

    // The frame's clipmap, invalidations and uniform block (written into the frame's slot).
    void prepare(const VirtualFrameInputs& inputs, const ShadowSettings& settings);

    // Marking and allocation from the caller's depth (ScreenInputs' depth and projection).
    void record_marking(VkCommandBuffer cmd, uint64_t frame, const ScreenInputs& screen, gpu::GpuTimer* timer);

    // Culls, clears and draws the frame's pages; copies the counters for the host.
    void record_pages(VkCommandBuffer cmd, VkDescriptorSet caster_frame_set, const passes::CasterScene& scene,
                      uint64_t frame, const BiasSettings& bias, const passes::CasterFaceCulling& culling,
                      gpu::GpuTimer* timer);

    // The sampling set's virtual bindings for `frame`.
    VkBuffer clipmap_buffer(uint64_t frame) const { return pages_.clipmap_buffer(frame); }
    VkBuffer page_table() const { return pages_.page_table(); }
    VkDeviceSize page_table_bytes() const { return VkDeviceSize{pages_.entry_count()} * sizeof(uint32_t); }
    const gpu::Image& pool() const { return pass_.pool(); }

    // FrameInfo::virtual_map of `frame`, with the GPU's counters of `counted_frame` (a
    // frame known complete) when they are still there.
    VirtualShadowInfo info(uint64_t counted_frame) const;
    uint64_t pool_bytes() const { return pass_.memory_bytes(); }
    uint64_t buffer_bytes() const { return pages_.buffer_bytes() + pass_.buffer_bytes(); }

private:
    std::vector<shader::VirtualInvalidation> invalidations(const VirtualFrameInputs& inputs) const;

    const gpu::Device& device_;
    VirtualClipmapConfig config_;
    passes::VirtualPages pages_;
    passes::VirtualShadowPass pass_;
    std::optional<VirtualClipmap> previous_;  // the last prepared frame's clipmap
    VirtualClipmap clipmap_;
    std::vector<core::Aabb> dynamic_bounds_;  // the dynamic casters' bounds last frame (their pages are stale now)
    bool invalidate_all_ = true;
    bool casts_ = false;
    uint32_t invalidation_count_ = 0;
    bool invalidated_all_ = false;
    // The culling's workgroups for the scene of version culled_version_ (counted again only
    // when the scene changes).
    glm::uvec2 cull_workgroups_{0, 0};
    uint64_t culled_version_ = ~uint64_t{0};
};

}  // namespace penumbra::library
