// Screen-space contact shadows (Settings::contact; docs/techniques.md, "Contact shadows"):
// from a surface point, a short ray toward the light is marched through the caller's depth
// buffer, and a sample that lies behind the surface the depth buffer holds there (by less
// than Settings::contact.thickness) is occluded. This finds the shadows smaller than a
// shadow map's texels and biases: where a caster touches or nearly touches its receiver.
// The design of UE's contact shadows and of Bend Studio's screen-space shadows (Days Gone):
// samples spread along the ray with a per-pixel offset (interleaved gradient noise, Jimenez
// 2014) so that the steps do not band, a thickness so that thin objects do not shadow all
// behind them, and a fade with view distance.
//
// The compute resolve (ShadowSystem::record_visibility) calls these with the depth it is
// given; a forward shader calls them with a depth pre-pass of the same frame:
//   PenumbraContactScreen screen = PenumbraContactScreen(view_projection, inverse_view_projection,
//                                                        vec2(width, height), background_depth);
//   float contact = penumbra_sun_contact(depth, screen, world_position, geometric_normal, gl_FragCoord.xy);
//   float visibility = min(penumbra_sun_visibility(receiver, normal), contact);
// Cost: Settings::contact.steps depth reads per ray (a four-texel gather within 4 texels of
// its start, one texel beyond), about a dozen multiply-adds and two divisions per read, and
// four 4 x 4 products per ray; none beyond contact_max_distance.
#ifndef PENUMBRA_GLSL_CONTACT
#define PENUMBRA_GLSL_CONTACT

#include "penumbra/glsl/dialect.glsl"

// What the trace reads of the caller's depth buffer.
struct PenumbraContactScreen {
    mat4 view_projection;          // world -> the depth buffer's clip space
    mat4 inverse_view_projection;  // clip -> world
    vec2 size;                     // the depth buffer's pixels
    float background_depth;        // where nothing was drawn (never occludes)
};

// A per-pixel offset in [0, 1) that moves with the frame (interleaved gradient noise).
float penumbra_contact_jitter(vec2 pixel) {
    const vec2 moved = floor(pixel) + 5.588238 * float(penumbra_shadow.frame_index % 64u);
    return fract(52.9829189 * fract(dot(moved, vec2(0.06711056, 0.00583715))));
}

// How strongly a hit darkens at this view depth: 1, fading to 0 over the last fifth of
// Settings::contact.max_distance.
float penumbra_contact_strength(vec3 world_position) {
    const float far_end = penumbra_shadow.contact_max_distance;
    return 1.0 - smoothstep(0.8 * far_end, far_end, penumbra_view_depth(world_position));
}

// The camera's view depth (penumbra_view_depth()) as an affine function of the world
// point: dot(row, vec4(point, 1)).
vec4 penumbra_view_depth_row() {
    const mat4 view = penumbra_shadow.camera_view;
    return -vec4(PENUMBRA_MATRIX_ELEMENT(view, 0, 2), PENUMBRA_MATRIX_ELEMENT(view, 1, 2), PENUMBRA_MATRIX_ELEMENT(view, 2, 2),
                 PENUMBRA_MATRIX_ELEMENT(view, 3, 2));
}

// View-depth differences across the four texels around a sample, relative to the nearer,
// up to which the surface is taken to be continuous there; beyond it, a silhouette. Small:
// a 6 mm step seen from 0.6 m (1 %) is a slab's edge, whose shadow interpolation would
// lose. A plane seen at a grazing angle at low resolution changes by more per texel and
// falls back to the nearest texel too, which there rarely finds the plane itself: seen at
// a grazing angle, a sample's height above it is magnified along the line of sight.
PENUMBRA_CONST float kPenumbraContactContinuous = 0.01;

// Texels from the start (each way) within which the trace interpolates the depth.
PENUMBRA_CONST float kPenumbraContactInterpolated = 4.0;

