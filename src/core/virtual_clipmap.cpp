// The virtual shadow map clipmap of a directional light (see virtual_clipmap.hpp).
//
// Per frame, a pure function of the camera position, the light and the scene bounds:
//   1. one light view for every level (light_view_matrix: a rotation, so a texel grid in
//      its XY plane is fixed in the world);
//   2. level l spans first_level_extent * 2^l metres in level_resolution texels; its window
//      is the square of pages_per_side pages of that grid centred on the camera, snapped to
//      whole pages (the clipmap idea of Tanner et al. 1998, at page granularity), so a page
//      keeps its texels while the camera moves;
//   3. its depth range is the scene's along the light (depth_range_of_scene), which does not
//      follow the camera either.
#include "core/virtual_clipmap.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/cascade_fitting.hpp"
#include "core/cascades.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

bool is_power_of_two(uint32_t value) { return value != 0 && (value & (value - 1)) == 0; }

int floor_mod(int value, int modulus) {
    const int remainder = value % modulus;
    return remainder < 0 ? remainder + modulus : remainder;
}

}  // namespace

void validate_virtual_clipmap_config(const VirtualClipmapConfig& config, const char* where) {
    const auto reject = [where](const std::string& field, const std::string& problem) {
        throw InputError(std::string(where) + ": " + field + ": " + problem);
    };
    if (!is_power_of_two(config.level_resolution) || config.level_resolution < 1024 ||
        config.level_resolution > 16384) {
        reject("virtual_resolution",
               std::to_string(config.level_resolution) + " must be a power of two in 1024..16384");
    }
    if (config.level_count < 1 || config.level_count > kMaxVirtualLevels) {
        reject("virtual_levels",
               std::to_string(config.level_count) + " is out of range (1.." + std::to_string(kMaxVirtualLevels) + ")");
    }
    if (!(config.first_level_extent >= 0.01f && config.first_level_extent <= 1.0e5f)) {
        reject("virtual_first_extent",
               std::to_string(config.first_level_extent) + " metres is out of range (0.01..100000)");
    }
    if (!(config.lod_bias >= -4.0f && config.lod_bias <= 4.0f)) {
        reject("virtual_lod_bias", std::to_string(config.lod_bias) + " is out of range (-4..4)");
    }
}

VirtualClipmap compute_virtual_clipmap(const glm::vec3& camera_position, const glm::vec3& light_direction,
                                       const VirtualClipmapConfig& config, const core::Aabb& scene_bounds) {
    VirtualClipmap clipmap;
    clipmap.light_view = light_view_matrix(light_direction);
    clipmap.light_direction = glm::normalize(light_direction);
    clipmap.level_resolution = config.level_resolution;
    clipmap.pages_per_side = config.level_resolution / kVirtualPageTexels;
    const glm::vec2 camera_in_light(clipmap.light_view * glm::vec4(camera_position, 1.0f));
    const core::Aabb light_space_scene = core::transform_aabb(scene_bounds, clipmap.light_view);
    const int half_pages = static_cast<int>(clipmap.pages_per_side / 2);
    for (uint32_t l = 0; l < config.level_count; ++l) {
        VirtualLevel level;
        level.extent = std::ldexp(config.first_level_extent, static_cast<int>(l));
        level.texel_world_size = level.extent / static_cast<float>(config.level_resolution);
        level.texels_per_metre = static_cast<float>(config.level_resolution) / level.extent;
        const float page_metres = level.texel_world_size * static_cast<float>(kVirtualPageTexels);
        // The page holding the camera is the window's centre page (pages_per_side is even).
        const glm::ivec2 camera_page(glm::floor(camera_in_light / page_metres));
        level.first_page = camera_page - half_pages;
        LightOrthoBox box;
        box.half_size = glm::vec2(0.5f * level.extent);
        box.center = glm::vec2(level.first_page) * page_metres + box.half_size;
        box.near_distance = -0.5f * level.extent;
        box.far_distance = 0.5f * level.extent;
        const glm::mat4 projection = light_projection(depth_range_of_scene(box, light_space_scene));
        level.depth_scale = projection[2][2];
        level.depth_offset = projection[3][2];
        clipmap.levels.push_back(level);
    }
    return clipmap;
}

