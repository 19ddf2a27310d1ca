#version 460
// The screen-space shadow resolve (ShadowSystem::record_visibility): once per pixel of the
// caller's depth buffer, the visibility of the sun and of every shadowed spot and point
// light, with the same filters as forward shading (penumbra/shadow.glsl), into slots of
// RGBA8 layers (slot s: layer s / 4, channel s % 4; 0 the sun, 1 + i the i-th shadowed
// local light). The deferred shadow buffer of ShadowLib's RenderBuffer and AMD ShadowFX.
//
// Positions come from the depth and the caller's inverse view-projection. What a fragment
// shader takes from screen-space derivatives comes from the neighbouring pixels: on each
// axis the neighbour whose view depth is closer (so that a silhouette does not count as a
// slope, as in Turanszki's normal reconstruction), giving the receiver-plane gradients of
// the sun's cascades and the geometric normal (the shading normal too, without a normal
// buffer). With the caller's face normals (ScreenInputs::face_normals) the plane is the
// surface's own instead: the neighbours are where their pixels' rays meet it, as a
// fragment shader's derivatives see its own triangle, so thin objects and silhouettes get
// the receiver plane that forward shading gives them. Pixels without geometry are lit in
// every slot.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"
#define PENUMBRA_SHADOW_SET 0
#include "penumbra/shadow.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform sampler2D screen_depth;
layout(set = 1, binding = 1) uniform sampler2D screen_normals;  // the depth again when there are none
layout(set = 1, binding = 2, rgba8) uniform writeonly image2DArray visibility;
layout(set = 1, binding = 3) uniform sampler2D screen_face_normals;  // the depth again when there are none
layout(push_constant) uniform PushBlock { ResolvePushConstants resolve; };

bool has_geometry(float depth) { return depth != resolve.background_depth; }

float depth_at(ivec2 pixel) { return texelFetch(screen_depth, pixel, 0).r; }

vec3 unproject(vec2 pixel_centre, float depth) {
    const vec2 ndc = pixel_centre / vec2(resolve.width, resolve.height) * 2.0 - 1.0;
    const vec4 world = resolve.inverse_view_projection * vec4(ndc, depth, 1.0);
    return world.xyz / world.w;
}

vec3 world_position(ivec2 pixel, float depth) { return unproject(vec2(pixel) + 0.5, depth); }

// The neighbour along `axis` (+1 or -1 steps) that continues this pixel's surface best, as
// the signed step and its world position; step 0 when neither has geometry.
struct Neighbour {
    int step;
    vec3 position;
};

Neighbour neighbour_along(ivec2 pixel, ivec2 axis, float view_depth) {
    Neighbour best = Neighbour(0, vec3(0.0));
    float best_difference = 1e30;
    for (int step = 1; step >= -1; step -= 2) {
        const ivec2 other = pixel + step * axis;
        if (any(lessThan(other, ivec2(0))) || any(greaterThanEqual(other, ivec2(resolve.width, resolve.height))))
            continue;
        const float depth = depth_at(other);
        if (!has_geometry(depth)) continue;
        const vec3 position = world_position(other, depth);
        const float difference = abs(penumbra_view_depth(position) - view_depth);
        if (difference < best_difference) {
            best_difference = difference;
            best = Neighbour(step, position);
        }
    }
    return best;
}

vec3 camera_position() {
    const mat4 view = penumbra_shadow.camera_view;
    return -(transpose(mat3(view)) * view[3].xyz);
}

const uint kEncodingUnsignedNormalized = 1u;
const uint kEncodingOctahedral = 2u;

// Octahedral decoding (Cigolle et al. 2014; NormalEncoding::Octahedral).
vec3 decode_octahedral(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return n;
}

vec3 decode(vec4 stored, bool face) {
    if (resolve.normal_encoding == kEncodingOctahedral) return decode_octahedral(face ? stored.zw : stored.xy);
    return resolve.normal_encoding == kEncodingUnsignedNormalized ? stored.xyz * 2.0 - 1.0 : stored.xyz;
}