// The view depth of the surface the depth buffer holds at q = (ndc, depth, 1): with h =
// inverse_view_projection * q that surface is h.xyz / h.w, so its view depth is
// dot(depth_row, h) / h.w = dot(surface_row, q) / dot(w_row, q) (penumbra_contact_trace()).
float penumbra_contact_view_depth(vec2 ndc, float depth, vec4 surface_row, vec4 w_row) {
    const vec4 q = vec4(ndc, depth, 1.0);
    return dot(surface_row, q) / dot(w_row, q);
}

// The depth buffer's depth at `ndc`, interpolated between the four texel centres around it
// (Bend Studio's bilinear depth): point sampling puts a sloped surface up to half a texel's
// depth change in front of the samples just above it, so that the trace finds the surface it
// starts from (acne of the trace, worst on ground seen at a grazing angle). NDC depth is
// affine in screen space across a plane, so the interpolation is exact on planes. Across a
// silhouette (view depths differing by more than kPenumbraContactContinuous) it would make a
// surface between the two: there the nearest texel's depth is used, as where any is empty.
// Under a perspective projection a surface's view depth is 1 / h.w with h.w = dot(w_row, q)
// affine in the depth, so the relative difference of the nearest and farthest of the four is
// |w_row.z (high - low)| / the larger h.w: no division per sample. (Under an orthographic
// projection h.w is constant and every four count as continuous.)
float penumbra_contact_depth(PENUMBRA_DEPTH_TEXTURE(depth_buffer), PenumbraContactScreen screen, vec2 ndc, vec4 w_row) {
    const vec2 position = (ndc * 0.5 + 0.5) * screen.size - 0.5;  // texel centres at integers
    const vec2 corner = floor(position);
    const vec2 f = position - corner;
    // x: (i, j + 1), y: (i + 1, j + 1), z: (i + 1, j), w: (i, j), with (i, j) = corner.
    const vec4 d = penumbra_depth_quad(PENUMBRA_MAP(depth_buffer), (corner + 1.0) / screen.size);
    const float low = min(min(d.x, d.y), min(d.z, d.w));
    const float high = max(max(d.x, d.y), max(d.z, d.w));
    const bool empty = any(equal(d, vec4(screen.background_depth)));
    const float w_low = dot(w_row, vec4(ndc, low, 1.0));
    const float w_high = w_low + w_row.z * (high - low);
    if (empty || abs(w_high - w_low) > kPenumbraContactContinuous * max(abs(w_low), abs(w_high))) {
        return f.y >= 0.5 ? (f.x >= 0.5 ? d.y : d.x) : (f.x >= 0.5 ? d.z : d.w);
    }
    return mix(mix(d.w, d.z, f.x), mix(d.x, d.y, f.x), f.y);
}

