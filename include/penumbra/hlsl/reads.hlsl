// The shadow library's texture reads in HLSL: what penumbra/glsl/reads.glsl does in GLSL,
// with the same results. Every map has one mip level, so the reads name level 0 (as
// GLSL's implicit level does there) and work in every stage.
#ifndef PENUMBRA_HLSL_READS
#define PENUMBRA_HLSL_READS

float penumbra_map_compare(PENUMBRA_COMPARISON_ARRAY(map), float2 uv, float layer, float reference) {
    return map.SampleCmpLevelZero(map_sampler, float3(uv, layer), reference);
}

int2 penumbra_repeat_texel(int2 texel, int2 size) { return ((texel % size) + size) % size; }

// Four texel reads compared in the shader: the same texels and the same comparison as a
// comparison gather (reference >= stored, VK_COMPARE_OP_GREATER_OR_EQUAL), which glslang's
// HLSL front end does not translate to valid SPIR-V (GatherCmp gets a Bias operand).
float4 penumbra_map_compare_quad(PENUMBRA_COMPARISON_ARRAY(map), float2 first, float texel_uv, float layer,
                                 float reference) {
    uint width, height, layers;
    map.GetDimensions(width, height, layers);
    const int2 size = int2(int(width), int(height));
    const int2 base = int2(first);
    const int2 offsets[4] = {int2(0, 1), int2(1, 1), int2(1, 0), int2(0, 0)};
    float4 lit;
    for (int i = 0; i < 4; ++i) {
        const int2 texel = penumbra_repeat_texel(base + offsets[i], size);
        lit[i] = reference >= map.Load(int4(texel, int(layer), 0)).r ? 1.0 : 0.0;
    }
    return lit;
}

float4 penumbra_map_read(PENUMBRA_TEXTURE_ARRAY(map), float2 uv, float layer) {
    return map.SampleLevel(map_sampler, float3(uv, layer), 0.0);
}

float penumbra_map_compare_level_zero(PENUMBRA_COMPARISON_ARRAY(map), float2 uv, float layer, float reference) {
    return map.SampleCmpLevelZero(map_sampler, float3(uv, layer), reference);
}

float4 penumbra_depth_quad(PENUMBRA_DEPTH_TEXTURE(map), float2 uv) { return map.GatherRed(map_sampler, uv); }

float penumbra_depth_texel(PENUMBRA_DEPTH_TEXTURE(map), int2 texel) { return map.Load(int3(texel, 0)); }

float penumbra_map_texel(PENUMBRA_TEXTURE_ARRAY(map), int2 texel, int layer) {
    return map.Load(int4(texel, layer, 0)).r;
}

#endif
