// Every shadow filter, written once for the sun's cascades and for the spot and point
// lights' layers (included by penumbra/shadow.glsl before sun.glsl and local.glsl), and the
// one switch over kPenumbraFilterMode: a new filter is a function and a case here.
//
// A filter sees a receiver through a PenumbraShadowView, which sun.glsl (a cascade:
// orthographic) and local.glsl (a light's corner of a layer: perspective) build, and reads
// the maps it is given as parameters, as Filament's ShadowSample_PCSS(DIRECTIONAL, ...)
// serves every light type with one body. Comparison filters (hard, pcf, poisson, pcss)
// read the depth map through a comparison sampler: each hardware tap is itself a bilinear
// 2x2 percentage-closer filter (Reeves et al. 1987). Moment filters (vsm, evsm, msm) read
// the moments map that Penumbra's moments conversion rendered and blurred.
#ifndef PENUMBRA_GLSL_FILTERS
#define PENUMBRA_GLSL_FILTERS

#include "penumbra/glsl/dialect.glsl"

// A receiver in one shadow map, as the filters see it.
struct PenumbraShadowView {
    vec2 uv;              // the receiver in the map
    float layer;          // its array layer
    float depth;          // reverse-Z depth of the receiver (1 = nearest the light)
    vec2 depth_gradient;  // receiver plane dz/du, dz/dv (0 without receiver-plane bias)
    float texel_uv;       // one texel of the map in UV
    vec4 uv_bounds;       // every tap is clamped to [xy, zw] (the texels the view's map uses)
    vec2 uv_offset;       // the layer UV of the view's UV 0 (a toroidal cascade's layer_origin; samplers repeat)
    // PCSS (Fernando 2005). Distances are along the light's axis, in the units that
    // pcss_depth_to_distance gives a stored depth.
    vec2 pcss_search_radius;       // the blocker search's radius in UV, before its clamp
    vec2 pcss_penumbra_scale;      // penumbra radius in UV per unit of (receiver - blocker) distance,
    bool pcss_perspective;         // ... and per unit of blocker distance (a light at a finite distance)
    float pcss_receiver_distance;  // the receiver's distance
    vec4 pcss_depth_to_distance;   // distance = (x + y d) / (z + w d) of a stored reverse-Z depth d
    float moments_distance;        // the receiver's distance as the moments store it (0..1)
    // The depth bias the shadow pass gave the map's casters: slope factor, largest bias.
    float caster_slope_bias;
    float caster_bias_clamp;
    // The sun's virtual shadow map level the view reads (penumbra/glsl/virtual.glsl: every
    // texel through the page table), or -1 for a map of the given samplers.
    int virtual_level;
};

// Rotation of the Poisson patterns: interleaved gradient noise per pixel (Jimenez 2014,
// "Next Generation Post Processing in Call of Duty: Advanced Warfare") plus a golden-ratio
// step per frame, so that successive frames sample new directions and a temporal filter
// can accumulate them. The frame step is Fibonacci hashing (frame * 2^32 / phi, wrapping),
// exact for any frame index, where fract(frame * 0.618) would lose precision.
mat2 penumbra_sample_rotation(vec2 pixel) {
    const float noise = fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
    const float frame_offset = float(penumbra_shadow.frame_index * 2654435769u) * (1.0 / 4294967296.0);
    const float angle = 6.28318530718 * fract(noise + frame_offset);
    const float c = cos(angle);
    const float s = sin(angle);
    return PENUMBRA_MAT2_COLUMNS(vec2(c, s), vec2(-s, c));
}

// The gradient (dz/du, dz/dv) of a plane over a map whose depth changes by `depth_steps`.x
// over the UV step `step_x` and by .y over `step_y`: with J the matrix of the two steps as
// columns, the gradient is depth_steps J^-1 (written out for the 2 x 2 case). 0 where the
// steps are parallel, their determinant below `min_determinant` in magnitude.
vec2 penumbra_plane_gradient(vec2 depth_steps, vec2 step_x, vec2 step_y, float min_determinant) {
    const float det = step_x.x * step_y.y - step_y.x * step_x.y;
    if (abs(det) < min_determinant) return vec2(0.0);
    return vec2(depth_steps.x * step_y.y - depth_steps.y * step_x.y, depth_steps.y * step_x.x - depth_steps.x * step_y.x) /
           det;
}