vec3 decode_normal(ivec2 pixel) { return normalize(decode(texelFetch(screen_normals, pixel, 0), false)); }

// The caller's face normal at `pixel`, unit length, or 0 where it gave none (where a
// triangle is degenerate the shading normal stands in, as in penumbra_geometric_normal()).
vec3 decode_face_normal(ivec2 pixel) {
    const vec3 n = decode(texelFetch(screen_face_normals, pixel, 0), true);
    const float length_squared = dot(n, n);
    return length_squared > 1e-12 ? n * inversesqrt(length_squared) : vec3(0.0);
}

// The neighbour `axis` pixels away on the plane through `position` with normal `n`: where
// that pixel's ray meets the plane (step 0 where the ray runs along it). Depth and half
// the depth give two points of the ray whatever the projection (reverse-Z depth 0 is at
// infinity, so the pixel's own depth is the safe end).
Neighbour neighbour_on_plane(ivec2 pixel, ivec2 axis, float depth, vec3 position, vec3 n) {
    const vec2 centre = vec2(pixel + axis) + 0.5;  // may lie outside the image: it is only a ray
    const vec3 a = unproject(centre, depth);
    const vec3 direction = unproject(centre, 0.5 * depth) - a;
    const float along = dot(direction, n);
    if (abs(along) < 1e-12 * dot(direction, direction)) return Neighbour(0, vec3(0.0));
    return Neighbour(1, a + direction * (dot(position - a, n) / along));
}

void write_slot(ivec2 pixel, uint slot, float value, inout vec4 texel) {
    texel[slot % 4u] = value;
    if (slot % 4u == 3u || slot + 1u == resolve.slot_count) {
        imageStore(visibility, ivec3(pixel, int(slot / 4u)), texel);
        texel = vec4(1.0);
    }
}

// Forward shading drops the sun's receiver-plane gradients where the pixel's 2 x 2 quad
// spans two cascades (fwidth of the cascade index): the same quads here, their pixels on
// the receiver's plane when it is known (as a triangle's helper invocations are), else
// where the depth puts them.
bool quad_spans_cascades(ivec2 pixel, float depth, vec3 position, vec3 face_normal, bool on_face, int cascade) {
    const ivec2 quad = pixel & ~1;
    for (int i = 0; i < 4; ++i) {
        const ivec2 other = quad + ivec2(i & 1, i >> 1);
        if (other == pixel) continue;
        vec3 other_position;
        if (on_face) {
            const Neighbour n = neighbour_on_plane(pixel, other - pixel, depth, position, face_normal);
            if (n.step == 0) continue;
            other_position = n.position;
        } else {
            if (any(greaterThanEqual(other, ivec2(resolve.width, resolve.height)))) continue;
            const float other_depth = depth_at(other);
            if (!has_geometry(other_depth)) continue;
            other_position = world_position(other, other_depth);
        }
        if (penumbra_sun_map_of(other_position) != cascade) return true;
    }
    return false;
}

// The caller's world -> clip for contact shadows, inverted once per workgroup rather than
// once per pixel.
shared mat4 contact_view_projection;

