#include "passes/shadow_pass.hpp"

#include <algorithm>
#include <string>

#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

void require_multiview(const gpu::Device& device, uint32_t cascade_count) {
    if (device.max_multiview_views() == 0) {
        throw DeviceError(
            "shadow strategy multiview: the device was not created with the multiview feature "
            "(VkPhysicalDeviceVulkan11Features::multiview)");
    }
    if (cascade_count > device.max_multiview_views()) {
        throw InputError("shadow strategy multiview: " + device.info().name + " renders at most " +
                         std::to_string(device.max_multiview_views()) + " views in one pass, not " +
                         std::to_string(cascade_count) + " cascades (use fewer cascades or per-cascade)");
    }
}

uint32_t view_mask_of(ShadowStrategy strategy, uint32_t cascade_count) {
    return strategy == ShadowStrategy::Multiview ? (1u << cascade_count) - 1u : 0u;
}

CasterPipelineTemplate depth_template(const gpu::Device& device, VkPipelineLayout layout, ShadowStrategy strategy,
                                      uint32_t cascade_count) {
    CasterPipelineTemplate pipelines;
    switch (strategy) {
        case ShadowStrategy::Multiview:
            pipelines.opaque_vertex = shaders::caster_multiview_vert();
            pipelines.masked_vertex = shaders::caster_multiview_masked_vert();
            break;
        case ShadowStrategy::Layered:
            pipelines.opaque_vertex = shaders::caster_layered_vert();
            pipelines.masked_vertex = shaders::caster_layered_masked_vert();
            break;
        case ShadowStrategy::PerCascade:
            pipelines.opaque_vertex = shaders::caster_cascade_vert();
            pipelines.masked_vertex = shaders::caster_cascade_masked_vert();
            break;
    }
    pipelines.masked_fragment = shaders::caster_masked_frag();
    pipelines.layout = layout;
    pipelines.depth_bias = true;
    // Casters in front of a cascade's near plane are flattened onto it instead of clipped.
    pipelines.depth_clamp = device.depth_clamp_supported();
    pipelines.view_mask = view_mask_of(strategy, cascade_count);
    return pipelines;
}

}  // namespace

ShadowPass::ShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                       VkDescriptorSetLayout alpha_mask_set_layout, uint32_t resolution, uint32_t cascade_count,
                       ShadowStrategy strategy, bool cached, uint32_t frames_in_flight)
    : device_(device),
      resolution_(resolution),
      cascade_count_(cascade_count),
      strategy_(strategy),
      shadow_map_(create_depth_map(device, resolution, cascade_count,
                                   cached && strategy != ShadowStrategy::Multiview
                                       ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_DST_BIT}
                                       : VkImageUsageFlags{0})),
      gpu_culling_(create_gpu_culling(device, strategy == ShadowStrategy::Layered, frame_set_layout, frames_in_flight)),
      pipeline_layout_(
          create_caster_pipeline_layout(device, frame_set_layout, alpha_mask_set_layout, gpu_culling_.get())),
      pipelines_(device, depth_template(device, pipeline_layout_, strategy, cascade_count)) {
    if (strategy == ShadowStrategy::Multiview) require_multiview(device, cascade_count);
    if (cached && strategy != ShadowStrategy::Multiview) {
        cache_ = std::make_unique<gpu::Image>(
            create_depth_map(device, resolution, cascade_count, VK_IMAGE_USAGE_TRANSFER_DST_BIT));
    }
}

void ShadowPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                        const std::vector<CascadeDraws>& draws, const BiasSettings& bias,
                        const CasterFaceCulling& culling, gpu::GpuTimer* timer, GpuCullOptions gpu_culling) {
    const auto any = [&](auto&& wanted) { return std::any_of(draws.begin(), draws.end(), wanted); };
    // A layer that keeps what the last frame left in it needs the cache, and no discard.
    const bool keep = any([](const CascadeDraws& d) { return d.reuse; });
    if (keep && !cache_) {
        throw UsageError("ShadowPass::record: a cascade reuses a cache this pass does not keep");
    }
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, PENUMBRA_SET_CASTER_FRAME,
                                     1, &frame_set, 0, nullptr);
    const bool layered = strategy_ == ShadowStrategy::Layered;
    if (layered) record_gpu_culling(cmd, frame_set, scene, draws, timer, gpu_culling);
    if (strategy_ == ShadowStrategy::Multiview) {
        gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::DiscardAfterShaderReads,
                        gpu::ImageState::DepthAttachment);
        record_multiview(cmd, scene, draws, bias, culling, timer);
        gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::DepthAttachment, gpu::ImageState::ShaderSampled);
        return;
    }
    gpu::ImageState map_state = keep ? gpu::ImageState::ShaderSampled : gpu::ImageState::DiscardAfterShaderReads;
    if (any([](const CascadeDraws& d) { return !d.restore.empty(); })) {
        gpu::TimedScope scope(device_, timer, cmd, "shadow_cache_restore");
        gpu::transition(device_, cmd, shadow_map_, map_state, gpu::ImageState::TransferDst);
        map_state = gpu::ImageState::TransferDst;
        copy_cache(cmd, draws, true);
    }
    gpu::transition(device_, cmd, shadow_map_, map_state, gpu::ImageState::DepthAttachment);
    if (layered) {
        record_layered_static(cmd, scene, draws, bias, culling, timer);
    } else {
        record_static(cmd, scene, draws, bias, culling, timer);
    }
    map_state = gpu::ImageState::DepthAttachment;
    if (any([](const CascadeDraws& d) { return !d.store.empty(); })) {
        gpu::TimedScope scope(device_, timer, cmd, "shadow_cache_store");
        gpu::transition(device_, cmd, shadow_map_, map_state, gpu::ImageState::TransferSrc);
        map_state = gpu::ImageState::TransferSrc;
        copy_cache(cmd, draws, false);
    }
    if (any([](const CascadeDraws& d) { return !d.dynamic.empty(); })) {
        gpu::transition(device_, cmd, shadow_map_, map_state, gpu::ImageState::DepthAttachment);
        map_state = gpu::ImageState::DepthAttachment;
        if (layered) {
            record_layered_dynamic(cmd, scene, draws, bias, culling, timer);
        } else {
            record_dynamic(cmd, scene, draws, bias, culling, timer);
        }
    }
    gpu::transition(device_, cmd, shadow_map_, map_state, gpu::ImageState::ShaderSampled);
}

void ShadowPass::record_multiview(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                                  const BiasSettings& bias, const CasterFaceCulling& culling,
                                  gpu::GpuTimer* timer) const {
    // One pass renders every layer, so a draw goes in when any cascade needs it (multiview
    // layers are not toroidal: one region per cascade, tile 0).
    DrawList union_list;
    for (const CascadeDraws& cascade : draws) {
        for (const CascadeDraws::Region& region : cascade.regions)
            union_list.insert(union_list.end(), region.casters.begin(), region.casters.end());
    }
    std::sort(union_list.begin(), union_list.end());
    union_list.erase(std::unique(union_list.begin(), union_list.end()), union_list.end());
    gpu::TimedScope scope(device_, timer, cmd, "shadow_multiview");
    begin_rendering(cmd, shadow_map_.view, (1u << cascade_count_) - 1u, bias, VK_ATTACHMENT_LOAD_OP_CLEAR);
    record_caster_draws(device_, cmd, pipelines_, scene, union_list, 0, culling);
    device_->vkCmdEndRendering(cmd);
}

namespace {

// What each tile of each cascade draws (4 cascade + tile; core/shadow_cache.hpp
// layer_pieces): its piece of the window, and the window texels of `draws`' regions in it.
CascadeTiles cascade_tiles(const std::vector<CascadeDraws>& draws, uint32_t cascade_count, uint32_t resolution) {
    CascadeTiles tiles{resolution, std::vector<CullTileRects>(size_t{4} * cascade_count)};
    for (uint32_t c = 0; c < cascade_count && c < draws.size(); ++c) {
        for (const LayerPiece& piece : layer_pieces(whole_map(resolution), draws[c].layer_origin, resolution))
            tiles.tiles[4 * c + piece.tile].piece = piece.window;
        for (const CascadeDraws::Region& region : draws[c].regions)
            tiles.tiles[4 * c + region.tile].rects.push_back(region.window);
    }
    return tiles;
}

}  // namespace

// The layered strategy: the GPU culls every caster against the tiles that draw something
// this frame (its static casters' rectangles, and with a cache the pieces its dynamic
// casters are drawn over); the passes then draw each tile's buckets. Nothing is culled when
// no tile draws.
void ShadowPass::record_gpu_culling(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                                    const std::vector<CascadeDraws>& draws, gpu::GpuTimer* timer,
                                    GpuCullOptions options) {
    const CascadeTiles tiles = cascade_tiles(draws, cascade_count_, resolution_);
    std::vector<bool> enabled(tiles.tiles.size(), false);
    for (uint32_t c = 0; options.casts && c < cascade_count_ && c < draws.size(); ++c) {
        const bool dynamic = cache_ && !draws[c].dynamic.empty();
        for (uint32_t tile = 0; tile < 4; ++tile) {
            const CullTileRects& rects = tiles.tiles[4 * c + tile];
            enabled[4 * c + tile] = !rects.rects.empty() || (dynamic && !rects.piece.empty());
        }
    }
    if (std::find(enabled.begin(), enabled.end(), true) == enabled.end()) return;
    gpu::TimedScope scope(device_, timer, cmd, "shadow_cull");
    gpu_culling_->record_cull(cmd, frame_set, scene, CullLayers::CascadeTiles, enabled, options.cull, options.frame,
                              &tiles);
}