// The UV of a tap `offset` (UV) away from the receiver, inside the view's bounds, so that
// no tap of a local light reads another light's texels or a neighbouring cube face, and
// no tap of a toroidal cascade reads the opposite edge where the cascade wraps.
vec2 penumbra_view_tap(PenumbraShadowView view, vec2 offset) {
    return clamp(view.uv + offset, view.uv_bounds.xy, view.uv_bounds.zw);
}

// Where a tap's UV lies in the map layer (the samplers repeat: a toroidal cascade wraps).
vec2 penumbra_layer_uv(PenumbraShadowView view, vec2 tap_uv) { return tap_uv + view.uv_offset; }

// The share of the receiver-plane bias's sampling error kept although the depth pass's
// slope bias covers it, measured (docs/filters.md, "Receiver-plane depth bias"): 0
// speckles creases (box-on-plane, one cascade, pcf: mean |error| 0.0008 -> 0.0018), 0.75
// and 1 let ClearCoatTest's ground light up under its tiles (pcf: 3.1 and 5.2 % false lit
// outside edges), 0.5 does neither (0.0010; 0.28 %).
PENUMBRA_CONST float kPenumbraReceiverPlaneSlack = 0.5;

// Bias for the texels a tap actually compares: a bilinear comparison reads texel centres
// up to one texel away from the tap on each axis, where the receiver's plane has moved
// by |dz/du| + |dz/dv| texels' worth (the "fractional sampling error" of receiver-plane
// bias, Isidoro 2006). The shadow pass already pushed every caster back by its
// slope-scaled depth bias: the slope factor times the caster's larger depth slope per
// texel, up to the clamp (vkCmdSetDepthBias). Where the caster is the receiver's own
// surface, the acne this term is for, that is slope_bias * max(|dz/du|, |dz/dv|) per
// texel, all of the error from a slope factor of 2 up unless clamped. So the term is the
// part of the error the slope bias leaves, plus kPenumbraReceiverPlaneSlack of the part
// it covers: slack for where the receiver is no plane (a wall meeting the floor, whose
// plane the outer taps extend across the crease) and for the screen-space gradient's
// error. The whole error on top of the slope bias let receivers light up under casters
// closer than both biases together (the ground 3 cm under ClearCoatTest's tiles, issue
// 16); none of it left speckles along creases. A comparison at the receiver itself extends
// the plane nowhere and takes no slack (`slack` 0). Zero without receiver-plane bias.
float penumbra_receiver_plane_bias_term(PenumbraShadowView view, float slack) {
    const vec2 slope_per_texel = abs(view.depth_gradient) * view.texel_uv;
    const float sampling_error = slope_per_texel.x + slope_per_texel.y;
    const float slope_bias = view.caster_slope_bias * max(slope_per_texel.x, slope_per_texel.y);
    const float caster_bias = min(slope_bias, view.caster_bias_clamp);
    const float covered = min(sampling_error, caster_bias);
    return sampling_error - covered + slack * covered;
}

// The static bias of a kernel's taps (pcf, poisson, PCSS's search and disk).
float penumbra_receiver_plane_static_bias(PenumbraShadowView view) {
    return penumbra_receiver_plane_bias_term(view, kPenumbraReceiverPlaneSlack);
}

// The static bias of one comparison at the receiver (PCSS's centre and narrow taps).
float penumbra_receiver_plane_centre_bias(PenumbraShadowView view) {
    return penumbra_receiver_plane_bias_term(view, 0.0);
}

// The receiver's depth at a tap's UV: with receiver-plane bias (Isidoro 2006) it follows
// the receiver's plane to the tap (the clamped one, where the texels are read).
float penumbra_reference_depth(PenumbraShadowView view, vec2 tap_uv, float static_bias) {
    return view.depth + dot(view.depth_gradient, tap_uv - view.uv) + static_bias;
}

