#include "passes/virtual_pages.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/debug_names.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

constexpr uint32_t kMarkGroupSize = 8;        // local_size_x and _y of virtual_mark.comp
constexpr uint32_t kMarkPixelsPerThread = 2;  // kPixelsPerThread of virtual_mark.comp, per axis
constexpr uint32_t kMarkGroupPixels = kMarkGroupSize * kMarkPixelsPerThread;
constexpr uint32_t kPagesGroupSize = 64;  // local_size_x of virtual_pages.comp

constexpr VkShaderStageFlags kCompute = VK_SHADER_STAGE_COMPUTE_BIT;

// Set 0 of both passes, in binding order (PENUMBRA_BINDING_VIRTUAL_*).
constexpr std::array<VkDescriptorType, 10> kPagesBindingTypes{
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
static_assert(PENUMBRA_BINDING_VIRTUAL_DRAWS + 1 == kPagesBindingTypes.size());

// The casters' vertex shaders read the clipmap, the table and their page draws too.
gpu::UniqueDescriptorSetLayout create_pages_set_layout(const gpu::Device& device) {
    std::array<VkDescriptorSetLayoutBinding, kPagesBindingTypes.size()> bindings{};
    for (uint32_t b = 0; b < bindings.size(); ++b) {
        bindings[b] = {b, kPagesBindingTypes[b], 1, kCompute | VK_SHADER_STAGE_VERTEX_BIT, nullptr};
    }
    return gpu::create_descriptor_set_layout(device, bindings);
}

gpu::UniqueDescriptorSetLayout create_depth_set_layout(const gpu::Device& device) {
    const VkDescriptorSetLayoutBinding binding{PENUMBRA_BINDING_VIRTUAL_DEPTH,
                                               VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kCompute, nullptr};
    return gpu::create_descriptor_set_layout(device, {&binding, 1});
}

void check_desc(const VirtualPagesDesc& desc) {
    const auto reject = [](const std::string& problem) { throw InputError("VirtualPages: " + problem); };
    if (desc.level_count < 1 || desc.level_count > PENUMBRA_MAX_VIRTUAL_LEVELS) reject("level_count out of range");
    if (desc.pages_per_side < 2 || desc.pages_per_side % 2 != 0) reject("pages_per_side must be even and >= 2");
    if (desc.pool_pages < 1 || desc.pool_pages > kMaxVirtualPoolPages) reject("pool_pages out of range");
    if (desc.frames_in_flight < 1) reject("frames_in_flight must be >= 1");
    if (desc.max_page_draws < 1) reject("max_page_draws must be >= 1");
}

// Every access of the pages' buffers, for the barriers between the steps and frames.
constexpr VkPipelineStageFlags2 kShaderStages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                                VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                                VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

// From one step to the next, which reads and writes the buffers and whose dispatch
// command the previous one wrote.
void compute_to_indirect_compute(const gpu::Device& device, VkCommandBuffer cmd) {
    gpu::memory_barrier(device, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                            VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

}  // namespace

uint32_t virtual_pool_layers(uint32_t pool_pages) {
    return (pool_pages + kVirtualPagesPerPoolLayer - 1) / kVirtualPagesPerPoolLayer;
}

shader::PenumbraVirtualClipmap virtual_clipmap_block(const VirtualClipmap& clipmap, const VirtualClipmap& previous,
                                                     const VirtualFrameView& view) {
    shader::PenumbraVirtualClipmap block{};
    block.light_view = clipmap.light_view;
    block.camera_view = view.camera_view;
    block.camera_position = glm::vec4(view.camera_position, view.footprint_per_metre);
    block.footprint_base = view.footprint_base;
    block.level_count = static_cast<uint32_t>(clipmap.levels.size());
    block.pages_per_side = clipmap.pages_per_side;
    block.frame = view.frame;
    block.lod_scale = std::exp2(view.lod_bias);
    block.mark_radius_texels = view.mark_radius_texels;
    block.shadow_distance = view.shadow_distance;
    for (size_t l = 0; l < clipmap.levels.size() && l < PENUMBRA_MAX_VIRTUAL_LEVELS; ++l) {
        const VirtualLevel& level = clipmap.levels[l];
        shader::PenumbraVirtualLevel& out = block.levels[l];
        out.first_page = level.first_page;
        // A level the previous clipmap lacked held nothing.
        out.previous_first_page = l < previous.levels.size() ? previous.levels[l].first_page : level.first_page;
        out.texels_per_metre = level.texels_per_metre;
        out.texel_world_size = level.texel_world_size;
        out.depth_scale = level.depth_scale;
        out.depth_offset = level.depth_offset;
    }
    return block;
}

VirtualPages::VirtualPages(const gpu::Device& device, const VirtualPagesDesc& desc)
    : device_(device),
      desc_((check_desc(desc), desc)),
      pages_set_layout_(create_pages_set_layout(device)),
      depth_set_layout_(create_depth_set_layout(device)) {
    const VkPushConstantRange mark_range{kCompute, 0, sizeof(shader::VirtualMarkPushConstants)};
    const std::array<VkDescriptorSetLayout, 2> mark_sets{pages_set_layout_, depth_set_layout_};
    mark_layout_ = gpu::create_pipeline_layout(device, mark_sets, {&mark_range, 1});
    const VkPushConstantRange step_range{kCompute, 0, sizeof(shader::VirtualStepPushConstants)};
    const VkDescriptorSetLayout pages_set = pages_set_layout_;
    pages_layout_ = gpu::create_pipeline_layout(device, {&pages_set, 1}, {&step_range, 1});
    mark_pipeline_ = gpu::create_compute_pipeline(
        device, {VK_SHADER_STAGE_COMPUTE_BIT, shaders::virtual_mark_comp(), {}}, mark_layout_);
    pages_pipeline_ = gpu::create_compute_pipeline(
        device, {VK_SHADER_STAGE_COMPUTE_BIT, shaders::virtual_pages_comp(), {}}, pages_layout_);
    gpu::SamplerDesc sampler;
    sampler.filter = VK_FILTER_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    nearest_ = gpu::create_sampler(device, sampler);

    constexpr VkBufferUsageFlags kStorage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    const auto create = [&](VkDeviceSize bytes, VkBufferUsageFlags usage = 0) {
        return gpu::create_buffer(device, bytes, kStorage | usage, gpu::MemoryKind::DeviceLocal);
    };
    const VkDeviceSize entries = entry_count();
    page_table_ = create(entries * sizeof(uint32_t));
    requests_ = create(entries * sizeof(uint32_t));
    physical_ = create(VkDeviceSize{desc_.pool_pages} * sizeof(shader::VirtualPhysicalPage));
    counters_ = create(sizeof(shader::VirtualCounters), VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    needs_ = create(entries * sizeof(uint32_t));
    free_list_ = create(VkDeviceSize{desc_.pool_pages} * sizeof(uint32_t));
    // A level's part of the list has room for the whole pool: no level draws more pages.
    render_list_ = create(VkDeviceSize{desc_.level_count} * desc_.pool_pages * sizeof(uint32_t));
    page_draws_ = create(VkDeviceSize{desc_.max_page_draws} * sizeof(shader::VirtualPageDraw));

    const uint32_t slot_count = desc_.frames_in_flight + 1;
    const std::array<VkDescriptorPoolSize, 3> sizes{{
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, slot_count},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, slot_count * static_cast<uint32_t>(kPagesBindingTypes.size() - 1)},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, slot_count},
    }};
    pool_ = gpu::create_descriptor_pool(device, 2 * slot_count, sizes);
    slots_.resize(slot_count);
    for (FrameSlot& slot : slots_) {
        slot.clipmap = gpu::create_buffer(device, sizeof(shader::PenumbraVirtualClipmap),
                                          VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryKind::HostUpload);
        slot.invalidations =
            gpu::create_buffer(device, VkDeviceSize{desc_.max_invalidations + 1} * sizeof(shader::VirtualInvalidation),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::HostUpload);
        slot.statistics = gpu::create_buffer(device, sizeof(shader::VirtualCounters), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                             gpu::MemoryKind::HostReadback);
        slot.pages_set = gpu::allocate_descriptor_set(device, pool_, pages_set_layout_);
        slot.depth_set = gpu::allocate_descriptor_set(device, pool_, depth_set_layout_);
        write_pages_set(slot);
    }
}

