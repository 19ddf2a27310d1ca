#include "passes/moments_conversion.hpp"

#include <algorithm>
#include <array>
#include <span>

#include "passes/shader_interface.hpp"
#include "passes/shadow_filter_specialization.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

constexpr uint32_t kGroupSize = 8;  // the compute shaders' local size in x and y

bool filters_linearly(const gpu::Device& device, VkFormat format) {
    VkFormatProperties properties{};
    device->vkGetPhysicalDeviceFormatProperties(device.physical_device(), format, &properties);
    return (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
}

// RGBA16_UNORM is written through an R32G32_UINT view (shaders/moments_storage.glsl).
VkFormat storage_format(VkFormat format) {
    return format == VK_FORMAT_R16G16B16A16_UNORM ? VK_FORMAT_R32G32_UINT : VK_FORMAT_UNDEFINED;
}

gpu::Image create_moments_image(const gpu::Device& device, VkFormat format, uint32_t resolution, uint32_t layers) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = layers;
    // Transfer source: a caller (or a test) may read the moments back, as it may the depth.
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.array_view = true;
    desc.storage_view_format = storage_format(format);
    return gpu::create_image(device, desc);
}

// The view the compute shaders write through.
VkImageView storage_view(const gpu::Image& image) {
    return image.storage_view ? image.storage_view.get() : image.view.get();
}

struct VariantShaders {
    std::span<const uint32_t> convert;
    std::span<const uint32_t> blur;
};

VariantShaders variant_shaders(VkFormat format) {
    if (format == VK_FORMAT_R16G16B16A16_UNORM) {
        return {shaders::moments_convert_rgba16_comp(), shaders::moments_blur_rgba16_comp()};
    }
    if (format == VK_FORMAT_R32G32B32A32_SFLOAT) {
        return {shaders::moments_convert_rgba32f_comp(), shaders::moments_blur_rgba32f_comp()};
    }
    return {shaders::moments_convert_rg32f_comp(), shaders::moments_blur_rg32f_comp()};
}

gpu::UniqueDescriptorSetLayout create_set_layout(const gpu::Device& device, VkDescriptorType first) {
    const std::array<VkDescriptorSetLayoutBinding, 2> bindings{{
        {0, first, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    }};
    return gpu::create_descriptor_set_layout(device, bindings);
}

gpu::UniquePipelineLayout create_layout(const gpu::Device& device, VkDescriptorSetLayout set_layout) {
    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(shader::MomentsPushConstants)};
    return gpu::create_pipeline_layout(device, {&set_layout, 1}, {&range, 1});
}

}  // namespace

VkFormat moments_format(const FilterSettings& filter) {
    if (filter.mode == ShadowFilter::Msm) {
        return filter.msm_optimized_quantization ? VK_FORMAT_R16G16B16A16_UNORM : VK_FORMAT_R32G32B32A32_SFLOAT;
    }
    if (filter.mode == ShadowFilter::Evsm && filter.evsm_components == 4) return VK_FORMAT_R32G32B32A32_SFLOAT;
    return VK_FORMAT_R32G32_SFLOAT;
}

