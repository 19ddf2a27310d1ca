#include "penumbra/scene/primitives.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "scene/mesh_tools.hpp"

namespace penumbra {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

// Appends a quad whose corners p0..p3 run counter-clockwise when seen from the side that
// `normal` points to, with UVs (0,0), (1,0), (1,1), (0,1).
void add_quad(Mesh& mesh, const std::array<glm::vec3, 4>& corners, const glm::vec3& normal) {
    static constexpr std::array<glm::vec2, 4> kCornerUvs{glm::vec2{0.0f, 0.0f}, glm::vec2{1.0f, 0.0f},
                                                         glm::vec2{1.0f, 1.0f}, glm::vec2{0.0f, 1.0f}};
    const auto base = static_cast<uint32_t>(mesh.vertices.size());
    for (size_t i = 0; i < 4; ++i) mesh.vertices.push_back({corners[i], normal, kCornerUvs[i]});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// One face of a box: `up_on_face` is the face's V direction; U = up x normal so that
// U x V = normal and the quad (-U-V, +U-V, +U+V, -U+V) is counter-clockwise.
void add_box_face(Mesh& mesh, const glm::vec3& half_size, const glm::vec3& normal, const glm::vec3& up_on_face) {
    const glm::vec3 u_axis = glm::cross(up_on_face, normal);
    const glm::vec3 center = normal * half_size;
    const glm::vec3 u = u_axis * glm::dot(glm::abs(u_axis), half_size);
    const glm::vec3 v = up_on_face * glm::dot(glm::abs(up_on_face), half_size);
    add_quad(mesh, {center - u - v, center + u - v, center + u + v, center - u + v}, normal);
}

// Point on the unit circle in XZ. Angle grows towards -Z so that walking down a side
// and then along increasing angle turns counter-clockwise seen from outside.
glm::vec3 circle_point(float angle) { return {std::cos(angle), 0.0f, -std::sin(angle)}; }

void add_cylinder_side(Mesh& mesh, float radius, float half_height, uint32_t segments) {
    const auto base = static_cast<uint32_t>(mesh.vertices.size());
    for (uint32_t segment = 0; segment <= segments; ++segment) {
        const float u = static_cast<float>(segment) / static_cast<float>(segments);
        const glm::vec3 radial = circle_point(u * kTwoPi);
        mesh.vertices.push_back({radial * radius + glm::vec3{0.0f, half_height, 0.0f}, radial, {u, 0.0f}});
        mesh.vertices.push_back({radial * radius - glm::vec3{0.0f, half_height, 0.0f}, radial, {u, 1.0f}});
    }
    for (uint32_t segment = 0; segment < segments; ++segment) {
        const uint32_t top = base + 2 * segment;
        const uint32_t bottom = top + 1;
        const uint32_t next_top = top + 2;
        const uint32_t next_bottom = top + 3;
        mesh.indices.insert(mesh.indices.end(), {top, bottom, next_bottom, top, next_bottom, next_top});
    }
}

// A triangle fan around the cap's centre; `facing` is +1 for the top cap, -1 for the bottom.
void add_cylinder_cap(Mesh& mesh, float radius, float half_height, uint32_t segments, float facing) {
    const glm::vec3 normal{0.0f, facing, 0.0f};
    const auto center = static_cast<uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back({normal * half_height, normal, {0.5f, 0.5f}});
    for (uint32_t segment = 0; segment <= segments; ++segment) {
        const glm::vec3 radial = circle_point(kTwoPi * static_cast<float>(segment) / static_cast<float>(segments));
        const glm::vec2 uv{0.5f + 0.5f * radial.x, 0.5f + 0.5f * radial.z};
        mesh.vertices.push_back({radial * radius + normal * half_height, normal, uv});
    }
    for (uint32_t segment = 0; segment < segments; ++segment) {
        const uint32_t current = center + 1 + segment;
        if (facing > 0.0f) {
            mesh.indices.insert(mesh.indices.end(), {center, current, current + 1});
        } else {
            mesh.indices.insert(mesh.indices.end(), {center, current + 1, current});
        }
    }
}

}  // namespace

Mesh make_plane(float size_x, float size_z) {
    Mesh mesh;
    const float x = 0.5f * size_x;
    const float z = 0.5f * size_z;
    // Counter-clockwise seen from +Y: (-x,+z) -> (+x,+z) -> (+x,-z) -> (-x,-z).
    // A grid of cells of at most 2 m rather than one quad: Mesa's lavapipe (22.3) writes
    // triangles that cover whole raster tiles into layer 0 during multiview rendering, so a
    // two-triangle ground would break the multiview shadow strategy there (docs/techniques.md).
    const int cells_x = std::clamp(static_cast<int>(std::ceil(size_x / 2.0f)), 1, 64);
    const int cells_z = std::clamp(static_cast<int>(std::ceil(size_z / 2.0f)), 1, 64);
    for (int i = 0; i < cells_x; ++i) {
        for (int j = 0; j < cells_z; ++j) {
            const float x0 = -x + size_x * i / cells_x, x1 = -x + size_x * (i + 1) / cells_x;
            const float z0 = -z + size_z * j / cells_z, z1 = -z + size_z * (j + 1) / cells_z;
            add_quad(
                mesh,
                {glm::vec3{x0, 0.0f, z1}, glm::vec3{x1, 0.0f, z1}, glm::vec3{x1, 0.0f, z0}, glm::vec3{x0, 0.0f, z0}},
                {0.0f, 1.0f, 0.0f});
        }
    }
    // One texture over the whole plane: (-x,+z) is UV (0,0) and (+x,-z) is (1,1).
    for (Vertex& vertex : mesh.vertices) {
        vertex.uv = {(vertex.position.x + x) / size_x, (z - vertex.position.z) / size_z};
    }
    mesh.bounds = compute_mesh_bounds(mesh.vertices);
    return mesh;
}

Mesh make_box(const glm::vec3& size) {
    Mesh mesh;
    const glm::vec3 half_size = 0.5f * size;
    const glm::vec3 up{0.0f, 1.0f, 0.0f};
    add_box_face(mesh, half_size, {1.0f, 0.0f, 0.0f}, up);
    add_box_face(mesh, half_size, {-1.0f, 0.0f, 0.0f}, up);
    add_box_face(mesh, half_size, {0.0f, 0.0f, 1.0f}, up);
    add_box_face(mesh, half_size, {0.0f, 0.0f, -1.0f}, up);
    add_box_face(mesh, half_size, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, -1.0f});
    add_box_face(mesh, half_size, {0.0f, -1.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    mesh.bounds = compute_mesh_bounds(mesh.vertices);
    return mesh;
}

Mesh make_sphere(float radius, uint32_t segments, uint32_t rings) {
    segments = std::max(segments, 3u);
    rings = std::max(rings, 2u);
    Mesh mesh;
    // A UV sphere: rings run from the north pole (v = 0) to the south pole (v = 1).
    for (uint32_t ring = 0; ring <= rings; ++ring) {
        const float v = static_cast<float>(ring) / static_cast<float>(rings);
        const float polar = v * std::numbers::pi_v<float>;
        for (uint32_t segment = 0; segment <= segments; ++segment) {
            const float u = static_cast<float>(segment) / static_cast<float>(segments);
            const glm::vec3 normal =
                circle_point(u * kTwoPi) * std::sin(polar) + glm::vec3{0.0f, std::cos(polar), 0.0f};
            mesh.vertices.push_back({normal * radius, normal, {u, v}});
        }
    }
    const uint32_t row = segments + 1;
    for (uint32_t ring = 0; ring < rings; ++ring) {
        for (uint32_t segment = 0; segment < segments; ++segment) {
            const uint32_t upper = ring * row + segment;
            const uint32_t lower = upper + row;
            // The triangle touching a pole would be degenerate: leave it out.
            if (ring != 0) mesh.indices.insert(mesh.indices.end(), {upper, lower, upper + 1});
            if (ring != rings - 1) mesh.indices.insert(mesh.indices.end(), {upper + 1, lower, lower + 1});
        }
    }
    mesh.bounds = compute_mesh_bounds(mesh.vertices);
    return mesh;
}

Mesh make_cylinder(float radius, float height, uint32_t segments) {
    segments = std::max(segments, 3u);
    Mesh mesh;
    const float half_height = 0.5f * height;
    add_cylinder_side(mesh, radius, half_height, segments);
    add_cylinder_cap(mesh, radius, half_height, segments, 1.0f);
    add_cylinder_cap(mesh, radius, half_height, segments, -1.0f);
    mesh.bounds = compute_mesh_bounds(mesh.vertices);
    return mesh;
}

glm::mat4 compose_transform(const glm::vec3& translation, const glm::vec3& rotation_degrees, const glm::vec3& scale) {
    const glm::mat4 identity{1.0f};
    const glm::vec3 radians = glm::radians(rotation_degrees);
    const glm::mat4 rotation = glm::rotate(identity, radians.z, glm::vec3{0.0f, 0.0f, 1.0f}) *
                               glm::rotate(identity, radians.y, glm::vec3{0.0f, 1.0f, 0.0f}) *
                               glm::rotate(identity, radians.x, glm::vec3{1.0f, 0.0f, 0.0f});
    return glm::translate(identity, translation) * rotation * glm::scale(identity, scale);
}

}  // namespace penumbra
