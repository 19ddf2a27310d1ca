#include "core/shadow_cache.hpp"

#include "core/local_lights.hpp"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// Map texel coordinates of clip-space x, y in [-1, 1] (the viewport covers the map).
glm::vec2 clip_to_texels(float x, float y, uint32_t resolution) {
    const float size = static_cast<float>(resolution);
    return {(x * 0.5f + 0.5f) * size, (y * 0.5f + 0.5f) * size};
}

bool same_mapping_but_translation(const Cascade& a, const Cascade& b) {
    return a.view == b.view && a.texels_per_metre == b.texels_per_metre && a.depth_scale == b.depth_scale &&
           a.depth_offset == b.depth_offset;
}

}  // namespace

TexelRect intersect(const TexelRect& a, const TexelRect& b) {
    TexelRect result{glm::max(a.min, b.min), glm::min(a.max, b.max)};
    return result.empty() ? TexelRect{} : result;
}

TexelRect whole_map(uint32_t resolution) { return {glm::ivec2(0), glm::ivec2(static_cast<int32_t>(resolution))}; }

void place_in_layers(CascadeSet& set, uint32_t resolution, bool toroidal) {
    const int64_t side = static_cast<int64_t>(resolution);
    for (Cascade& cascade : set.cascades) {
        if (!toroidal) {
            cascade.layer_origin = glm::ivec2(0);
            continue;
        }
        // The origin is a whole number; one beyond +-2^62 texels (a scene near the float
        // range) is placed at 0, as no int64 holds it.
        const auto wrap = [&](float origin) {
            if (!std::isfinite(origin) || std::abs(origin) > 4.0e18f) return 0;
            const int64_t value = static_cast<int64_t>(origin) % side;
            return static_cast<int32_t>(value < 0 ? value + side : value);
        };
        cascade.layer_origin = {wrap(cascade.texel_origin.x), wrap(cascade.texel_origin.y)};
    }
}

std::vector<LayerPiece> layer_pieces(const TexelRect& window_rect, glm::ivec2 layer_origin, uint32_t resolution) {
    const int32_t size = static_cast<int32_t>(resolution);
    // Window texel w lies at layer texel w + origin, less one side past the layer's edge:
    // the window splits at w = size - origin on each axis.
    const glm::ivec2 split = glm::ivec2(size) - layer_origin;
    std::vector<LayerPiece> pieces;
    for (uint32_t tile = 0; tile < 4; ++tile) {
        const glm::ivec2 wrapped(static_cast<int32_t>(tile & 1u), static_cast<int32_t>(tile >> 1u));
        TexelRect part;
        for (int axis = 0; axis < 2; ++axis) {
            part.min[axis] = wrapped[axis] ? split[axis] : 0;
            part.max[axis] = wrapped[axis] ? size : split[axis];
        }
        const TexelRect window = intersect(window_rect, part);
        if (window.empty()) continue;
        const glm::ivec2 move = layer_origin - wrapped * size;
        pieces.push_back({window, {window.min + move, window.max + move}, tile});
    }
    return pieces;
}

std::optional<glm::ivec2> whole_texel_shift(const Cascade& cached, const Cascade& current) {
    if (!same_mapping_but_translation(cached, current)) return std::nullopt;
    // A point at grid texel g sits at g - origin in each map.
    return glm::ivec2(cached.texel_origin - current.texel_origin);
}

std::vector<TexelRect> exposed_by_shift(glm::ivec2 shift, uint32_t resolution) {
    const int32_t size = static_cast<int32_t>(resolution);
    if (shift == glm::ivec2(0)) return {};
    if (std::abs(shift.x) >= size || std::abs(shift.y) >= size) return {whole_map(resolution)};
    std::vector<TexelRect> rects;
    // The columns the shifted map leaves uncovered, full height ...
    if (shift.x > 0) rects.push_back({{0, 0}, {shift.x, size}});
    if (shift.x < 0) rects.push_back({{size + shift.x, 0}, {size, size}});
    // ... and the rows, between those columns.
    const int32_t x0 = std::max(shift.x, 0);
    const int32_t x1 = size + std::min(shift.x, 0);
    if (shift.y > 0) rects.push_back({{x0, 0}, {x1, shift.y}});
    if (shift.y < 0) rects.push_back({{x0, size + shift.y}, {x1, size}});
    return rects;
}

