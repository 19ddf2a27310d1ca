#pragma once
// The sun's virtual shadow map pages (core/virtual_clipmap.hpp): the page table of every
// clipmap level, the physical pool's bookkeeping, and the two GPU steps that start a frame
// without any readback:
//   1. marking (shaders/virtual_mark.comp): each pixel of the caller's depth requests the
//      pages its filter reads in the level that matches its footprint;
//   2. allocation (shaders/virtual_pages.comp, two dispatches): requested pages get physical
//      pages (free ones, else the least recently requested), pages that left their level's
//      window or whose casters changed lose their texels, and every page to draw this frame
//      is listed.
// The pool's depth texels themselves belong to the pass that draws and samples them.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/virtual_clipmap.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/one_time_commands.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"

namespace penumbra::passes {

struct VirtualPagesDesc {
    uint32_t level_count = 16;
    uint32_t pages_per_side = 128;  // of each level's window: its virtual resolution / kVirtualPageTexels
    uint32_t pool_pages = 4096;     // physical pages
    uint32_t frames_in_flight = 2;
    // Invalidation rectangles one frame takes; more make the frame invalidate every page.
    uint32_t max_invalidations = 1024;
    // Caster instances drawn into pages one frame holds (VirtualPageDraw, 8 bytes each);
    // draws beyond it are dropped and their pages drawn again the next frame.
    uint32_t max_page_draws = 1u << 22;
};

// Everything the GPU holds about the pages, read back (tests).
struct VirtualPageState {
    std::vector<uint32_t> page_table;  // per level and slot: PENUMBRA_PAGE_* bits and the physical page
    std::vector<uint32_t> requests;    // per level and slot: 1 where a pixel requested the page this frame
    std::vector<shader::VirtualPhysicalPage> physical;
    shader::VirtualCounters counters{};
    std::vector<uint32_t> rendered;  // the entries drawn this frame, finer levels first (counters.rendered of them)
};

// The pool image is a 2D array whose layers hold 4 x 4 pages each (512^2 texels): physical
// page p is page (p % 4, p / 4 % 4) of layer p / 16 (kPenumbraVirtualPoolLayerPages in
// penumbra/glsl/virtual_clipmap.glsl). A caster drawn into a page goes to its layer
// (gl_Layer) and to the viewport and scissor of its place in the layer (gl_ViewportIndex),
// so the rasteriser's guard band and scissor keep it inside the page instead of clip planes
// at the page's edges, which clip every triangle crossing them (docs/PERFORMANCE.md).
// Sixteen viewports is what every device with multiViewport has (maxViewports >= 16).
inline constexpr uint32_t kVirtualPoolLayerPages = 4;
inline constexpr uint32_t kVirtualPagesPerPoolLayer = kVirtualPoolLayerPages * kVirtualPoolLayerPages;

// The most physical pages a pool holds: 1 GiB of D32 in 1,024 layers (maxImageArrayLayers is
// 2,048 on current desktop GPUs; a device with fewer is refused by name).
inline constexpr uint32_t kMaxVirtualPoolPages = 128 * 128;

// Layers of the pool image.
uint32_t virtual_pool_layers(uint32_t pool_pages);

// What the marking needs of the frame's camera and filter, beside the clipmap.
struct VirtualFrameView {
    glm::mat4 camera_view{1.0f};  // world -> view of the prepared camera
    glm::vec3 camera_position{0.0f};
    float footprint_per_metre = 0.0f;  // pixel_footprint_per_metre() of the prepared camera
    float footprint_base = 0.0f;       // metres of pixel footprint at distance 0 (orthographic views)
    float lod_bias = 0.0f;
    float mark_radius_texels = 0.0f;  // the filter's reach, the normal offset and a bilinear tap, in texels
    float shadow_distance = 0.0f;
    uint32_t frame = 0;  // increases by one per frame
};

// The clipmap's uniform block: `clipmap`'s levels, with `previous` (last frame's clipmap, or
// the same one) telling which pages left their window.
shader::PenumbraVirtualClipmap virtual_clipmap_block(const VirtualClipmap& clipmap, const VirtualClipmap& previous,
                                                     const VirtualFrameView& view);

class VirtualPages {
public:
    VirtualPages(const gpu::Device& device, const VirtualPagesDesc& desc);

    const VirtualPagesDesc& desc() const { return desc_; }
    uint32_t entry_count() const { return desc_.level_count * desc_.pages_per_side * desc_.pages_per_side; }

    // Writes frame `frame`'s clipmap and invalidations into its slot (the frame that used
    // the slot before, frames_in_flight earlier, must be complete). More invalidations than
    // the desc's maximum set invalidate_all instead. `cull_workgroups`: the casters'
    // culling dispatch (x, y) of a frame that draws pages (VirtualCounters::cull_groups).
    void prepare(uint64_t frame, shader::PenumbraVirtualClipmap clipmap,
                 std::span<const shader::VirtualInvalidation> invalidations, glm::uvec2 cull_workgroups = {0, 0});