void VirtualPages::write_pages_set(FrameSlot& slot) const {
    gpu::write_uniform_buffer(device_, slot.pages_set, PENUMBRA_BINDING_VIRTUAL_CLIPMAP, slot.clipmap.get(),
                              slot.clipmap.size);
    const std::array<std::pair<uint32_t, const gpu::Buffer*>, 9> storage{{
        {PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE, &page_table_},
        {PENUMBRA_BINDING_VIRTUAL_REQUESTS, &requests_},
        {PENUMBRA_BINDING_VIRTUAL_PHYSICAL, &physical_},
        {PENUMBRA_BINDING_VIRTUAL_COUNTERS, &counters_},
        {PENUMBRA_BINDING_VIRTUAL_NEEDS, &needs_},
        {PENUMBRA_BINDING_VIRTUAL_FREE, &free_list_},
        {PENUMBRA_BINDING_VIRTUAL_RENDER, &render_list_},
        {PENUMBRA_BINDING_VIRTUAL_INVALIDATIONS, &slot.invalidations},
        {PENUMBRA_BINDING_VIRTUAL_DRAWS, &page_draws_},
    }};
    for (const auto& [binding, buffer] : storage) {
        gpu::write_storage_buffer(device_, slot.pages_set, binding, buffer->get(), buffer->size);
    }
}