TexelRect caster_footprint(const Cascade& cascade, const core::Aabb& world_box, uint32_t resolution) {
    if (world_box.empty()) return {};
    // Arvo's method bounds the box in clip space (the projection is affine); only the far
    // side culls, as in caster_may_shadow_cascade (nearer boxes are flattened onto the
    // near plane by depth clamp).
    const core::Aabb clip_box = core::transform_aabb(world_box, cascade.view_projection);
    // A box too large to project (infinite or NaN clip coordinates: bounds near the float
    // range) may reach every texel.
    const auto finite = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite(clip_box.min) || !finite(clip_box.max)) return whole_map(resolution);
    if (clip_box.max.z < 0.0f) return {};
    // Wholly beyond the window's edges: no texel (the common case, kept as cheap as
    // caster_may_shadow_cascade).
    if (clip_box.min.x > 1.0f || clip_box.max.x < -1.0f || clip_box.min.y > 1.0f || clip_box.max.y < -1.0f) return {};
    const glm::vec2 low = clip_to_texels(clip_box.min.x, clip_box.min.y, resolution);
    const glm::vec2 high = clip_to_texels(clip_box.max.x, clip_box.max.y, resolution);
    // One texel of margin: rasterisation covers texels whose centres the triangles reach.
    const glm::vec2 limit(static_cast<float>(resolution) + 2.0f);
    const TexelRect rect{glm::ivec2(glm::clamp(glm::floor(low) - 1.0f, glm::vec2(-2.0f), limit)),
                         glm::ivec2(glm::clamp(glm::ceil(high) + 1.0f, glm::vec2(-2.0f), limit))};
    return intersect(rect, whole_map(resolution));
}

bool may_cast_into_layer(const LocalLayerKey& layer, const core::Aabb& box) {
    if (box.empty() || !caster_may_shadow_frustum(layer.view_projection, box)) return false;
    return layer.sphere.w <= 0.0f || caster_may_shadow_sphere(glm::vec3(layer.sphere), layer.sphere.w, box);
}

bool local_layer_reusable(const std::optional<LocalLayerKey>& kept, const LocalLayerKey& current,
                          std::span<const core::Aabb> changed_static_bounds,
                          std::span<const core::Aabb> dynamic_bounds) {
    if (!kept || !(*kept == current)) return false;
    const auto reaches = [&](const core::Aabb& box) { return may_cast_into_layer(current, box); };
    return std::none_of(changed_static_bounds.begin(), changed_static_bounds.end(), reaches) &&
           std::none_of(dynamic_bounds.begin(), dynamic_bounds.end(), reaches);
}

int64_t CascadeUpdate::redraw_texels() const {
    int64_t texels = 0;
    for (const TexelRect& rect : redraw) texels += rect.area();
    return texels;
}

CascadeUpdate plan_cascade_update(const std::optional<Cascade>& cached, const Cascade& current, uint32_t resolution,
                                  std::span<const core::Aabb> changed_static_bounds) {
    CascadeUpdate update;
    const std::optional<glm::ivec2> shift = cached ? whole_texel_shift(*cached, current) : std::nullopt;
    if (!shift) return update;
    update.reuse = true;
    update.shift = *shift;
    update.redraw = exposed_by_shift(*shift, resolution);
    for (const core::Aabb& bounds : changed_static_bounds) {
        const TexelRect footprint = caster_footprint(current, bounds, resolution);
        if (!footprint.empty()) update.redraw.push_back(footprint);
    }
    const double share =
        static_cast<double>(update.redraw_texels()) / static_cast<double>(whole_map(resolution).area());
    if (update.redraw.size() > kMaxRedrawRects || share > kMaxRedrawShare) return CascadeUpdate{};
    return update;
}

}  // namespace penumbra