float pixel_footprint_per_metre(float fov_y_radians, uint32_t image_height) {
    return 2.0f * std::tan(0.5f * fov_y_radians) / static_cast<float>(std::max(image_height, 1u));
}

glm::vec2 virtual_texel_of(const VirtualClipmap& clipmap, int level, const glm::vec3& world_position) {
    const VirtualLevel& l = clipmap.levels.at(static_cast<size_t>(level));
    const glm::vec2 light(clipmap.light_view * glm::vec4(world_position, 1.0f));
    // The world grid's texel less the window's first texel (a whole number of pages): the
    // same operations as the GPU's, so both agree on which page a point lies in.
    return light * l.texels_per_metre - glm::vec2(l.first_page * static_cast<int>(kVirtualPageTexels));
}

int select_virtual_level(const VirtualClipmap& clipmap, const glm::vec3& camera_position, float footprint_per_metre,
                         float lod_bias, const glm::vec3& world_position, float margin_texels, float footprint_base) {
    if (clipmap.levels.empty()) return -1;
    const float footprint =
        (footprint_base + glm::length(world_position - camera_position) * footprint_per_metre) * std::exp2(lod_bias);
    const float finest = clipmap.levels.front().texel_world_size;
    const int last = static_cast<int>(clipmap.levels.size()) - 1;
    const int wanted = footprint > finest ? static_cast<int>(std::floor(std::log2(footprint / finest))) : 0;
    const float side = static_cast<float>(clipmap.level_resolution);
    for (int level = std::min(wanted, last); level <= last; ++level) {
        const glm::vec2 texel = virtual_texel_of(clipmap, level, world_position);
        if (texel.x >= margin_texels && texel.y >= margin_texels && texel.x <= side - margin_texels &&
            texel.y <= side - margin_texels) {
            return level;
        }
    }
    return -1;
}

PageRect pages_around(const VirtualClipmap& clipmap, glm::vec2 texel, float radius_texels) {
    const float page = static_cast<float>(kVirtualPageTexels);
    const glm::ivec2 limit(static_cast<int>(clipmap.pages_per_side));
    PageRect rect;
    rect.min = glm::clamp(glm::ivec2(glm::floor((texel - radius_texels) / page)), glm::ivec2(0), limit);
    rect.max = glm::clamp(glm::ivec2(glm::floor((texel + radius_texels) / page)) + 1, glm::ivec2(0), limit);
    return rect;
}

PageRect world_pages_of_box(const VirtualClipmap& clipmap, int level, const core::Aabb& world_box) {
    if (world_box.empty()) return {};
    const VirtualLevel& l = clipmap.levels.at(static_cast<size_t>(level));
    const core::Aabb light = core::transform_aabb(world_box, clipmap.light_view);
    const float page_metres = l.texel_world_size * static_cast<float>(kVirtualPageTexels);
    const glm::vec2 low = glm::vec2(light.min) - l.texel_world_size;
    const glm::vec2 high = glm::vec2(light.max) + l.texel_world_size;
    // Far beyond the float range of page numbers the box reaches every page.
    constexpr float kLimit = 1.0e9f;
    PageRect rect;
    rect.min = glm::ivec2(glm::clamp(glm::floor(low / page_metres), -kLimit, kLimit));
    rect.max = glm::ivec2(glm::clamp(glm::floor(high / page_metres) + 1.0f, -kLimit, kLimit));
    return rect;
}

uint32_t page_table_slot(const VirtualClipmap& clipmap, int level, glm::ivec2 window_page) {
    const int side = static_cast<int>(clipmap.pages_per_side);
    const glm::ivec2 world_page = clipmap.levels.at(static_cast<size_t>(level)).first_page + window_page;
    return static_cast<uint32_t>(floor_mod(world_page.x, side) + floor_mod(world_page.y, side) * side);
}

glm::ivec2 world_page_of_slot(glm::ivec2 first_page, uint32_t pages_per_side, uint32_t slot) {
    const int side = static_cast<int>(pages_per_side);
    const glm::ivec2 slot_xy(static_cast<int>(slot % pages_per_side), static_cast<int>(slot / pages_per_side));
    return first_page +
           glm::ivec2(floor_mod(slot_xy.x - first_page.x, side), floor_mod(slot_xy.y - first_page.y, side));
}

}  // namespace penumbra
