// The shadow library's texture reads in GLSL (penumbra/hlsl/reads.hlsl has the same in
// HLSL): the filters and the contact trace read maps only through these.
#ifndef PENUMBRA_GLSL_READS
#define PENUMBRA_GLSL_READS

#include "penumbra/glsl/dialect.glsl"

// One bilinear comparison tap of a layered map: the fraction of the four texels around `uv`
// (weighted bilinearly) whose stored depth the reference passes (the sampler's compare op).
float penumbra_map_compare(PENUMBRA_COMPARISON_ARRAY(map), vec2 uv, float layer, float reference) {
    return texture(map, vec4(uv, layer, reference));
}

// The comparisons of the four texels whose lowest one is `first` (texel indices; the map
// repeats beyond its edges), in textureGather's order: x (0, 1), y (1, 1), z (1, 0), w (0, 0).
vec4 penumbra_map_compare_quad(PENUMBRA_COMPARISON_ARRAY(map), vec2 first, float texel_uv, float layer, float reference) {
    return textureGather(map, vec3((first + 1.0) * texel_uv, layer), reference);
}

// What the sampler of a layered map reads at `uv`: the stored depth, or the moments.
vec4 penumbra_map_read(PENUMBRA_TEXTURE_ARRAY(map), vec2 uv, float layer) { return texture(map, vec3(uv, layer)); }

// penumbra_map_compare at the first mip level, where implicit derivatives are undefined
// (divergent control flow); GLSL has no textureLod for array comparison samplers.
float penumbra_map_compare_level_zero(PENUMBRA_COMPARISON_ARRAY(map), vec2 uv, float layer, float reference) {
    return textureGrad(map, vec4(uv, layer, reference), vec2(0.0), vec2(0.0));
}

// The depths of the four texels around `uv`, in textureGather's order (above).
vec4 penumbra_depth_quad(PENUMBRA_DEPTH_TEXTURE(map), vec2 uv) { return textureGather(map, uv, 0); }

// The depth of one texel.
float penumbra_depth_texel(PENUMBRA_DEPTH_TEXTURE(map), ivec2 texel) { return texelFetch(map, texel, 0).r; }

// The stored depth of one texel of a layered map.
float penumbra_map_texel(PENUMBRA_TEXTURE_ARRAY(map), ivec2 texel, int layer) {
    return texelFetch(map, ivec3(texel, layer), 0).r;
}

#endif