MomentsConversion::MomentsConversion(const gpu::Device& device, const gpu::Image& depth_map, VkSampler depth_sampler,
                                     const FilterSettings& filter, bool partial_updates)
    : device_(device),
      blur_radius_(static_cast<uint32_t>(std::max(filter.blur_radius, 0))),
      side_(depth_map.desc.width),
      partial_updates_(partial_updates),
      moments_(create_moments_image(device, moments_format(filter), depth_map.desc.width, depth_map.desc.layers)) {
    const VkFormat format = moments_.desc.format;
    gpu::SamplerDesc sampler;
    sampler.filter = filters_linearly(device, format) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    // Repeat: a toroidal cascade wraps around its layer's edges (filters clamp their taps
    // to the texels a layer uses).
    sampler.address = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    sampler_ = gpu::create_sampler(device, sampler);
    if (blur_radius_ > 0) {
        scratch_.emplace(create_moments_image(device, format, depth_map.desc.width, depth_map.desc.layers));
        // A blurred texel depends on the unblurred moments around it: updating some texels
        // needs the others' unblurred moments, kept here (the blur overwrites moments_).
        if (partial_updates_)
            raw_.emplace(create_moments_image(device, format, depth_map.desc.width, depth_map.desc.layers));
    }
    const gpu::Image& converted = raw_ ? *raw_ : moments_;

    convert_layout_ = create_set_layout(device, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    blur_layout_ = create_set_layout(device, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    const std::array<VkDescriptorPoolSize, 2> sizes{
        {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 5}}};
    pool_ = gpu::create_descriptor_pool(device, 3, sizes);
    convert_set_ = gpu::allocate_descriptor_set(device, pool_, convert_layout_);
    gpu::write_combined_image_sampler(device, convert_set_, 0, depth_map.view, depth_sampler);
    gpu::write_storage_image(device, convert_set_, 1, storage_view(converted));

    const VariantShaders variant = variant_shaders(format);
    const std::vector<gpu::SpecializationValue> constants = shadow_filter_specialization(filter);
    convert_pipeline_layout_ = create_layout(device, convert_layout_);
    convert_ = gpu::create_compute_pipeline(device, {VK_SHADER_STAGE_COMPUTE_BIT, variant.convert, constants},
                                            convert_pipeline_layout_);
    if (!scratch_) return;
    horizontal_set_ = gpu::allocate_descriptor_set(device, pool_, blur_layout_);
    gpu::write_storage_image(device, horizontal_set_, 0, storage_view(converted));
    gpu::write_storage_image(device, horizontal_set_, 1, storage_view(*scratch_));
    vertical_set_ = gpu::allocate_descriptor_set(device, pool_, blur_layout_);
    gpu::write_storage_image(device, vertical_set_, 0, storage_view(*scratch_));
    gpu::write_storage_image(device, vertical_set_, 1, storage_view(moments_));
    blur_pipeline_layout_ = create_layout(device, blur_layout_);
    blur_ =
        gpu::create_compute_pipeline(device, {VK_SHADER_STAGE_COMPUTE_BIT, variant.blur, {}}, blur_pipeline_layout_);
}

uint64_t MomentsConversion::memory_bytes() const {
    return moments_.memory_size + (scratch_ ? scratch_->memory_size : 0u) + (raw_ ? raw_->memory_size : 0u);
}

void MomentsConversion::dispatch_region(VkCommandBuffer cmd, const MomentsLayer& layer, glm::vec2 evsm_exponents,
                                        Step step, const TexelRect& region) const {
    if (region.empty()) return;
    const bool convert = step == Step::Convert;
    const VkPipelineLayout layout = convert ? convert_pipeline_layout_.get() : blur_pipeline_layout_.get();
    const VkDescriptorSet set = convert ? convert_set_ : step == Step::Horizontal ? horizontal_set_ : vertical_set_;
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, convert ? convert_.get() : blur_.get());
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
    const glm::uvec2 first(region.min);
    const glm::uvec2 size(region.max - region.min);
    const shader::MomentsPushConstants constants{
        {layer.layer, layer.resolution, blur_radius_, step == Step::Horizontal ? 1u : 0u},
        {layer.near_plane, layer.far_plane, evsm_exponents.x, evsm_exponents.y},
        {layer.layer_origin.x, layer.layer_origin.y, side_, 0u},
        {first.x, first.y, size.x, size.y}};
    device_->vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    device_->vkCmdDispatch(cmd, (size.x + kGroupSize - 1) / kGroupSize, (size.y + kGroupSize - 1) / kGroupSize, 1);
}

