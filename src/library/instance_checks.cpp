#include "library/instance_checks.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "library/conversions.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/shadow_system.hpp"

namespace penumbra::library {
namespace {

// Below this, the 3x3 part's columns are (nearly) coplanar: its inverse, and with it the
// normals and the light-space fit, are meaningless. Measured on the normalised columns, so
// that uniform scale does not matter (a 1 mm mesh and a 1 km one pass alike).
constexpr double kSmallestNormalisedDeterminant = 1e-6;

[[noreturn]] void reject(const char* call, const std::string& argument, const std::string& problem) {
    throw InputError(std::string("ShadowSystem::") + call + ": " + argument + ": " + problem);
}

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// One snprintf, not a chain of string additions: GCC 12 at -O3 (the examples' install
// build) reports a false -Wrestrict overlap in `"(" + std::string`.
std::string vector_text(const Vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", double{v.x}, double{v.y}, double{v.z});
    return text;
}

const std::string& beyond_limit() {
    static const std::string text = "is beyond " + number(kMaxWorldMagnitude) + " in magnitude (kMaxWorldMagnitude)";
    return text;
}

bool within_limit(const Vec3& v) {
    return std::abs(v.x) <= kMaxWorldMagnitude && std::abs(v.y) <= kMaxWorldMagnitude &&
           std::abs(v.z) <= kMaxWorldMagnitude;
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The determinant of the 3x3 part divided by the product of its column lengths, in double
// (a 1e30 scale squares beyond float): 1 for any rotation and scale, 0 when singular.
double normalised_determinant(const Mat4& world) {
    double columns[3][3];
    double length_product = 1.0;
    for (int c = 0; c < 3; ++c) {
        double squared = 0.0;
        for (int r = 0; r < 3; ++r) {
            columns[c][r] = world(r, c);
            squared += columns[c][r] * columns[c][r];
        }
        length_product *= std::sqrt(squared);
    }
    const double(&a)[3] = columns[0];
    const double(&b)[3] = columns[1];
    const double(&d)[3] = columns[2];
    const double determinant =
        a[0] * (b[1] * d[2] - b[2] * d[1]) - b[0] * (a[1] * d[2] - a[2] * d[1]) + d[0] * (a[1] * b[2] - a[2] * b[1]);
    return length_product > 0.0 ? determinant / length_product : 0.0;
}

}  // namespace

void check_positions(std::span<const Vec3> positions, const char* call) {
    for (size_t i = 0; i < positions.size(); ++i) {
        const std::string argument = "positions[" + std::to_string(i) + "]";
        if (!finite(positions[i])) reject(call, argument, "must be finite");
        if (!within_limit(positions[i])) reject(call, argument, vector_text(positions[i]) + " " + beyond_limit());
    }
}

void check_bounds_magnitude(const Bounds& bounds, const char* call) {
    if (!within_limit(bounds.min) || !within_limit(bounds.max)) {
        reject(call, "bounds", vector_text(bounds.min) + " .. " + vector_text(bounds.max) + " " + beyond_limit());
    }
}

core::Aabb checked_world_bounds(const Mat4& world, const core::Aabb& mesh_bounds, const char* call) {
    for (const float value : world.m) {
        if (!std::isfinite(value)) reject(call, "world", "must be finite");
    }
    if (world(3, 0) != 0.0f || world(3, 1) != 0.0f || world(3, 2) != 0.0f || world(3, 3) != 1.0f) {
        char row[128];
        std::snprintf(row, sizeof row, "(%g, %g, %g, %g)", double{world(3, 0)}, double{world(3, 1)},
                      double{world(3, 2)}, double{world(3, 3)});
        reject(call, "world", std::string("is not affine: its bottom row is ") + row + ", not (0, 0, 0, 1)");
    }
    const double determinant = normalised_determinant(world);
    if (!(std::abs(determinant) >= kSmallestNormalisedDeterminant)) {
        reject(call, "world",
               "is not invertible (its 3x3 part is singular: normalised determinant " + number(determinant) + ")");
    }
    const core::Aabb bounds = core::transform_aabb(mesh_bounds, to_glm(world));
    const Vec3 low = to_public(bounds.min);
    const Vec3 high = to_public(bounds.max);
    if (!finite(low) || !finite(high) || !within_limit(low) || !within_limit(high)) {
        reject(call, "world",
               "places the mesh at " + vector_text(low) + " .. " + vector_text(high) + ", which " + beyond_limit());
    }
    return bounds;
}

void check_instance_flags(uint32_t flags, const char* call) {
    const uint32_t undefined = flags & ~static_cast<uint32_t>(kInstanceAllFlags);
    if (undefined != 0) {
        char text[96];
        std::snprintf(text, sizeof text, "0x%x holds bits InstanceFlags does not define (0x%x; defined: 0x%x)", flags,
                      undefined, static_cast<uint32_t>(kInstanceAllFlags));
        reject(call, "flags", text);
    }
}

}  // namespace penumbra::library
