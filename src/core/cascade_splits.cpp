// Cascade split distances: uniform, logarithmic, practical (PSSM) and manual.
//
// Reference: Zhang, Sun, Xu, Lun, "Parallel-Split Shadow Maps for Large-scale Virtual
// Environments" (VRCIA 2006). The logarithmic scheme gives every cascade the same ratio
// far/near, which is what perspective aliasing asks for, but it crowds the first
// cascades into the first metres; the uniform scheme does the opposite. PSSM's
// "practical" scheme blends the two with a lambda.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/cascades.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

// Split i of count for the uniform scheme: C_i^uni = n + (f - n) * i / N.
double uniform_split(double near_plane, double far_plane, int i, int count) {
    return near_plane + (far_plane - near_plane) * static_cast<double>(i) / count;
}

// Split i of count for the logarithmic scheme: C_i^log = n * (f / n)^(i / N).
double logarithmic_split(double near_plane, double far_plane, int i, int count) {
    return near_plane * std::pow(far_plane / near_plane, static_cast<double>(i) / count);
}

// Manual splits are user input checked against a camera the settings validator never
// saw (the far plane may be nearer than a split), hence an InputError here.
void require_manual_splits_inside(float near_plane, float far_plane, int count, const std::vector<float>& manual) {
    if (static_cast<int>(manual.size()) != count - 1) {
        std::ostringstream message;
        message << "splits: " << manual.size() << " manual split distances given, " << count - 1 << " needed for "
                << count << " cascades";
        throw InputError(message.str());
    }
    float previous = near_plane;
    for (const float split : manual) {
        if (!(split > previous) || !(split < far_plane)) {
            std::ostringstream message;
            message << "splits: manual split " << split << " must lie strictly between the previous split " << previous
                    << " and the shadow distance " << far_plane
                    << " (camera near plane .. min(camera far, max_distance))";
            throw InputError(message.str());
        }
        previous = split;
    }
}

}  // namespace

std::vector<float> compute_split_distances(float near_plane, float far_plane, int count, SplitScheme scheme,
                                           float lambda, const std::vector<float>& manual) {
    if (!(near_plane > 0.0f) || !(far_plane > near_plane) || !std::isfinite(far_plane)) {
        throw std::invalid_argument("compute_split_distances: requires 0 < near < far < infinity");
    }
    if (count < 1 || count > kMaxCascades) {
        throw std::invalid_argument("compute_split_distances: count must be 1..kMaxCascades");
    }
    if (scheme == SplitScheme::Manual) require_manual_splits_inside(near_plane, far_plane, count, manual);

    // Lambda only matters for the practical scheme; uniform and logarithmic are its ends.
    double blend = 0.0;
    if (scheme == SplitScheme::Logarithmic) blend = 1.0;
    if (scheme == SplitScheme::Practical) blend = static_cast<double>(lambda);

    std::vector<float> splits(static_cast<size_t>(count) + 1);
    splits.front() = near_plane;
    splits.back() = far_plane;
    for (int i = 1; i < count; ++i) {
        if (scheme == SplitScheme::Manual) {
            splits[i] = manual[i - 1];
            continue;
        }
        // PSSM: C_i = lambda * C_i^log + (1 - lambda) * C_i^uni, evaluated in double and
        // written so that lambda 0 and 1 reproduce the pure schemes exactly.
        const double uniform = uniform_split(near_plane, far_plane, i, count);
        const double logarithmic = logarithmic_split(near_plane, far_plane, i, count);
        splits[i] = static_cast<float>((1.0 - blend) * uniform + blend * logarithmic);
    }
    return splits;
}

}  // namespace penumbra