namespace {

// `rects` grown by `grow` texels on each axis, clipped to [0, used)^2.
std::vector<TexelRect> grown(const std::vector<TexelRect>& rects, glm::ivec2 grow, uint32_t used) {
    std::vector<TexelRect> result;
    for (const TexelRect& rect : rects) {
        const TexelRect bigger = intersect({rect.min - grow, rect.max + grow}, whole_map(used));
        if (!bigger.empty()) result.push_back(bigger);
    }
    return result;
}

}  // namespace

// Whole layers, or for a cached cascade the texels its changed depth reaches: a texel's
// unblurred moments read the depth one texel around it (the slope), the horizontal blur
// reads `radius` texels left and right, the vertical one `radius` up and down.
void MomentsConversion::dispatch(VkCommandBuffer cmd, const MomentsLayer& layer, glm::vec2 evsm_exponents,
                                 Step step) const {
    if (!layer.changed) {
        dispatch_region(cmd, layer, evsm_exponents, step, whole_map(layer.resolution));
        return;
    }
    const int radius = static_cast<int>(blur_radius_);
    const glm::ivec2 grow = step == Step::Convert      ? glm::ivec2(1)
                            : step == Step::Horizontal ? glm::ivec2(1 + radius, 1)
                                                       : glm::ivec2(1 + radius);
    for (const TexelRect& region : grown(*layer.changed, grow, layer.resolution))
        dispatch_region(cmd, layer, evsm_exponents, step, region);
}

void MomentsConversion::record(VkCommandBuffer cmd, const std::vector<MomentsLayer>& layers, glm::vec2 evsm_exponents,
                               bool keep_others) const {
    using gpu::ImageState;
    const bool partial =
        std::any_of(layers.begin(), layers.end(), [](const MomentsLayer& layer) { return layer.changed.has_value(); });
    if (partial && !partial_updates_) {
        throw UsageError("MomentsConversion::record: a layer is updated in part without partial_updates");
    }
    // Kept texels (other layers, or a partial layer's unchanged ones) keep their contents.
    const bool keep = keep_others || partial;
    if (keep_others && layers.empty()) return;
    const ImageState before = keep ? ImageState::ShaderSampled : ImageState::DiscardAfterShaderReads;
    gpu::transition(device_, cmd, moments_, before, ImageState::ComputeStorage);
    // The unblurred moments and the horizontal pass are kept between frames too.
    const ImageState kept_storage = keep ? ImageState::ComputeStorage : ImageState::DiscardAfterShaderReads;
    if (raw_) {
        gpu::transition(device_, cmd, *raw_, raw_initialised_ ? kept_storage : ImageState::DiscardAfterShaderReads,
                        ImageState::ComputeStorage);
    }
    for (const MomentsLayer& layer : layers) dispatch(cmd, layer, evsm_exponents, Step::Convert);
    if (scratch_) {
        // Every layer converted before the blur reads it.
        const gpu::Image& converted = raw_ ? *raw_ : moments_;
        gpu::transition(device_, cmd, converted, ImageState::ComputeStorage, ImageState::ComputeStorage);
        gpu::transition(device_, cmd, *scratch_,
                        scratch_initialised_ ? kept_storage : ImageState::DiscardAfterShaderReads,
                        ImageState::ComputeStorage);
        for (const MomentsLayer& layer : layers) dispatch(cmd, layer, evsm_exponents, Step::Horizontal);
        gpu::transition(device_, cmd, *scratch_, ImageState::ComputeStorage, ImageState::ComputeStorage);
        gpu::transition(device_, cmd, moments_, ImageState::ComputeStorage, ImageState::ComputeStorage);
        for (const MomentsLayer& layer : layers) dispatch(cmd, layer, evsm_exponents, Step::Vertical);
        scratch_initialised_ = true;
    }
    raw_initialised_ = raw_.has_value();
    gpu::transition(device_, cmd, moments_, ImageState::ComputeStorage, ImageState::ShaderSampled);
}

}  // namespace penumbra::passes
