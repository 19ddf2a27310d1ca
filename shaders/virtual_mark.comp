#version 460
// Virtual shadow maps, step 1 of a frame: page marking (UE5's "mark pages" pass). One
// thread per 2 x 2 pixels of the caller's depth buffer: each pixel's world position selects the
// clipmap level whose texel matches its footprint (virtual_clipmap.glsl), and every page
// its filter reads around it (the filter's reach plus the normal offset, in that level's
// texels) is requested. Nothing is read back: the allocation passes take the requests
// from here. Pixels without geometry, or beyond the shadow distance, request nothing.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std140, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_CLIPMAP) uniform ClipmapBlock {
    PenumbraVirtualClipmap clipmap;
};
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_REQUESTS) buffer Requests { uint requests[]; };
layout(set = 1, binding = PENUMBRA_BINDING_VIRTUAL_DEPTH) uniform sampler2D screen_depth;
layout(push_constant) uniform PushBlock { VirtualMarkPushConstants mark; };

#define PENUMBRA_VIRTUAL_CLIPMAP clipmap
#include "penumbra/glsl/virtual_clipmap.glsl"

vec3 world_position(ivec2 pixel, float depth) {
    const vec2 ndc = (vec2(pixel) + 0.5) / vec2(mark.width, mark.height) * 2.0 - 1.0;
    const vec4 world = mark.inverse_view_projection * vec4(ndc, depth, 1.0);
    return world.xyz / world.w;
}

// Every page of `level` that a filter reading `radius` texels around the receiver (across
// the light at `light_xy`) touches.
void request_pages(uint level, vec2 light_xy, float radius) {
    const vec2 texel = penumbra_virtual_texel_at(level, light_xy);
    const ivec2 limit = ivec2(clipmap.pages_per_side);
    const float page = float(kPenumbraVirtualPageTexels);
    const ivec2 first = clamp(ivec2(floor((texel - radius) / page)), ivec2(0), limit);
    const ivec2 last = clamp(ivec2(floor((texel + radius) / page)) + 1, ivec2(0), limit);
    const uint stamp = PENUMBRA_VIRTUAL_REQUEST_STAMP(clipmap.frame);
    for (int y = first.y; y < last.y; ++y) {
        for (int x = first.x; x < last.x; ++x) {
            const uint entry = penumbra_virtual_entry(level, ivec2(x, y));
            // Many pixels request one page: a plain store of the same value (no atomic),
            // the frame's stamp (no clearing of the requests between frames).
            if (requests[entry] != stamp) requests[entry] = stamp;
        }
    }
}

// The requests of one pixel.
void mark_pixel(ivec2 pixel) {
    if (pixel.x >= int(mark.width) || pixel.y >= int(mark.height)) return;
    const float depth = texelFetch(screen_depth, pixel, 0).r;
    if (depth == mark.background_depth) return;
    const vec3 position = world_position(pixel, depth);
    if (-(clipmap.camera_view * vec4(position, 1.0)).z > clipmap.shadow_distance) return;
    const float radius = clipmap.mark_radius_texels;
    const int level = penumbra_select_virtual_level(position, radius);
    if (level < 0) return;
    const vec2 light_xy = penumbra_virtual_light_xy(position);
    request_pages(uint(level), light_xy, radius);
    // The next coarser level too: a receiver whose page the pool cannot serve samples it.
    if (level + 1 < int(clipmap.level_count)) request_pages(uint(level + 1), light_xy, radius);
}

// Each thread marks a block of kPixelsPerThread^2 pixels: what a pixel costs is small next to
// starting a workgroup (a 4K screen at one pixel per thread is 130,000 workgroups).
const int kPixelsPerThread = 2;

void main() {
    const ivec2 first = ivec2(gl_GlobalInvocationID.xy) * kPixelsPerThread;
    for (int y = 0; y < kPixelsPerThread; ++y) {
        for (int x = 0; x < kPixelsPerThread; ++x) mark_pixel(first + ivec2(x, y));
    }
}
