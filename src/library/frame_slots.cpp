#include "library/frame_slots.hpp"

#include <array>
#include <cstring>

#include "penumbra/gpu/barriers.hpp"

#include "passes/shader_interface.hpp"

namespace penumbra::library {
namespace {

// Scopes a frame can open: per view one per cascade (or the virtual map's four) and the
// resolve, the local lights, and room.
constexpr uint32_t kMaxTimedScopes = 8 * kMaxViews + 8;

}  // namespace

FrameSetLayouts create_frame_set_layouts(const gpu::Device& device) {
    // The caller may read the maps from any stage of its own pipelines.
    constexpr VkShaderStageFlags kAll = VK_SHADER_STAGE_ALL;
    const std::array<VkDescriptorSetLayoutBinding, 12> sampling{{
        {PENUMBRA_BINDING_SHADOW_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_CASCADE_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_CASCADE_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_CASCADE_MOMENTS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_LOCAL_SHADOWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_LOCAL_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_LOCAL_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_LOCAL_MOMENTS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_VIRTUAL_CLIPMAP_BLOCK, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_VIRTUAL_POOL, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
        {PENUMBRA_BINDING_VIRTUAL_POOL_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kAll, nullptr},
    }};
    const std::array<VkDescriptorSetLayoutBinding, 2> caster{{
        // Compute: the layered strategy's culling tests casters against the cascades and the
        // local lights' layers.
        {PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    }};
    return {gpu::create_descriptor_set_layout(device, sampling), gpu::create_descriptor_set_layout(device, caster)};
}

FrameSlots::FrameSlots(const gpu::Device& device, uint32_t count) : device_(device) {
    // Hardware depth comparison with bilinear filtering. Repeat: a toroidal cascade wraps
    // around its layer's edges, and the filters clamp every tap to the texels a cascade or
    // a local light uses (a border colour would also be wrong: lavapipe (Mesa 22.3)
    // returns it for in-range taps of linear-compare array lookups).
    gpu::SamplerDesc comparison;
    comparison.filter = VK_FILTER_LINEAR;
    comparison.address = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    comparison.compare = true;
    comparison.compare_op = VK_COMPARE_OP_GREATER_OR_EQUAL;
    comparison_sampler_ = gpu::create_sampler(device, comparison);
    // Raw depth for the blocker search: point sampling, so a blocker's depth is a real
    // caster depth rather than a blend with the background.
    gpu::SamplerDesc raw;
    raw.filter = VK_FILTER_NEAREST;
    raw.address = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    raw_depth_sampler_ = gpu::create_sampler(device, raw);
    // The virtual pool's pages are read texel by texel (penumbra/glsl/virtual.glsl); its
    // comparison binding is there for shaders that compare within one page.
    gpu::SamplerDesc pool_comparison = comparison;
    pool_comparison.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    pool_comparison_sampler_ = gpu::create_sampler(device, pool_comparison);
    placeholder_.clipmap = gpu::create_buffer(device, sizeof(shader::PenumbraVirtualClipmap),
                                              VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryKind::HostUpload);
    std::memset(placeholder_.clipmap.mapped, 0, sizeof(shader::PenumbraVirtualClipmap));
    placeholder_.page_table =
        gpu::create_buffer(device, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::HostUpload);
    std::memset(placeholder_.page_table.mapped, 0, 16);
    gpu::ImageDesc pool;
    pool.format = VK_FORMAT_D32_SFLOAT;
    pool.width = pool.height = 16;
    pool.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    pool.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    pool.array_view = true;  // the pool's bindings are 2D arrays
    placeholder_.pool = gpu::create_image(device, pool);

    slots_.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        slots_.push_back({gpu::create_buffer(device, sizeof(shader::PenumbraLocalShadows),
                                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::HostUpload),
                          gpu::GpuTimer(device, kMaxTimedScopes)});
    }
}

uint64_t FrameSlots::buffer_bytes() const {
    uint64_t bytes = 0;
    for (const FrameSlot& slot : slots_) bytes += slot.local_shadows.size;
    return bytes;
}

ViewSlots::ViewSlots(const gpu::Device& device, const FrameSlots& frames, const FrameSetLayouts& layouts,
                     VkDescriptorSetLayout screen_set_layout) {
    const uint32_t count = frames.count();
    const std::array<VkDescriptorPoolSize, 4> sizes{{{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 3 * count},
                                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3 * count},
                                                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 11 * count},
                                                     {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, count}}};
    pool_ = gpu::create_descriptor_pool(device, 3 * count, sizes);
    slots_.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        ViewSlot slot{gpu::create_buffer(device, sizeof(shader::PenumbraShadowUniforms),
                                         VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryKind::HostUpload),
                      gpu::allocate_descriptor_set(device, pool_, layouts.sampling),
                      gpu::allocate_descriptor_set(device, pool_, layouts.caster),
                      gpu::allocate_descriptor_set(device, pool_, screen_set_layout)};
        const gpu::Buffer& local_shadows = frames.at(i).local_shadows;
        gpu::write_uniform_buffer(device, slot.sampling_set, PENUMBRA_BINDING_SHADOW_UNIFORMS,
                                  slot.shadow_uniforms.get(), slot.shadow_uniforms.size);
        gpu::write_storage_buffer(device, slot.sampling_set, PENUMBRA_BINDING_LOCAL_SHADOWS, local_shadows.get(),
                                  local_shadows.size);
        gpu::write_uniform_buffer(device, slot.caster_set, PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS,
                                  slot.shadow_uniforms.get(), slot.shadow_uniforms.size);
        gpu::write_storage_buffer(device, slot.caster_set, PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS, local_shadows.get(),
                                  local_shadows.size);
        slots_.push_back(std::move(slot));
    }
}

