#pragma once
// Sample directions over the sun's disk for the soft-shadow reference. The sun is a disk
// of angular diameter d seen along `to_sun`; a direction toward a point of the disk is
// to_sun + tan(d / 2) * (x * tangent + y * bitangent) for (x, y) in the unit disk (exact
// for a disk perpendicular to to_sun; for half a degree it equals a uniform cone).
#include <cstdint>

#include <glm/glm.hpp>

namespace penumbra::quality {

// Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square": maps [0,1)^2 onto
// the unit disk, preserving area (so stratified squares give stratified disk samples).
glm::vec2 concentric_disk(glm::vec2 square);

// Point `index` of an n-point Fibonacci lattice in [0,1)^2, toroidally shifted by `shift`
// (a Cranley-Patterson rotation, so that neighbouring pixels use decorrelated sets). The
// lattice is stratified: each of the n horizontal strips holds one point.
glm::vec2 fibonacci_lattice(uint32_t index, uint32_t count, glm::vec2 shift);

// Two uniform values in [0,1) from an integer (PCG hash, Jarzynski & Olano 2020).
glm::vec2 hash_to_unit_square(uint32_t value);

// An orthonormal basis around a unit vector (Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited").
struct TangentBasis {
    glm::vec3 tangent;
    glm::vec3 bitangent;
};
TangentBasis orthonormal_basis(const glm::vec3& unit_normal);

class SunDisk {
public:
    SunDisk(const glm::vec3& to_sun, float angular_diameter_degrees);
    // The unit direction toward the sun's centre.
    const glm::vec3& center() const { return to_sun_; }
    // The unit direction toward the point `disk_point` (in the unit disk) of the sun.
    glm::vec3 direction(glm::vec2 disk_point) const;

private:
    glm::vec3 to_sun_;
    TangentBasis basis_;
    float tan_half_angle_;
};

}  // namespace penumbra::quality