// 0 where a sample of the ray from `start` along `ray` (its whole length) lies behind the
// depth buffer's surface by less than the thickness, else 1.
float penumbra_contact_trace(PENUMBRA_DEPTH_TEXTURE(depth_buffer), PenumbraContactScreen screen, vec3 start, vec3 ray, float jitter) {
    const uint steps = penumbra_shadow.contact_steps;
    // Clip coordinates and view depth are affine in the world point, so along the ray they
    // advance by constant amounts: the matrix products are per ray, not per sample.
    const vec4 clip_start = PENUMBRA_MUL(screen.view_projection, vec4(start, 1.0));
    const vec4 clip_ray = PENUMBRA_MUL(screen.view_projection, vec4(ray, 0.0));
    const vec4 depth_row = penumbra_view_depth_row();
    const float depth_start = dot(depth_row, vec4(start, 1.0));
    const float depth_ray = dot(depth_row.xyz, ray);
    // For penumbra_contact_view_depth().
    const vec4 surface_row = PENUMBRA_ROW_MUL(depth_row, screen.inverse_view_projection);
    const vec4 w_row = PENUMBRA_ROW_MUL(vec4(0.0, 0.0, 0.0, 1.0), screen.inverse_view_projection);
    // Samples still inside the start's own texel can only find the surface the ray leaves
    // (at silhouettes, where the depth is not interpolated, it lies up to a texel's depth
    // change in front of them): they are skipped.
    const vec2 start_texel = (clip_start.xy / clip_start.w * 0.5 + 0.5) * screen.size;
    for (uint i = 0u; i < steps; ++i) {
        const float along = (float(i) + jitter) / float(steps);
        const vec4 clip = clip_start + clip_ray * along;
        if (clip.w <= 0.0) break;  // behind the camera: the depth buffer knows nothing there
        const vec2 ndc = clip.xy / clip.w;
        if (any(greaterThan(abs(ndc), vec2(1.0)))) break;  // off the screen, likewise
        const vec2 texel_position = (ndc * 0.5 + 0.5) * screen.size;
        const vec2 from_start = abs(texel_position - start_texel);
        if (all(lessThan(from_start, vec2(1.0)))) continue;
        // Near the start the samples lie little above the surface they left, within the
        // error of a point-sampled depth: interpolate there; farther on, one texel is enough.
        const float stored = all(lessThan(from_start, vec2(kPenumbraContactInterpolated)))
                                 ? penumbra_contact_depth(PENUMBRA_MAP(depth_buffer), screen, ndc, w_row)
                                 : penumbra_depth_texel(PENUMBRA_MAP(depth_buffer), min(ivec2(texel_position), ivec2(screen.size) - 1));
        if (stored == screen.background_depth) continue;
        // How far the sample lies behind the surface on its own line of sight.
        const float behind =
            depth_start + depth_ray * along - penumbra_contact_view_depth(ndc, stored, surface_row, w_row);
        if (behind > 0.0 && behind < penumbra_shadow.contact_thickness) return 0.0;
    }
    return 1.0;
}

// The contact visibility toward a light, over `ray_length` metres along `to_light` (unit): 1
// lit, down to 0 where the trace finds an occluder.
float penumbra_contact_toward(PENUMBRA_DEPTH_TEXTURE(depth_buffer), PenumbraContactScreen screen, vec3 world_position,
                              vec3 geometric_normal, vec3 to_light, float ray_length, vec2 pixel) {
    const float strength = penumbra_contact_strength(world_position);
    if (strength <= 0.0) return 1.0;  // beyond contact_max_distance: no samples
    const vec3 start = world_position + geometric_normal * penumbra_shadow.contact_bias;
    const float lit =
        penumbra_contact_trace(PENUMBRA_MAP(depth_buffer), screen, start, to_light * ray_length, penumbra_contact_jitter(pixel));
    return 1.0 - (1.0 - lit) * strength;
}

// The sun's contact visibility (1 when Settings::contact leaves the sun out or there is
// no sun). `geometric_normal`: the surface's face normal, toward the camera.
float penumbra_sun_contact(PENUMBRA_DEPTH_TEXTURE(depth_buffer), PenumbraContactScreen screen, vec3 world_position,
                           vec3 geometric_normal, vec2 pixel) {
    if ((penumbra_shadow.contact_lights & PENUMBRA_CONTACT_SUN) == 0u || penumbra_shadow.to_sun.w == 0.0) return 1.0;
    return penumbra_contact_toward(PENUMBRA_MAP(depth_buffer), screen, world_position, geometric_normal, penumbra_shadow.to_sun.xyz,
                                   penumbra_shadow.contact_length, pixel);
}

// Spot or point light `index`'s contact visibility; the ray stops at the light.
float penumbra_light_contact(uint index, PENUMBRA_DEPTH_TEXTURE(depth_buffer), PenumbraContactScreen screen, vec3 world_position,
                             vec3 geometric_normal, vec2 pixel) {
    if ((penumbra_shadow.contact_lights & PENUMBRA_CONTACT_LOCAL) == 0u || index >= penumbra_local.light_count)
        return 1.0;
    const vec3 to_light = penumbra_local.lights[index].position - world_position;
    const float distance = length(to_light);
    if (distance <= 0.0) return 1.0;
    return penumbra_contact_toward(PENUMBRA_MAP(depth_buffer), screen, world_position, geometric_normal, to_light / distance,
                                   min(penumbra_shadow.contact_length, distance), pixel);
}

#endif
