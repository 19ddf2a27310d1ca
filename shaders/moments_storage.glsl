// The moments map as a storage image for the moments compute passes
// (moments_convert.comp, moments_blur.comp), one variant per moments format
// (passes/moments_conversion.hpp): RG32F, RGBA32F, or RGBA16_UNORM written through an
// RG32_UINT view with two 16-bit values packed per channel (packUnorm2x16), which needs no
// device feature beyond Vulkan 1.3's core (an rgba16 format qualifier would need
// shaderStorageImageExtendedFormats). Declare images as
// `layout(PENUMBRA_MOMENTS_QUALIFIER) uniform PENUMBRA_MOMENTS_IMAGE name;`.
#ifndef PENUMBRA_MOMENTS_STORAGE_GLSL
#define PENUMBRA_MOMENTS_STORAGE_GLSL

#if defined(PENUMBRA_MOMENTS_RGBA16)
#define PENUMBRA_MOMENTS_QUALIFIER rg32ui
#define PENUMBRA_MOMENTS_IMAGE uimage2DArray
#define PENUMBRA_LOAD_MOMENTS(image, texel) penumbra_unpack_moments(imageLoad(image, texel).xy)
#define PENUMBRA_STORE_MOMENTS(image, texel, moments) imageStore(image, texel, penumbra_pack_moments(moments))
vec4 penumbra_unpack_moments(uvec2 packed) { return vec4(unpackUnorm2x16(packed.x), unpackUnorm2x16(packed.y)); }
uvec4 penumbra_pack_moments(vec4 moments) {
    return uvec4(packUnorm2x16(moments.xy), packUnorm2x16(moments.zw), 0u, 0u);
}
#else
#if defined(PENUMBRA_MOMENTS_RGBA32F)
#define PENUMBRA_MOMENTS_QUALIFIER rgba32f
#else
#define PENUMBRA_MOMENTS_QUALIFIER rg32f
#endif
#define PENUMBRA_MOMENTS_IMAGE image2DArray
#define PENUMBRA_LOAD_MOMENTS(image, texel) imageLoad(image, texel)
#define PENUMBRA_STORE_MOMENTS(image, texel, moments) imageStore(image, texel, moments)
#endif

// The texels a layer uses (MomentsPushConstants): `used` per side from layer texel
// `window.xy`, wrapping around the layer's side `window.z` (a toroidal cascade; a local
// light's corner starts at 0 and never wraps). Invocations run over used texels; taps
// beyond the used texels' edges clamp to them.
ivec2 penumbra_moments_layer_texel(MomentsPushConstants pass, ivec2 used_texel) {
    const ivec2 last = ivec2(int(pass.layer.y) - 1);
    return (clamp(used_texel, ivec2(0), last) + ivec2(pass.window.xy)) % int(pass.window.z);
}

#endif
