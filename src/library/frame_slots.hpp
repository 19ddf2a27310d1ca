#pragma once
// The per-frame resources of a ShadowSystem, one set per frame in flight: the uniform
// buffers prepare() writes, the descriptor sets the caller and the passes bind, and the
// timestamp queries. Slot `frame % frames_in_flight` is reused once its last frame has
// completed (the caller's guarantee). What the frame's views share (the local lights'
// block, the timer) is a FrameSlot; what each view has of its own (its sun's uniforms and
// the sets that bind them) a ViewSlot.
#include <cstdint>
#include <optional>
#include <vector>

#include "library/shadow_maps.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/timestamps.hpp"

namespace penumbra::library {

struct FrameSlot {
    gpu::Buffer local_shadows;  // PenumbraLocalShadows
    gpu::GpuTimer timer;
    uint64_t frame = 0;          // the frame that last used the slot
    bool timer_started = false;  // the frame's first recording call began the timer
    bool shadow_maps_recorded = false;
};

// One view's part of a frame slot.
struct ViewSlot {
    gpu::Buffer shadow_uniforms;                    // PenumbraShadowUniforms: the view's camera and sun
    VkDescriptorSet sampling_set = VK_NULL_HANDLE;  // the caller's (penumbra/shadow.glsl) and the resolve's set 0
    VkDescriptorSet caster_set = VK_NULL_HANDLE;    // set 0 of the caster passes
    VkDescriptorSet screen_set = VK_NULL_HANDLE;    // set 1 of the resolve
    bool pages_marked = false;                      // record_page_marking() ran (the virtual shadow map)
    bool visibility_recorded = false;
};

// The descriptor set layouts every slot's sets use.
struct FrameSetLayouts {
    gpu::UniqueDescriptorSetLayout sampling;
    gpu::UniqueDescriptorSetLayout caster;
};

FrameSetLayouts create_frame_set_layouts(const gpu::Device& device);

// The virtual shadow map as the sampling set binds it: the frame's clipmap block, the page
// table and the pool.
struct SampledVirtual {
    VkBuffer clipmap = VK_NULL_HANDLE;
    VkBuffer page_table = VK_NULL_HANDLE;
    VkDeviceSize page_table_bytes = 0;
    VkImageView pool = VK_NULL_HANDLE;
};

class FrameSlots {
public:
    FrameSlots(const gpu::Device& device, uint32_t count);

    FrameSlot& at(uint64_t frame) { return slots_[frame % slots_.size()]; }
    const FrameSlot& at(uint64_t frame) const { return slots_[frame % slots_.size()]; }
    uint32_t count() const { return static_cast<uint32_t>(slots_.size()); }
    uint64_t buffer_bytes() const;

    // Points the slot's sampling set at the current maps (rewritten every frame: maps are
    // replaced as local lights come and go, and the slot's last frame is complete).
    // `virtual_map`: nullopt with the cascades (the bindings get placeholders whose clipmap has
    // no level, which the shaders read as "no virtual map").
    void write_sampling_set(VkDescriptorSet set, const SampledMaps& cascades, const SampledMaps& local,
                            const std::optional<SampledVirtual>& virtual_map) const;

    // The placeholder pool's first layout transition (once, in the first recorded frame).
    void record_placeholder_layout(VkCommandBuffer cmd);

private:
    struct VirtualPlaceholder {
        gpu::Buffer clipmap;     // a PenumbraVirtualClipmap of zeros: level_count 0
        gpu::Buffer page_table;  // one entry, unallocated
        gpu::Image pool;         // one page
        bool ready = false;      // in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
    };

    const gpu::Device& device_;
    gpu::UniqueSampler comparison_sampler_;
    gpu::UniqueSampler raw_depth_sampler_;
    gpu::UniqueSampler pool_comparison_sampler_;  // the virtual pool: clamp, no array
    VirtualPlaceholder placeholder_;
    std::vector<FrameSlot> slots_;
};

// A view's slots, one per frame slot, from a descriptor pool of the view's own (views come
// and go with the frames). Their sets bind the view's uniforms and the frame slot's local
// lights' block.
class ViewSlots {
public:
    ViewSlots(const gpu::Device& device, const FrameSlots& frames, const FrameSetLayouts& layouts,
              VkDescriptorSetLayout screen_set_layout);

    ViewSlot& at(uint64_t frame) { return slots_[frame % slots_.size()]; }
    const ViewSlot& at(uint64_t frame) const { return slots_[frame % slots_.size()]; }
    uint64_t buffer_bytes() const;

private:
    gpu::UniqueDescriptorPool pool_;
    std::vector<ViewSlot> slots_;
};

}  // namespace penumbra::library