uint64_t ViewSlots::buffer_bytes() const {
    uint64_t bytes = 0;
    for (const ViewSlot& slot : slots_) bytes += slot.shadow_uniforms.size;
    return bytes;
}

void FrameSlots::record_placeholder_layout(VkCommandBuffer cmd) {
    if (placeholder_.ready) return;
    // Never sampled (no level reads it), but given defined contents all the same: an image
    // made readable from UNDEFINED is a mistake elsewhere (the best-practices layer says so).
    gpu::record_depth_clear_to_sampled(device_, cmd, placeholder_.pool, 0.0f);  // reverse-Z: far
    placeholder_.ready = true;
}

void FrameSlots::write_sampling_set(VkDescriptorSet set, const SampledMaps& cascades, const SampledMaps& local,
                                    const std::optional<SampledVirtual>& virtual_map) const {
    const SampledVirtual bound =
        virtual_map.value_or(SampledVirtual{placeholder_.clipmap.get(), placeholder_.page_table.get(),
                                            placeholder_.page_table.size, placeholder_.pool.view});
    gpu::write_uniform_buffer(device_, set, PENUMBRA_BINDING_VIRTUAL_CLIPMAP_BLOCK, bound.clipmap,
                              sizeof(shader::PenumbraVirtualClipmap));
    gpu::write_storage_buffer(device_, set, PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE_BUFFER, bound.page_table,
                              bound.page_table_bytes);
    gpu::write_combined_image_sampler(device_, set, PENUMBRA_BINDING_VIRTUAL_POOL, bound.pool,
                                      pool_comparison_sampler_);
    gpu::write_combined_image_sampler(device_, set, PENUMBRA_BINDING_VIRTUAL_POOL_DEPTH, bound.pool,
                                      raw_depth_sampler_);
    const auto write_maps = [&](const SampledMaps& maps, uint32_t comparison, uint32_t raw, uint32_t moments) {
        const VkImageView depth = maps.depth->view;
        gpu::write_combined_image_sampler(device_, set, comparison, depth, comparison_sampler_);
        gpu::write_combined_image_sampler(device_, set, raw, depth, raw_depth_sampler_);
        // Without moments the binding still needs a valid image: the depth, which the
        // comparison filters never read through it.
        if (maps.moments) {
            gpu::write_combined_image_sampler(device_, set, moments, maps.moments->view, maps.moments_sampler);
        } else {
            gpu::write_combined_image_sampler(device_, set, moments, depth, raw_depth_sampler_);
        }
    };
    write_maps(cascades, PENUMBRA_BINDING_CASCADE_MAP, PENUMBRA_BINDING_CASCADE_DEPTH,
               PENUMBRA_BINDING_CASCADE_MOMENTS);
    write_maps(local, PENUMBRA_BINDING_LOCAL_MAP, PENUMBRA_BINDING_LOCAL_DEPTH, PENUMBRA_BINDING_LOCAL_MOMENTS);
}

}  // namespace penumbra::library