namespace {

VkRect2D to_vk_rect(const TexelRect& rect) {
    return {{rect.min.x, rect.min.y},
            {static_cast<uint32_t>(rect.max.x - rect.min.x), static_cast<uint32_t>(rect.max.y - rect.min.y)}};
}

}  // namespace

// Each region's casters under its scissor (the rasteriser writes only inside it), with
// its tile's offset; a kept layer's regions are cleared first.
void ShadowPass::record_regions(VkCommandBuffer cmd, const CasterScene& scene,
                                const std::vector<CascadeDraws::Region>& regions, uint32_t cascade, bool clear,
                                const CasterFaceCulling& culling) const {
    for (const CascadeDraws::Region& region : regions) {
        const VkRect2D rect = to_vk_rect(region.rect);
        if (clear) {
            const VkClearAttachment attachment{VK_IMAGE_ASPECT_DEPTH_BIT, 0, {.depthStencil = {0.0f, 0}}};
            const VkClearRect clear_rect{rect, 0, 1};
            device_->vkCmdClearAttachments(cmd, 1, &attachment, 1, &clear_rect);
        }
        if (region.casters.empty()) continue;
        device_->vkCmdSetScissor(cmd, 0, 1, &rect);
        record_caster_draws(device_, cmd, pipelines_, scene, region.casters, cascade, culling, region.tile);
    }
}

// Step 2, layered: one pass over every layer. A frame that keeps no layer clears them all;
// else each kept layer's stale rectangles and every other layer are cleared first. Each
// rectangle then draws its tile's culled static casters (every caster without a cache)
// under its own scissor, so that a large caster (a ground) is rasterised only where texels
// are drawn again. A tile's casters are those that meet any of its rectangles: one that
// does not reach a rectangle is clipped there entirely, and the depths a caster writes
// where two rectangles overlap are the same each time (the nearest wins).
void ShadowPass::record_layered_static(VkCommandBuffer cmd, const CasterScene& scene,
                                       const std::vector<CascadeDraws>& draws, const BiasSettings& bias,
                                       const CasterFaceCulling& culling, gpu::GpuTimer* timer) const {
    // Every layer kept whole: nothing to clear or draw.
    const auto untouched = [](const CascadeDraws& d) { return d.reuse && d.regions.empty(); };
    if (!draws.empty() && std::all_of(draws.begin(), draws.end(), untouched)) return;
    const bool keep = std::any_of(draws.begin(), draws.end(), [](const CascadeDraws& d) { return d.reuse; });
    gpu::TimedScope scope(device_, timer, cmd, "shadow_layered");
    begin_rendering(cmd, shadow_map_.view, 0, bias, keep ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR,
                    cascade_count_);
    if (keep) {
        std::vector<VkClearRect> clears;
        for (uint32_t c = 0; c < cascade_count_; ++c) {
            if (c >= draws.size() || !draws[c].reuse) {
                clears.push_back({to_vk_rect(whole_map(resolution_)), c, 1});
                continue;
            }
            for (const CascadeDraws::Region& region : draws[c].regions)
                clears.push_back({to_vk_rect(region.rect), c, 1});
        }
        const VkClearAttachment attachment{VK_IMAGE_ASPECT_DEPTH_BIT, 0, {.depthStencil = {0.0f, 0}}};
        if (!clears.empty()) {
            device_->vkCmdClearAttachments(cmd, 1, &attachment, static_cast<uint32_t>(clears.size()), clears.data());
        }
    }
    const BucketKind kind = cache_ ? BucketKind::Static : BucketKind::All;
    for (uint32_t c = 0; c < cascade_count_ && c < draws.size(); ++c) {
        for (const CascadeDraws::Region& region : draws[c].regions) {
            const VkRect2D scissor = to_vk_rect(region.rect);
            device_->vkCmdSetScissor(cmd, 0, 1, &scissor);
            gpu_culling_->record_draws(cmd, pipelines_, scene, culling, 4 * c + region.tile, kind);
        }
    }
    device_->vkCmdEndRendering(cmd);
}