void main() {
    const bool contact = penumbra_shadow.contact_lights != 0u;  // a uniform: the same for every invocation
    if (contact) {
        if (gl_LocalInvocationIndex == 0u) contact_view_projection = inverse(resolve.inverse_view_projection);
        barrier();
    }
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(resolve.width) || pixel.y >= int(resolve.height)) return;
    const float depth = depth_at(pixel);
    vec4 texel = vec4(1.0);
    if (!has_geometry(depth)) {
        for (uint slot = 0u; slot < resolve.slot_count; ++slot) write_slot(pixel, slot, 1.0, texel);
        return;
    }
    const vec3 position = world_position(pixel, depth);
    const float view_depth = penumbra_view_depth(position);
    const vec3 face_normal = resolve.has_face_normals != 0u ? decode_face_normal(pixel) : vec3(0.0);
    const bool on_face = dot(face_normal, face_normal) > 0.0;
    const Neighbour x = on_face ? neighbour_on_plane(pixel, ivec2(1, 0), depth, position, face_normal)
                                : neighbour_along(pixel, ivec2(1, 0), view_depth);
    const Neighbour y = on_face ? neighbour_on_plane(pixel, ivec2(0, 1), depth, position, face_normal)
                                : neighbour_along(pixel, ivec2(0, 1), view_depth);
    const vec3 to_camera = camera_position() - position;

    // The geometric normal: the caller's, or from the neighbours, facing the camera.
    vec3 plane_normal = face_normal;
    if (!on_face && x.step != 0 && y.step != 0) {
        const vec3 n = cross(float(x.step) * (x.position - position), float(y.step) * (y.position - position));
        if (dot(n, n) > 1e-20) plane_normal = normalize(n);
    }
    vec3 normal = resolve.has_normals != 0u ? decode_normal(pixel) : plane_normal;
    if (resolve.has_normals == 0u && dot(normal, to_camera) < 0.0) normal = -normal;
    if (dot(plane_normal, plane_normal) == 0.0) plane_normal = normal;
    if (dot(normal, normal) == 0.0) normal = normalize(to_camera);  // a lone pixel: face the camera

    const vec2 centre = vec2(pixel) + 0.5;
    PenumbraSunReceiver receiver = penumbra_sun_receiver(position, normal, centre);
    // The sun's face test by the surface's own plane, as penumbra_sun_receiver_fragment() in
    // forward shading: a smooth normal alone lets faces turned from the sun pass (leaves).
    receiver.face_normal = plane_normal;
    if (x.step != 0 && y.step != 0) {
        const ivec2 cascades = penumbra_receiver_cascades(receiver.cascade);
        vec3 coord_dx[2];
        vec3 coord_dy[2];
        for (int i = 0; i < 2; ++i) {
            const vec3 coord = penumbra_project_to_cascade(cascades[i], position, normal);
            coord_dx[i] = float(x.step) * (penumbra_project_to_cascade(cascades[i], x.position, normal) - coord);
            coord_dy[i] = float(y.step) * (penumbra_project_to_cascade(cascades[i], y.position, normal) - coord);
        }
        // Forward shading has no gradient where its quad spans two cascades; the virtual
        // map's levels break no derivative there (penumbra_sun_receiver_with_derivatives).
        const bool seam = !penumbra_sun_is_virtual() &&
                          quad_spans_cascades(pixel, depth, position, face_normal, on_face, receiver.cascade);
        penumbra_set_receiver_plane(receiver, coord_dx, coord_dy, seam);
    }
    // Contact shadows (Settings::contact) trace this depth buffer from the visible side of
    // the surface; the visibility is the darker of the map's and the trace's.
    PenumbraContactScreen screen;
    vec3 contact_normal = plane_normal;
    if (contact) {
        screen = PenumbraContactScreen(contact_view_projection, resolve.inverse_view_projection,
                                       vec2(resolve.width, resolve.height), resolve.background_depth);
        if (dot(contact_normal, to_camera) < 0.0) contact_normal = -contact_normal;
    }
    float sun = penumbra_sun_visibility(receiver, normal);
    if (contact && sun > 0.0)
        sun = min(sun, penumbra_sun_contact(screen_depth, screen, position, contact_normal, centre));
    write_slot(pixel, 0u, sun, texel);
    for (uint slot = 1u; slot < resolve.slot_count; ++slot) {
        const uint shadowed = slot - 1u;
        const uint light = penumbra_local.shadowed_lights[shadowed / 4u][shadowed % 4u];
        float visibility = penumbra_light_visibility(light, position, normal, plane_normal, centre);
        if (contact && visibility > 0.0) {
            visibility =
                min(visibility, penumbra_light_contact(light, screen_depth, screen, position, contact_normal, centre));
        }
        write_slot(pixel, slot, visibility, texel);
    }
}
