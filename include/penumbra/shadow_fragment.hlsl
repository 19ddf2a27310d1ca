// Pixel-shader helpers of penumbra/shadow.hlsl (include it first), as
// penumbra/shadow_fragment.glsl's: receiver-plane gradients and the geometric normal from
// screen-space derivatives, so call them in uniform control flow, before any discard or
// per-pixel branch. `pixel` is the pixel's centre (SV_Position.xy).
//   float3 penumbra_geometric_normal(world_position, shading_normal)
//   PenumbraSunReceiver penumbra_sun_receiver_fragment(world_position, normal, pixel)
#ifndef PENUMBRA_SHADOW_FRAGMENT_HLSL
#define PENUMBRA_SHADOW_FRAGMENT_HLSL

#include "penumbra/hlsl/dialect_begin.hlsl"
#include "penumbra/glsl/fragment.glsl"
#include "penumbra/hlsl/dialect_end.hlsl"

PenumbraSunReceiver penumbra_sun_receiver_fragment(float3 world_position, float3 normal, float2 pixel) {
    return penumbra_sun_receiver_with_derivatives(world_position, normal, pixel);
}

#endif
