#include "filter_measurements.hpp"

#include <cmath>

namespace penumbra::testing {

std::vector<GroundSample> ground_samples(const Scene& scene, const renderer::FrameImages& images, float half_size,
                                         const std::vector<Aabb>& boxes) {
    std::vector<GroundSample> samples;
    for (uint32_t y = 0; y < images.height; ++y) {
        for (uint32_t x = 0; x < images.width; ++x) {
            const PixelRay ray = pixel_ray(scene.camera, images.width, images.height, x, y);
            const auto ground = intersect_ground(ray, half_size);
            if (!ground) continue;
            bool blocked = false;
            for (const Aabb& box : boxes) {
                const auto hit = intersect_box(ray, box);
                blocked = blocked || (hit && *hit < *ground);
            }
            if (blocked) continue;
            const glm::vec3 point = ray.origin + ray.direction * *ground;
            samples.push_back({{point.x, point.z}, visibility_at(images, x, y)});
        }
    }
    return samples;
}

Profile visibility_profile(const std::vector<GroundSample>& samples,
                           const std::function<std::optional<float>(glm::vec2)>& signed_distance, float lowest,
                           float highest, float bin_width) {
    const auto bins = static_cast<size_t>(std::ceil((highest - lowest) / bin_width));
    std::vector<double> sums(bins, 0.0);
    std::vector<size_t> counts(bins, 0);
    for (const GroundSample& sample : samples) {
        const std::optional<float> distance = signed_distance(sample.xz);
        if (!distance || *distance < lowest || *distance >= highest) continue;
        const auto bin = static_cast<size_t>((*distance - lowest) / bin_width);
        if (bin >= bins) continue;
        sums[bin] += sample.visibility;
        counts[bin] += 1;
    }
    Profile profile{lowest, bin_width, std::vector<std::optional<float>>(bins)};
    for (size_t i = 0; i < bins; ++i) {
        if (counts[i] > 0) profile.mean_visibility[i] = static_cast<float>(sums[i] / static_cast<double>(counts[i]));
    }
    return profile;
}

std::optional<float> transition_width(const Profile& profile, float lit, float shadow) {
    // Walk from the lit side (large distances) inward.
    std::optional<size_t> last_lit;
    std::optional<size_t> first_shadow;
    for (size_t i = profile.mean_visibility.size(); i-- > 0;) {
        const std::optional<float>& mean = profile.mean_visibility[i];
        if (!mean) continue;
        if (!first_shadow && *mean >= lit) last_lit = i;
        if (last_lit && *mean <= shadow) {
            first_shadow = i;
            break;
        }
    }
    if (!last_lit || !first_shadow) return std::nullopt;
    return static_cast<float>(*last_lit - *first_shadow) * profile.bin_width;
}

float partial_width(const Profile& profile, float low, float high) {
    float width = 0.0f;
    for (const std::optional<float>& mean : profile.mean_visibility) {
        if (mean && *mean > low && *mean < high) width += profile.bin_width;
    }
    return width;
}

}  // namespace penumbra::testing
