// The engine example's pixel shader, in HLSL through Penumbra's HLSL shadow library
// (penumbra/shadow.hlsl): the sun's visibility of the forward-shaded view, with the filter
// of Penumbra's specialization constants (rebuilt when update_settings() says so).
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