// A bilinear comparison at `uv` of the view's map: one hardware comparison tap, or four
// texel reads through a virtual shadow map's pages. (One return after an if/else: an early
// return here crashes the SPIR-V optimizer of Debian 12's glslc, shaderc 2023.2, at -O.)
float penumbra_compare_at(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view, vec2 uv, float reference) {
    float lit;
    if (view.virtual_level >= 0) {
        lit = penumbra_virtual_compare(uint(view.virtual_level), uv, reference);
    } else {
        lit = penumbra_map_compare(PENUMBRA_MAP(map), penumbra_layer_uv(view, uv), view.layer, reference);
    }
    return lit;
}

// The stored depth under `uv` of the view's map (PCSS's blocker search).
float penumbra_depth_at(PENUMBRA_TEXTURE_ARRAY(depth_map), PenumbraShadowView view, vec2 uv) {
    float depth;
    if (view.virtual_level >= 0) {
        depth = penumbra_virtual_depth(uint(view.virtual_level), uv);
    } else {
        depth = penumbra_map_read(PENUMBRA_MAP(depth_map), penumbra_layer_uv(view, uv), view.layer).r;
    }
    return depth;
}

// One comparison tap `offset` (UV) away from the receiver.
float penumbra_compare_tap(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view, vec2 offset, float static_bias) {
    const vec2 uv = penumbra_view_tap(view, offset);
    return penumbra_compare_at(PENUMBRA_MAP(map), view, uv, penumbra_reference_depth(view, uv, static_bias));
}

// hard: one comparison tap, no receiver-plane bias.
float penumbra_filter_hard(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view) {
    return penumbra_compare_at(PENUMBRA_MAP(map), view, penumbra_view_tap(view, vec2(0.0)), view.depth);
}

// pcf: the (2R+1) x (2R+1) grid of comparison taps one texel apart, as (R+1)^2 weighted
// taps (penumbra/glsl/pcf.glsl).
float penumbra_filter_pcf(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view) {
    const int radius = int(penumbra_shadow.pcf_radius);
    const float texel = view.texel_uv;
    const float bias = penumbra_receiver_plane_static_bias(view);
    const vec2 f = fract(view.uv / texel - 0.5);
    float lit = 0.0;
    for (int j = 0; j <= radius; ++j) {
        const vec2 y = penumbra_pcf_tap(f.y, radius, j);
        for (int i = 0; i <= radius; ++i) {
            const vec2 x = penumbra_pcf_tap(f.x, radius, i);
            lit += x.y * y.y * penumbra_compare_tap(PENUMBRA_MAP(map), view, vec2(x.x, y.x) * texel, bias);
        }
    }
    const float side = float(2 * radius + 1);
    return lit / (side * side);
}

// The average of comparison taps over a rotated Poisson disk of per-axis radius `radius_uv`.
float penumbra_poisson_comparisons(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view, uint taps, vec2 radius_uv,
                                   mat2 rotation) {
    const float bias = penumbra_receiver_plane_static_bias(view);
    float lit = 0.0;
    for (uint i = 0u; i < taps; ++i) {
        lit += penumbra_compare_tap(PENUMBRA_MAP(map), view, PENUMBRA_MUL(rotation, penumbra_poisson_tap(taps, i)) * radius_uv, bias);
    }
    return lit / float(taps);
}

// poisson: 16 or 32 comparison taps on a Poisson disk of poisson_radius texels, rotated per pixel.
float penumbra_filter_poisson(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view, vec2 pixel) {
    const vec2 radius_uv = vec2(penumbra_shadow.poisson_radius_texels * view.texel_uv);
    return penumbra_poisson_comparisons(PENUMBRA_MAP(map), view, kPenumbraSearchTaps, radius_uv, penumbra_sample_rotation(pixel));
}

struct PenumbraBlockerSearch {
    float average_distance;  // of the blockers found (pcss_depth_to_distance)
    uint count;
};

// A stored reverse-Z depth as a distance along the light's axis: affine in depth for an
// orthographic map (w = 0), its inverse for a perspective one.
float penumbra_depth_to_distance(PenumbraShadowView view, float depth) {
    const vec4 terms = view.pcss_depth_to_distance;
    return (terms.x + terms.y * depth) / (terms.z + terms.w * depth);
}