// Step 4, layered: the dynamic casters over the static ones, each tile of a cascade they
// reach under the scissor of its piece.
void ShadowPass::record_layered_dynamic(VkCommandBuffer cmd, const CasterScene& scene,
                                        const std::vector<CascadeDraws>& draws, const BiasSettings& bias,
                                        const CasterFaceCulling& culling, gpu::GpuTimer* timer) const {
    gpu::TimedScope scope(device_, timer, cmd, "shadow_dynamic");
    begin_rendering(cmd, shadow_map_.view, 0, bias, VK_ATTACHMENT_LOAD_OP_LOAD, cascade_count_);
    for (uint32_t c = 0; c < cascade_count_ && c < draws.size(); ++c) {
        if (draws[c].dynamic.empty()) continue;
        for (const LayerPiece& piece : layer_pieces(whole_map(resolution_), draws[c].layer_origin, resolution_)) {
            const VkRect2D scissor = to_vk_rect(piece.layer);
            device_->vkCmdSetScissor(cmd, 0, 1, &scissor);
            gpu_culling_->record_draws(cmd, pipelines_, scene, culling, 4 * c + piece.tile, BucketKind::Dynamic);
        }
    }
    device_->vkCmdEndRendering(cmd);
}

// Step 2: per layer, everything from a cleared layer, or the stale rectangles of a kept one.
void ShadowPass::record_static(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                               const BiasSettings& bias, const CasterFaceCulling& culling, gpu::GpuTimer* timer) const {
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        const CascadeDraws& layer = draws[cascade];
        if (layer.reuse && layer.regions.empty()) continue;
        gpu::TimedScope scope(device_, timer, cmd, "shadow_cascade_" + std::to_string(cascade));
        begin_rendering(cmd, shadow_map_.layer_views[cascade], 0, bias,
                        layer.reuse ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR);
        record_regions(cmd, scene, layer.regions, cascade, layer.reuse, culling);
        device_->vkCmdEndRendering(cmd);
    }
}

// Steps 1 and 3: the cache's texels into the map (restore), or the map's static casters
// into the cache (store); the two images hold a cascade at the same layer texels.
void ShadowPass::copy_cache(VkCommandBuffer cmd, const std::vector<CascadeDraws>& draws, bool restore) {
    const gpu::ImageState wanted = restore ? gpu::ImageState::TransferSrc : gpu::ImageState::TransferDst;
    gpu::transition(device_, cmd, *cache_, cache_state_, wanted);
    cache_state_ = wanted;
    std::vector<VkImageCopy> regions;
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        for (const TexelRect& rect : restore ? draws[cascade].restore : draws[cascade].store) {
            if (rect.empty()) continue;
            VkImageCopy region{};
            region.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, cascade, 1};
            region.dstSubresource = region.srcSubresource;
            region.srcOffset = {rect.min.x, rect.min.y, 0};
            region.dstOffset = region.srcOffset;
            region.extent = {static_cast<uint32_t>(rect.max.x - rect.min.x),
                             static_cast<uint32_t>(rect.max.y - rect.min.y), 1};
            regions.push_back(region);
        }
    }
    if (regions.empty()) return;
    const VkImage source = restore ? cache_->get() : shadow_map_.get();
    const VkImage destination = restore ? shadow_map_.get() : cache_->get();
    device_->vkCmdCopyImage(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, destination,
                            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, static_cast<uint32_t>(regions.size()),
                            regions.data());
}

// Step 4: the dynamic casters over the static ones, every frame.
void ShadowPass::record_dynamic(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                                const BiasSettings& bias, const CasterFaceCulling& culling,
                                gpu::GpuTimer* timer) const {
    gpu::TimedScope scope(device_, timer, cmd, "shadow_dynamic");
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        if (draws[cascade].dynamic.empty()) continue;
        begin_rendering(cmd, shadow_map_.layer_views[cascade], 0, bias, VK_ATTACHMENT_LOAD_OP_LOAD);
        record_regions(cmd, scene, draws[cascade].dynamic, cascade, false, culling);
        device_->vkCmdEndRendering(cmd);
    }
}

void ShadowPass::begin_rendering(VkCommandBuffer cmd, VkImageView view, uint32_t view_mask, const BiasSettings& bias,
                                 VkAttachmentLoadOp load, uint32_t layers) const {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = load;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: 0 is the far plane (no caster)
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {resolution_, resolution_}};
    info.layerCount = view_mask == 0 ? layers : 0;
    info.viewMask = view_mask;
    info.pDepthAttachment = &depth;
    device_->vkCmdBeginRendering(cmd, &info);
    set_viewport_and_scissor(device_, cmd, resolution_, resolution_);
    set_shadow_depth_bias(device_, cmd, bias);
}

}  // namespace penumbra::passes
