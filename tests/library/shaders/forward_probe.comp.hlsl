// tests/library/shaders/forward_probe.comp in HLSL, through penumbra/shadow.hlsl: the same
// sun and local-light visibility at the same ground points, so that
// tests/library/test_forward_filter_modes.cpp can compare the HLSL library with the GLSL one.
#define PENUMBRA_SHADOW_SET 0
#include "penumbra/shadow.hlsl"

[[vk::binding(0, 1)]] RWStructuredBuffer<float2> values;

struct Probe {
    float half_extent;  // the ground's half-width the view sees (metres)
    uint size;          // pixels per side
    uint light;         // the local light's index in set_lights()
};
[[vk::push_constant]] ConstantBuffer<Probe> probe;

[numthreads(8, 8, 1)] void main(uint3 invocation : SV_DispatchThreadID) {
    const uint2 texel = invocation.xy;
    if (texel.x >= probe.size || texel.y >= probe.size) return;
    const float2 pixel = float2(texel) + 0.5;
    const float2 ndc = 2.0 * pixel / float(probe.size) - 1.0;
    const float3 world = float3(ndc.x * probe.half_extent, 0.0, ndc.y * probe.half_extent);
    const float3 up = float3(0.0, 1.0, 0.0);
    const float sun = penumbra_sun_visibility(penumbra_sun_receiver(world, up, pixel), up);
    const float local = penumbra_light_visibility(probe.light, world, up, up, pixel);
    values[texel.y * probe.size + texel.x] = float2(sun, local);
}