// PCSS step 1 (Fernando 2005): raw depths nearer the light than the receiver's plane,
// over a rotated Poisson disk of the search radius.
PenumbraBlockerSearch penumbra_find_blockers(PENUMBRA_TEXTURE_ARRAY(depth_map), PenumbraShadowView view, vec2 radius_uv,
                                             mat2 rotation) {
    const float bias = penumbra_receiver_plane_static_bias(view);
    PenumbraBlockerSearch search;
    search.average_distance = 0.0;
    search.count = 0u;
    for (uint i = 0u; i < kPenumbraSearchTaps; ++i) {
        const vec2 uv = penumbra_view_tap(view, PENUMBRA_MUL(rotation, penumbra_poisson_tap(kPenumbraSearchTaps, i)) * radius_uv);
        const float stored = penumbra_depth_at(PENUMBRA_MAP(depth_map), view, uv);
        if (stored > penumbra_reference_depth(view, uv, bias)) {  // reverse-Z: larger = nearer the light
            search.average_distance += penumbra_depth_to_distance(view, stored);
            search.count += 1u;
        }
    }
    if (search.count > 0u) search.average_distance /= float(search.count);
    return search;
}

// PCSS step 2: the light's footprint radius on the receiver, by similar triangles, the
// (receiver - blocker) distance times the light's size; for a light at a finite distance
// (perspective) over the blocker's distance from it. A directional light's size is an
// angle: nothing to divide by.
vec2 penumbra_pcss_penumbra_radius(PenumbraShadowView view, float blocker_distance) {
    const vec2 footprint = (view.pcss_receiver_distance - blocker_distance) * view.pcss_penumbra_scale;
    return view.pcss_perspective ? footprint / max(blocker_distance, 1e-4) : footprint;
}

// PCSS step 3's Poisson disk for a light footprint of radius `penumbra_radius`. Every tap
// is a bilinear 2x2 comparison, which by itself spreads an edge over one texel: a box one
// texel wide, of per-axis variance texel^2 / 12. A uniform disk of radius r has a per-axis
// variance of r^2 / 4, and variances add under convolution, so the disk that makes
// disk (x) bilinear as wide as the light's disk of radius R has r^2 = R^2 - texel^2 / 3.
// Below R = texel / sqrt(3) the bilinear tap alone is already as wide as the light: r = 0.
// (A one-texel floor on the disk made PCSS about twice the ray-traced penumbra at the
// sun's usual sub-texel widths: issue 16, docs/QUALITY.md.)
vec2 penumbra_pcss_disk_radius(vec2 penumbra_radius, float texel) {
    return sqrt(max(penumbra_radius * penumbra_radius - vec2(texel * texel / 3.0), vec2(0.0)));
}

// A disk narrower than this fraction of a texel barely moves any tap's bilinear weights:
// PCSS then makes one comparison at the receiver, without the rotation's noise or its cost.
PENUMBRA_CONST float kPenumbraSingleTapDisk = 0.05;

bool penumbra_pcss_is_single_tap(vec2 disk_radius, float texel) {
    return max(disk_radius.x, disk_radius.y) < kPenumbraSingleTapDisk * texel;
}

// PCSS's comparison at the receiver itself: the hard filter's, plus the receiver-plane
// bias's static term when that bias is on (then PCSS's only protection against acne).
float penumbra_pcss_centre_tap(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view) {
    return penumbra_compare_tap(PENUMBRA_MAP(map), view, vec2(0.0), penumbra_receiver_plane_centre_bias(view));
}

