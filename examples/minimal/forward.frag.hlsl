// forward.frag in HLSL: the same pixel shader through Penumbra's HLSL shadow library
// (penumbra/shadow.hlsl), for engines whose shaders are HLSL. `penumbra_minimal --hlsl`
// uses it; the image is forward.frag's.
#define PENUMBRA_SHADOW_SET 0
#include "penumbra/shadow.hlsl"
#include "penumbra/shadow_fragment.hlsl"

struct PixelInput {
    float4 position : SV_Position;
    [[vk::location(0)]] float3 world_position : POSITION0;
    [[vk::location(1)]] float3 world_normal : NORMAL0;
};

[[vk::location(0)]] float main(PixelInput input) : SV_Target0 {
    const float3 normal = normalize(input.world_normal);
    const PenumbraSunReceiver receiver =
        penumbra_sun_receiver_fragment(input.world_position, normal, input.position.xy);
    return penumbra_sun_visibility(receiver, normal);
}
