#include "quality/enclosing_casters.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "penumbra/errors.hpp"
#include "quality/shadow_ray_tracer.hpp"

namespace penumbra::quality {
namespace {

// Rays over the view: enough to see a sunlit patch of a few percent of the image, few
// enough to cost milliseconds on a scene of a million triangles.
constexpr int kGridColumns = 64;
constexpr int kGridRows = 36;
// Below this many receiving points seen, the camera looks at nothing worth judging.
constexpr size_t kMinimumPoints = 16;

bool contains(const Aabb& box, const glm::vec3& point) {
    return glm::all(glm::lessThanEqual(box.min, point)) && glm::all(glm::lessThanEqual(point, box.max));
}

// Casting entries around the camera that hold (nearly) everything else: the ground of a
// scene may poke out of its sky box, so only the others' centres must lie inside.
std::vector<size_t> candidate_entries(const std::vector<SceneEntry>& entries, const glm::vec3& eye) {
    std::vector<size_t> candidates;
    if (entries.size() < 2) return candidates;
    for (size_t i = 0; i < entries.size(); ++i) {
        if (entries[i].casting == 0 || !contains(entries[i].bounds, eye)) continue;
        size_t held = 0;
        for (size_t j = 0; j < entries.size(); ++j) {
            held += j != i && !entries[j].bounds.empty() && contains(entries[i].bounds, entries[j].bounds.center());
        }
        if (static_cast<double>(held) >= kHeldShare * static_cast<double>(entries.size() - 1)) {
            candidates.push_back(i);
        }
    }
    return candidates;
}

// The receiving surface points the camera sees, one per grid ray that meets one, each
// moved back toward the camera a little so that a shadow ray leaves the surface.
std::vector<glm::vec3> seen_receiving_points(const Scene& scene, const Camera& camera, float aspect) {
    const ShadowRayTracer everything(scene, TracedInstances::Everything);
    const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float half_height = std::tan(glm::radians(camera.fov_y_degrees) * 0.5f);
    std::vector<glm::vec3> points;
    for (int row = 0; row < kGridRows; ++row) {
        for (int column = 0; column < kGridColumns; ++column) {
            const float x = ((static_cast<float>(column) + 0.5f) / kGridColumns * 2.0f - 1.0f) * half_height * aspect;
            const float y = (1.0f - (static_cast<float>(row) + 0.5f) / kGridRows * 2.0f) * half_height;
            const glm::vec3 direction = glm::normalize(forward + x * right + y * up);
            const float along = glm::dot(direction, forward);  // the clip planes are distances along forward
            const auto hit =
                everything.first_hit(camera.eye, direction, camera.near_plane / along, camera.far_plane / along);
            if (!hit || !scene.instances[hit->instance].receive_shadows) continue;
            const float back = 1e-4f + 1e-3f * hit->distance;
            points.push_back(camera.eye + direction * (hit->distance - back));
        }
    }
    return points;
}

}  // namespace

std::vector<EnclosingCaster> find_enclosing_casters(const Scene& scene, const Camera& camera, float aspect) {
    const Light* sun = scene.sun();
    if (!sun || !sun->cast_shadows) return {};
    const std::vector<SceneEntry> entries = scene_inventory(scene);
    const std::vector<size_t> candidates = candidate_entries(entries, camera.eye);
    if (candidates.empty()) return {};
    const std::vector<glm::vec3> points = seen_receiving_points(scene, camera, aspect);
    if (points.size() < kMinimumPoints) return {};
    const glm::vec3 toward_sun = -glm::normalize(sun->direction);
    std::vector<EnclosingCaster> found;
    for (const size_t candidate : candidates) {
        const ShadowRayTracer alone(scene, TracedInstances::Casters, entries[candidate].instances);
        const auto blocked = std::count_if(points.begin(), points.end(),
                                           [&](const glm::vec3& point) { return alone.occluded(point, toward_sun); });
        const double share = static_cast<double>(blocked) / static_cast<double>(points.size());
        if (share >= kShadowedShare) found.push_back({entries[candidate], share});
    }
    return found;
}

std::string enclosing_casters_warning(const std::vector<EnclosingCaster>& casters) {
    std::string names;
    std::string advice;
    int least_share = 100;
    for (const EnclosingCaster& caster : casters) {
        const std::string name = exclusion_name(caster.entry.origin);
        names +=
            (names.empty() ? "\"" : ", \"") + escape_control_characters(name.empty() ? caster.entry.name : name) + "\"";
        advice += (advice.empty() ? "" : "; ") + escape_control_characters(no_shadow_advice(caster.entry.origin));
        least_share = std::min(least_share, static_cast<int>(std::floor(caster.shadowed_share * 100.0)));
    }
    if (casters.empty()) return {};
    const bool several = casters.size() > 1;
    return "penumbra: warning: " + names + (several ? " enclose" : " encloses") + " the camera and the scene and " +
           (several ? "shadow " : "shadows ") + std::to_string(least_share) +
           "% of what the camera sees (a sky box or dome?): " + advice;
}

}  // namespace penumbra::quality