// PCSS's comparison at the receiver for a light footprint of radius `penumbra_radius`
// (UV per axis) narrower than the bilinear comparison's own one-texel ramp: the same four
// texel comparisons (one gather, at the corner they share, so that the texels are exactly
// those the weights are computed for), weighted by a ramp as wide as the footprint. A
// ramp of width w has a per-axis variance of w^2 / 12, the light's disk r^2 / 4, so
// w = sqrt(3) r: one texel at r = texel / sqrt(3), where the Poisson disk takes over
// (penumbra_pcss_disk_radius); towards a contact, the nearest texel's comparison. The
// bilinear ramp made sub-texel penumbrae a texel wide (issue 16: ClearCoatTest's 0.04 px
// penumbra rendered 0.47 px wide, as the hard filter's).
float penumbra_pcss_narrow_tap(PENUMBRA_COMPARISON_ARRAY(map), PenumbraShadowView view, vec2 penumbra_radius) {
    const float texel = view.texel_uv;
    const vec2 uv = penumbra_view_tap(view, vec2(0.0));
    const vec2 position = penumbra_layer_uv(view, uv) / texel - 0.5;  // in texel centres
    const vec2 first = floor(position);
    const vec2 ramp = clamp(1.7320508 * penumbra_radius / texel, vec2(1e-4), vec2(1.0));
    const vec2 weight = clamp((position - first - 0.5) / ramp + 0.5, 0.0, 1.0);
    const float reference = penumbra_reference_depth(view, uv, penumbra_receiver_plane_centre_bias(view));
    // Gather order: x = (first.x, first.y + 1), y = (+1, +1), z = (+1, first.y), w = first.
    const vec4 lit = view.virtual_level >= 0
                         ? penumbra_virtual_gather(uint(view.virtual_level), ivec2(first), reference)
                         : penumbra_map_compare_quad(PENUMBRA_MAP(map), first, texel, view.layer, reference);
    return mix(mix(lit.w, lit.z, weight.x), mix(lit.x, lit.y, weight.x), weight.y);
}

// pcss: percentage-closer soft shadows (Fernando 2005). The view gives the light's
// geometry in UV per axis (a cascade whose X and Y extents differ gets an elliptical
// kernel). Where the penumbra is narrower than the bilinear comparison (the sun's usual
// case unless the caster is far), it is one comparison at the receiver, as hard is.
float penumbra_filter_pcss(PENUMBRA_COMPARISON_ARRAY(map), PENUMBRA_TEXTURE_ARRAY(depth_map), PenumbraShadowView view, vec2 pixel) {
    const float texel = view.texel_uv;
    const vec2 max_radius = vec2(texel * penumbra_shadow.pcss_max_penumbra_texels);
    const mat2 rotation = penumbra_sample_rotation(pixel);
    // 1. Blocker search over the light's disk seen from the receiver, as far as the
    //    light's near plane. None found: any occluder is nearer the receiver than the
    //    search's bias (a contact, a thin gap), so its penumbra is below a texel and the
    //    comparison at the receiver decides; returning lit there made contacts and thin
    //    gaps leak light. Every tap a blocker: the receiver is in the umbra (early out).
    const vec2 search_radius = clamp(view.pcss_search_radius, vec2(texel), max_radius);
    const PenumbraBlockerSearch blockers = penumbra_find_blockers(PENUMBRA_MAP(depth_map), view, search_radius, rotation);
    if (blockers.count == 0u) return penumbra_pcss_centre_tap(PENUMBRA_MAP(map), view);
    if (kPenumbraPcssEarlyOut && blockers.count == kPenumbraSearchTaps) return 0.0;
    // 2. Penumbra from the average blocker, at most the maximum.
    const vec2 penumbra_radius = min(penumbra_pcss_penumbra_radius(view, blockers.average_distance), max_radius);
    // 3. Variable-width Poisson PCF over the penumbra, less the taps' own bilinear width.
    //    Every blocker found counts: a fade toward lit below 3 blockers (removed) erased
    //    the shadows of thin casters, which only a few search taps hit.
    const vec2 disk_radius = penumbra_pcss_disk_radius(penumbra_radius, texel);
    if (penumbra_pcss_is_single_tap(disk_radius, texel)) return penumbra_pcss_narrow_tap(PENUMBRA_MAP(map), view, penumbra_radius);
    return penumbra_poisson_comparisons(PENUMBRA_MAP(map), view, kPenumbraFilterTaps, disk_radius, rotation);
}

// The smallest depth difference (in distance units, 0..1) that the moment filters
// resolve: the minimum variance is its square (warped for EVSM). It absorbs float
// rounding of the second moment (d^2 - mean^2 cancels).
PENUMBRA_CONST float kPenumbraMomentDepthTolerance = 5e-4;

