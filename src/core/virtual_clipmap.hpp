#pragma once
// Virtual shadow maps for a directional light: a clipmap of virtual levels, each a square
// of `level_resolution` virtual texels cut into pages of kVirtualPageTexels, each level
// twice the extent of the one before and centred on the camera (UE5's virtual shadow map
// clipmaps; Frogfood and Blender EEVEE-Next page theirs the same way). Only the pages that
// visible pixels sample get physical memory, so a texel can be as fine as a pixel near the
// camera and kilometres away alike.
//
// Everything here is pure: where the levels lie, which level and pages a receiver needs,
// and how a level's window maps onto its page table. The GPU passes (src/passes/
// virtual_pages.*) run the same formulas, and tests compare the two.
#include <cstdint>
#include <vector>

#include "core/camera_math.hpp"

namespace penumbra {

// Texels per side of one page (UE5's 128^2 pages: 64 KiB of D32).
inline constexpr uint32_t kVirtualPageTexels = 128;
inline constexpr uint32_t kMaxVirtualLevels = 24;

struct VirtualClipmapConfig {
    uint32_t level_resolution = 16384;  // virtual texels per side of every level: 8192 or 16384
    uint32_t level_count = 16;          // 1..kMaxVirtualLevels
    float first_level_extent = 4.0f;    // metres across level 0; level l spans first * 2^l
    // Level choice: a receiver takes the finest level whose texel is no larger than its
    // pixel's footprint times 2^lod_bias (negative: finer texels, more pages).
    float lod_bias = 0.0f;
};

// One level: a square window of the light's view plane, page-aligned in a page grid fixed
// in the world (the light view is a pure rotation), so a page of the world keeps its
// contents while the window moves with the camera.
struct VirtualLevel {
    float extent = 0.0f;            // metres per side
    float texel_world_size = 0.0f;  // metres per virtual texel
    float texels_per_metre = 0.0f;
    // The world page grid's page of the window's page (0, 0): the window spans world pages
    // first_page .. first_page + pages_per_side - 1 on each axis.
    glm::ivec2 first_page{0};
    // Reverse-Z depth of a light-view z: z * depth_scale + depth_offset (1 nearest the light).
    float depth_scale = 0.0f;
    float depth_offset = 0.0f;
};

struct VirtualClipmap {
    glm::mat4 light_view{1.0f};  // world -> light view (light_view_matrix), every level's
    glm::vec3 light_direction{0.0f, -1.0f, 0.0f};
    uint32_t level_resolution = 0;
    uint32_t pages_per_side = 0;  // level_resolution / kVirtualPageTexels
    std::vector<VirtualLevel> levels;
};

// Throws InputError naming the field when a config value is out of range.
void validate_virtual_clipmap_config(const VirtualClipmapConfig& config, const char* where);

// The levels around `camera_position` for a light travelling along `light_direction`. Each
// window is centred on the camera's light-view position, snapped to whole pages; its depth
// range is the scene's extent along the light (at least as deep as the level is wide,
// centred on the scene, as the cascades': depth_range_of_scene), so depths drawn in one
// frame stay valid in the next. Requires a validated config.
VirtualClipmap compute_virtual_clipmap(const glm::vec3& camera_position, const glm::vec3& light_direction,
                                       const VirtualClipmapConfig& config, const core::Aabb& scene_bounds);

// World metres per pixel at `distance` from the camera for a vertical field of view and an
// image height: the footprint the level choice compares texels with.
float pixel_footprint_per_metre(float fov_y_radians, uint32_t image_height);

// The level a receiver at `world_position` samples: the finest level whose texel is no
// larger than its pixel footprint (`footprint_base` plus the distance from
// `camera_position` times `footprint_per_metre`) times 2^lod_bias, or the first coarser level whose window holds
// the receiver `margin_texels` (its texels) inside the edge; -1 when no level does.
int select_virtual_level(const VirtualClipmap& clipmap, const glm::vec3& camera_position, float footprint_per_metre,
                         float lod_bias, const glm::vec3& world_position, float margin_texels,
                         float footprint_base = 0.0f);

// A receiver's place in a level: virtual texel coordinates from the window's corner.
glm::vec2 virtual_texel_of(const VirtualClipmap& clipmap, int level, const glm::vec3& world_position);

// Pages of a level, counted from the window's page (0, 0): [min, max) per axis.
struct PageRect {
    glm::ivec2 min{0};
    glm::ivec2 max{0};
    bool empty() const { return max.x <= min.x || max.y <= min.y; }
};

// The pages a filter reading `radius_texels` around `texel` touches, clipped to the window.
PageRect pages_around(const VirtualClipmap& clipmap, glm::vec2 texel, float radius_texels);

// The world pages [min, max) of `level` that a world-space box's casters reach: its
// light-space rectangle (shadows fall along the light) grown by one texel for the
// rasteriser's coverage at the edges. Not clipped to the window; empty for an empty box.
PageRect world_pages_of_box(const VirtualClipmap& clipmap, int level, const core::Aabb& world_box);

// The page table slot of a window page: the world page modulo pages_per_side on each axis
// (toroidal addressing, as the cascades' layers: a world page keeps its slot while the
// window moves, so a cached page needs no copy).
uint32_t page_table_slot(const VirtualClipmap& clipmap, int level, glm::ivec2 window_page);

// The world page a slot holds for a window starting at `first_page`: the one page of the
// window whose coordinates equal the slot's modulo pages_per_side.
glm::ivec2 world_page_of_slot(glm::ivec2 first_page, uint32_t pages_per_side, uint32_t slot);

}  // namespace penumbra