    // Records the frame's marking from the caller's depth (in `depth_layout`, its writes
    // visible to compute shaders) and then the allocation. Afterwards the page table, the
    // list of pages to draw and the counters (with the culling's and the clear's indirect
    // commands) are visible to compute, vertex, fragment and indirect reads.
    void record(VkCommandBuffer cmd, uint64_t frame, VkImageView depth, VkImageLayout depth_layout,
                const shader::VirtualMarkPushConstants& screen) {
        record_marking(cmd, frame, depth, depth_layout, screen);
        record_allocation(cmd, frame);
    }
    // The two halves of record(), for timing them apart.
    void record_marking(VkCommandBuffer cmd, uint64_t frame, VkImageView depth, VkImageLayout depth_layout,
                        const shader::VirtualMarkPushConstants& screen);
    void record_allocation(VkCommandBuffer cmd, uint64_t frame);

    // Copies the counters for the host (counters(frame)); after the frame's last pass that
    // counts (the casters' culling).
    void copy_counters(VkCommandBuffer cmd, uint64_t frame);
    // The copy alone, for a caller that has made the counters' compute writes visible to
    // copies and records the transfer-to-host barrier after it.
    void record_counters_copy(VkCommandBuffer cmd, uint64_t frame);

    // The counters of `frame`, once its commands completed; nullopt when its slot was reused
    // (after frames in flight + 1 frames) or nothing was recorded for it.
    std::optional<shader::VirtualCounters> counters(uint64_t frame) const;

    // Copies the whole state to the host (a one-time submission; tests).
    VirtualPageState read_back(const gpu::OneTimeCommands& commands) const;

    // Set PENUMBRA_SET_VIRTUAL_PAGES of the casters' pipelines and set 0 of their culling,
    // for `frame` (after prepare()).
    VkDescriptorSetLayout pages_set_layout() const { return pages_set_layout_; }
    VkDescriptorSet pages_set(uint64_t frame) const { return slots_[frame % slots_.size()].pages_set; }
    VkBuffer page_table() const { return page_table_.get(); }
    // The PenumbraVirtualClipmap uniform buffer of `frame` (the sampling set binds it).
    VkBuffer clipmap_buffer(uint64_t frame) const { return slots_[frame % slots_.size()].clipmap.get(); }
    VkBuffer rendered_entries() const { return render_list_.get(); }
    // Holds the indirect commands the allocation writes: VirtualCounters::cull_groups and
    // level_clears (one draw per level, desc().level_count of them).
    VkBuffer counters_buffer() const { return counters_.get(); }
    uint64_t buffer_bytes() const;

private:
    struct FrameSlot {
        gpu::Buffer clipmap;        // PenumbraVirtualClipmap (host-visible)
        gpu::Buffer invalidations;  // VirtualInvalidation[max_invalidations] (host-visible)
        VkDescriptorSet pages_set = VK_NULL_HANDLE;
        VkDescriptorSet depth_set = VK_NULL_HANDLE;
        gpu::Buffer statistics;  // the counters copied for the host
        uint64_t frame = ~uint64_t{0};
        glm::uvec2 cull_workgroups{0, 0};
    };

    void record_clear(VkCommandBuffer cmd);
    uint32_t first_page_thread() const;
    void push_step(VkCommandBuffer cmd, const FrameSlot& slot, uint32_t step) const;
    void write_pages_set(FrameSlot& slot) const;

    const gpu::Device& device_;
    VirtualPagesDesc desc_;
    gpu::UniqueDescriptorSetLayout pages_set_layout_;
    gpu::UniqueDescriptorSetLayout depth_set_layout_;
    gpu::UniquePipelineLayout mark_layout_;
    gpu::UniquePipelineLayout pages_layout_;
    gpu::UniquePipeline mark_pipeline_;
    gpu::UniquePipeline pages_pipeline_;
    gpu::UniqueSampler nearest_;
    gpu::UniqueDescriptorPool pool_;
    gpu::Buffer page_table_;
    gpu::Buffer requests_;
    gpu::Buffer physical_;
    gpu::Buffer counters_;
    gpu::Buffer needs_;
    gpu::Buffer free_list_;
    gpu::Buffer render_list_;
    gpu::Buffer page_draws_;
    // One per frame in flight and one more: a frame's statistics stay readable until the
    // frames in flight after it have been prepared.
    std::vector<FrameSlot> slots_;
    bool initialised_ = false;    // the page table, requests and physical pages cleared on the GPU
    uint32_t request_stamp_ = 0;  // of the last prepared frame (read_back())
};

}  // namespace penumbra::passes