// Linear filtering (and the optional Poisson taps of poisson_radius texels) average the
// moments: the average of a moment vector is the moment vector of the mixed
// distribution, which is why moments can be prefiltered at all.
vec4 penumbra_fetch_moments(PENUMBRA_TEXTURE_ARRAY(moments_map), PenumbraShadowView view, vec2 pixel) {
    if (!kPenumbraMomentsPoisson) {
        return penumbra_map_read(PENUMBRA_MAP(moments_map), penumbra_layer_uv(view, penumbra_view_tap(view, vec2(0.0))), view.layer);
    }
    const mat2 rotation = penumbra_sample_rotation(pixel);
    const vec2 radius_uv = vec2(penumbra_shadow.poisson_radius_texels * view.texel_uv);
    vec4 sum = vec4(0.0);
    for (uint i = 0u; i < 16u; ++i) {
        const vec2 uv = penumbra_view_tap(view, PENUMBRA_MUL(rotation, penumbra_poisson_tap(16u, i)) * radius_uv);
        sum += penumbra_map_read(PENUMBRA_MAP(moments_map), penumbra_layer_uv(view, uv), view.layer);
    }
    return sum / 16.0;
}

// Lauritzen 2007 (GPU Gems 3, ch. 8): light bleeding shows up as the low tail of the
// bound, so remap [amount, 1] to [0, 1], trading some softness for darker bleeding.
float penumbra_reduce_light_bleeding(float p_max, float amount) {
    return clamp((p_max - amount) / (1.0 - amount), 0.0, 1.0);
}

// Chebyshev's one-sided inequality (Donnelly & Lauritzen 2006): an upper bound on the
// fraction of occluders at least as far as `receiver`, given the mean and second moment.
float penumbra_chebyshev_upper_bound(vec2 moments, float receiver, float min_variance) {
    if (receiver <= moments.x) return 1.0;
    const float variance = max(moments.y - moments.x * moments.x, min_variance);
    const float difference = receiver - moments.x;
    return variance / (variance + difference * difference);
}

// vsm: Chebyshev's bound on (d, d^2).
float penumbra_vsm_visibility(vec4 moments, float receiver) {
    const float min_variance = kPenumbraMomentDepthTolerance * kPenumbraMomentDepthTolerance;
    return penumbra_chebyshev_upper_bound(moments.xy, receiver, min_variance);
}

// evsm: the bound on exponentially warped depths (Lauritzen & McCool 2008). The warp
// makes the receiver's distance to far occluders huge relative to the variance, which
// suppresses most of VSM's bleeding; the negative warp (4 components) bounds the other
// side. The tolerance is scaled by the warp's slope, d/dd e^{c w} = 2 c e^{c w}.
float penumbra_evsm_visibility(vec4 moments, float receiver, vec2 exponents) {
    const vec2 warped = penumbra_evsm_warp(receiver, exponents);
    const vec2 tolerance = kPenumbraMomentDepthTolerance * 2.0 * exponents * abs(warped);
    float p_max = penumbra_chebyshev_upper_bound(moments.xy, warped.x, tolerance.x * tolerance.x);
    if (kPenumbraEvsmComponents == 4u) {
        p_max = min(p_max, penumbra_chebyshev_upper_bound(moments.zw, warped.y, tolerance.y * tolerance.y));
    }
    return p_max;
}