void VirtualPages::prepare(uint64_t frame, shader::PenumbraVirtualClipmap clipmap,
                           std::span<const shader::VirtualInvalidation> invalidations, glm::uvec2 cull_workgroups) {
    FrameSlot& slot = slots_[frame % slots_.size()];
    slot.cull_workgroups = cull_workgroups;
    request_stamp_ = PENUMBRA_VIRTUAL_REQUEST_STAMP(clipmap.frame);
    clipmap.pool_pages = desc_.pool_pages;
    clipmap.level_count = std::min(clipmap.level_count, desc_.level_count);
    clipmap.pages_per_side = desc_.pages_per_side;
    if (invalidations.size() > desc_.max_invalidations) {
        clipmap.invalidate_all = 1u;
        clipmap.invalidation_count = 0u;
    } else {
        clipmap.invalidation_count = static_cast<uint32_t>(invalidations.size());
        // An empty span may hold a null pointer, which memcpy may not be given.
        if (!invalidations.empty()) {
            std::memcpy(slot.invalidations.mapped, invalidations.data(), invalidations.size_bytes());
        }
    }
    std::memcpy(slot.clipmap.mapped, &clipmap, sizeof(clipmap));
}

void VirtualPages::record_clear(VkCommandBuffer cmd) {
    // The previous frame's passes read and wrote what this one clears and rewrites.
    gpu::memory_barrier(
        device_, cmd, kShaderStages | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
            VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
        VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    // The marking does not touch the counters: the barrier after it makes their clearing
    // visible to the allocation. The render budget and the last frame's page draws stay (0 at
    // first: every page drawn).
    const VkDeviceSize per_frame = initialised_ ? offsetof(shader::VirtualCounters, render_budget) : VK_WHOLE_SIZE;
    device_->vkCmdFillBuffer(cmd, counters_.get(), 0, per_frame, 0u);
    if (!initialised_) {
        // No entry holds a page or was ever requested (no frame's stamp is 0), and no page
        // has an owner. Later frames leave the requests alone: each frame has its own stamp.
        device_->vkCmdFillBuffer(cmd, page_table_.get(), 0, VK_WHOLE_SIZE, 0u);
        device_->vkCmdFillBuffer(cmd, requests_.get(), 0, VK_WHOLE_SIZE, 0u);
        device_->vkCmdFillBuffer(cmd, physical_.get(), 0, VK_WHOLE_SIZE, PENUMBRA_PAGE_NO_OWNER);
        initialised_ = true;
        // vkCmdFillBuffer is a transfer write of the copy stage.
        gpu::memory_barrier(device_, cmd, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
}

// The scan's threads: one per page table entry (whole workgroups), then one per physical page.
uint32_t VirtualPages::first_page_thread() const {
    return (entry_count() + kPagesGroupSize - 1) / kPagesGroupSize * kPagesGroupSize;
}

void VirtualPages::push_step(VkCommandBuffer cmd, const FrameSlot& slot, uint32_t step) const {
    shader::VirtualStepPushConstants constants{};
    constants.step = step;
    constants.first_page_thread = first_page_thread();
    constants.cull_columns = slot.cull_workgroups.x;
    constants.cull_rows = slot.cull_workgroups.y;
    constants.draw_capacity = desc_.max_page_draws;
    device_->vkCmdPushConstants(cmd, pages_layout_, kCompute, 0, sizeof(constants), &constants);
}

void VirtualPages::record_marking(VkCommandBuffer cmd, uint64_t frame, VkImageView depth, VkImageLayout depth_layout,
                                  const shader::VirtualMarkPushConstants& screen) {
    FrameSlot& slot = slots_[frame % slots_.size()];
    gpu::write_combined_image_sampler(device_, slot.depth_set, PENUMBRA_BINDING_VIRTUAL_DEPTH, depth, nearest_,
                                      depth_layout);
    record_clear(cmd);

    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mark_pipeline_);
    const std::array<VkDescriptorSet, 2> mark_sets{slot.pages_set, slot.depth_set};
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mark_layout_, 0, 2, mark_sets.data(), 0,
                                     nullptr);
    device_->vkCmdPushConstants(cmd, mark_layout_, kCompute, 0, sizeof(screen), &screen);
    device_->vkCmdDispatch(cmd, (screen.width + kMarkGroupPixels - 1) / kMarkGroupPixels,
                           (screen.height + kMarkGroupPixels - 1) / kMarkGroupPixels, 1);
    // The requests, and the counters' clearing, to the allocation.
    gpu::memory_barrier(
        device_, cmd,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void VirtualPages::record_allocation(VkCommandBuffer cmd, uint64_t frame) {
    const FrameSlot& slot = slots_[frame % slots_.size()];
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pages_pipeline_);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pages_layout_, 0, 1, &slot.pages_set, 0,
                                     nullptr);
    push_step(cmd, slot, PENUMBRA_VIRTUAL_STEP_SCAN);
    device_->vkCmdDispatch(cmd, (first_page_thread() + desc_.pool_pages + kPagesGroupSize - 1) / kPagesGroupSize, 1, 1);
    compute_to_indirect_compute(device_, cmd);
    // The workgroups the scan's plan wrote: none when no page is assigned.
    push_step(cmd, slot, PENUMBRA_VIRTUAL_STEP_ASSIGN);
    device_->vkCmdDispatchIndirect(cmd, counters_.get(), offsetof(shader::VirtualCounters, assign_groups));

    // The frame's passes read the table and the list (the casters' culling writes the
    // counters and may invalidate pages).
    gpu::memory_barrier(device_, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        kShaderStages | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                            VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

void VirtualPages::copy_counters(VkCommandBuffer cmd, uint64_t frame) {
    gpu::memory_barrier(device_, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    record_counters_copy(cmd, frame);
    gpu::transfer_to_host_barrier(device_, cmd);
}

void VirtualPages::record_counters_copy(VkCommandBuffer cmd, uint64_t frame) {
    FrameSlot& slot = slots_[frame % slots_.size()];
    const VkBufferCopy region{0, 0, sizeof(shader::VirtualCounters)};
    device_->vkCmdCopyBuffer(cmd, counters_.get(), slot.statistics.get(), 1, &region);
    slot.frame = frame;
}

std::optional<shader::VirtualCounters> VirtualPages::counters(uint64_t frame) const {
    const FrameSlot& slot = slots_[frame % slots_.size()];
    if (slot.frame != frame) return std::nullopt;
    shader::VirtualCounters counters{};
    std::memcpy(&counters, slot.statistics.mapped, sizeof(counters));
    return counters;
}

VirtualPageState VirtualPages::read_back(const gpu::OneTimeCommands& commands) const {
    const gpu::ObjectNames names(device_, "virtual page readback");
    const std::array<const gpu::Buffer*, 5> sources{&page_table_, &requests_, &physical_, &counters_, &render_list_};
    VkDeviceSize total = 0;
    for (const gpu::Buffer* source : sources) total += source->size;
    const gpu::Buffer readback =
        gpu::create_buffer(device_, total, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryKind::HostReadback);
    commands.submit_and_wait([&](VkCommandBuffer cmd) {
        VkDeviceSize offset = 0;
        for (const gpu::Buffer* source : sources) {
            const VkBufferCopy region{0, offset, source->size};
            device_->vkCmdCopyBuffer(cmd, source->get(), readback.get(), 1, &region);
            offset += source->size;
        }
        gpu::transfer_to_host_barrier(device_, cmd);
    });
    const auto* bytes = static_cast<const std::byte*>(readback.mapped);
    const auto take = [&bytes](auto& out, size_t count) {
        out.resize(count);
        std::memcpy(out.data(), bytes, count * sizeof(out[0]));
        bytes += count * sizeof(out[0]);
    };
    VirtualPageState state;
    take(state.page_table, entry_count());
    take(state.requests, entry_count());
    for (uint32_t& request : state.requests) request = request == request_stamp_ ? 1u : 0u;
    take(state.physical, desc_.pool_pages);
    std::memcpy(&state.counters, bytes, sizeof(state.counters));
    bytes += counters_.size;
    // Each level's part of the list, finer levels first.
    std::vector<uint32_t> list;
    take(list, render_list_.size / sizeof(uint32_t));
    for (uint32_t level = 0; level < desc_.level_count; ++level) {
        const auto first = list.begin() + ptrdiff_t{level} * desc_.pool_pages;
        const uint32_t count = std::min(state.counters.level_clears[level].instance_count, desc_.pool_pages);
        state.rendered.insert(state.rendered.end(), first, first + count);
    }
    return state;
}

uint64_t VirtualPages::buffer_bytes() const {
    uint64_t bytes = 0;
    for (const gpu::Buffer* buffer :
         {&page_table_, &requests_, &physical_, &counters_, &needs_, &free_list_, &render_list_, &page_draws_}) {
        bytes += buffer->size;
    }
    for (const FrameSlot& slot : slots_) bytes += slot.clipmap.size + slot.invalidations.size + slot.statistics.size;
    return bytes;
}

}  // namespace penumbra::passes