// Peters & Klein 2015, Algorithm 3 ("Hamburger 4MSM"): the shadow intensity, the
// smallest possible fraction of occluders in front of `receiver` over all depth
// distributions with these four moments (bounded by a three-point distribution).
float penumbra_msm_hamburger_intensity(vec4 moments, float receiver, float moment_bias) {
    // 1. Bias the moments toward those of a spread distribution: keeps the Hankel matrix
    //    positive definite under rounding.
    const vec4 b = mix(moments, vec4(0.5), moment_bias);
    // 2. Solve [1 b1 b2; b1 b2 b3; b2 b3 b4] c = (1, z, z^2) by its LDL^T (Cholesky) factors.
    const float d2 = b.y - b.x * b.x;
    const float l32 = (b.z - b.x * b.y) / d2;
    const float d3 = b.w - b.y * b.y - l32 * l32 * d2;
    const float y2 = receiver - b.x;
    const float y3 = receiver * receiver - b.y - l32 * y2;
    const float c3 = y3 / d3;
    const float c2 = y2 / d2 - l32 * c3;
    const float c1 = 1.0 - b.x * c2 - b.y * c3;
    // 3. The other two support points: the roots of c3 z^2 + c2 z + c1.
    const float p = c2 / c3;
    const float q = c1 / c3;
    const float r = sqrt(max(0.25 * p * p - q, 0.0));
    const float z2 = -0.5 * p - r;
    const float z3 = -0.5 * p + r;
    // 4.-6. The weight of the support points in front of the receiver.
    if (receiver <= z2) return 0.0;
    if (receiver <= z3) {
        return clamp((receiver * z3 - b.x * (receiver + z3) + b.y) / ((z3 - z2) * (receiver - z2)), 0.0, 1.0);
    }
    return clamp(1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((receiver - z2) * (receiver - z3)), 0.0, 1.0);
}

// msm: four moments, optionally stored with the optimized quantization (an affine map,
// so it commutes with the filtering and is undone after it).
float penumbra_msm_visibility(vec4 moments, float receiver) {
    if (kPenumbraMsmQuantized) moments = penumbra_msm_dequantize(moments);
    return 1.0 - penumbra_msm_hamburger_intensity(moments, receiver, penumbra_shadow.msm_moment_bias);
}

// The visibility of a receiver at `receiver` (distance, 0..1, larger = farther from the
// light) through filtered `moments`, for the configured moment filter, with light-bleeding
// reduction.
float penumbra_moments_visibility(vec4 moments, float receiver) {
    float visibility;
    if (kPenumbraFilterMode == PENUMBRA_FILTER_EVSM) {
        const vec2 exponents = vec2(penumbra_shadow.evsm_positive_exponent, penumbra_shadow.evsm_negative_exponent);
        visibility = penumbra_evsm_visibility(moments, receiver, exponents);
    } else if (kPenumbraFilterMode == PENUMBRA_FILTER_MSM) {
        visibility = penumbra_msm_visibility(moments, receiver);
    } else {
        visibility = penumbra_vsm_visibility(moments, receiver);
    }
    return penumbra_reduce_light_bleeding(visibility, penumbra_shadow.light_bleeding_reduction);
}

// vsm, evsm, msm: the filtered moments around the receiver against its own distance.
float penumbra_filter_moments(PENUMBRA_TEXTURE_ARRAY(moments_map), PenumbraShadowView view, vec2 pixel) {
    return penumbra_moments_visibility(penumbra_fetch_moments(PENUMBRA_MAP(moments_map), view, pixel), view.moments_distance);
}

// The visibility of a receiver through one shadow map with the configured filter: the
// comparison sampler `map` and the raw `depth_map` of the same depth, and `moments_map`.
float penumbra_filter_shadow(PENUMBRA_COMPARISON_ARRAY(map), PENUMBRA_TEXTURE_ARRAY(depth_map), PENUMBRA_TEXTURE_ARRAY(moments_map),
                             PenumbraShadowView view, vec2 pixel) {
    switch (kPenumbraFilterMode) {
        case PENUMBRA_FILTER_PCF:
            return penumbra_filter_pcf(PENUMBRA_MAP(map), view);
        case PENUMBRA_FILTER_POISSON:
            return penumbra_filter_poisson(PENUMBRA_MAP(map), view, pixel);
        case PENUMBRA_FILTER_PCSS:
            return penumbra_filter_pcss(PENUMBRA_MAP(map), PENUMBRA_MAP(depth_map), view, pixel);
        case PENUMBRA_FILTER_VSM:
        case PENUMBRA_FILTER_EVSM:
        case PENUMBRA_FILTER_MSM:
            return penumbra_filter_moments(PENUMBRA_MAP(moments_map), view, pixel);
        default:  // PENUMBRA_FILTER_HARD
            return penumbra_filter_hard(PENUMBRA_MAP(map), view);
    }
}

#endif
