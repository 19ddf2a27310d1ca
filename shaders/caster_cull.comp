#version 460
// GPU-driven caster culling (the layered strategy): one invocation per caster draw tests its
// world bounds against every cascade and appends, for each cascade it can shadow, one
// indexed indirect command to its bucket (the draws sharing one pipeline state). The
// command's firstInstance is its own index, which the layered vertex shader
// (caster.vert, PENUMBRA_GPU_DRIVEN) reads the draw and its layer back from.
//
// The test is the CPU culling's (core/shadow_cache.cpp caster_footprint, the non-empty
// case) in the same operations and order, so that both select the same casters: the box
// bounded in clip space by Arvo's method (scene.hpp transform_aabb), culled only beyond the
// far side (depth < 0, reverse-Z) and outside the window's [-1, 1] rectangle; a box whose
// projection is not finite may reach every texel.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(local_size_x = 64) in;

layout(std140, set = PENUMBRA_SET_CASTER_FRAME, binding = PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS) uniform ShadowBlock {
    PenumbraShadowUniforms shadow;
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_INSTANCES) readonly buffer Instances {
    CullInstance instances[];
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_BUCKETS) readonly buffer Buckets {
    uint bucket_first_command[];
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_RECORDS) writeonly buffer Records {
    CullRecord records[];
};
// VkDrawIndexedIndirectCommand: indexCount, instanceCount, firstIndex, vertexOffset, firstInstance.
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_COMMANDS) writeonly buffer Commands {
    uint commands[];
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_COUNTS) buffer Counts {
    uint counts[];
};

layout(push_constant) uniform PushBlock { CullPushConstants cull; };

bool finite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

bool may_shadow(mat4 view_projection, vec3 box_min, vec3 box_max) {
    precise vec3 low = view_projection[3].xyz;
    precise vec3 high = view_projection[3].xyz;
    for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) {
            precise float a = view_projection[column][row] * box_min[column];
            precise float b = view_projection[column][row] * box_max[column];
            low[row] += min(a, b);
            high[row] += max(a, b);
        }
    }
    if (!finite(low) || !finite(high)) return true;
    if (high.z < 0.0) return false;
    return !(low.x > 1.0 || high.x < -1.0 || low.y > 1.0 || high.y < -1.0);
}

void main() {
    const uint index = gl_GlobalInvocationID.x;
    if (index >= cull.instance_count) return;
    const CullInstance instance = instances[index];
    const vec3 box_min = instance.bounds_min.xyz;
    const vec3 box_max = instance.bounds_max.xyz;
    // An empty box casts nothing (without culling every draw goes into every layer).
    if (cull.cull != 0 && any(greaterThan(box_min, box_max))) return;
    for (uint layer = 0; layer < cull.layer_count; ++layer) {
        if (cull.cull != 0 && !may_shadow(shadow.cascades[layer].view_projection, box_min, box_max)) continue;
        const uint command = bucket_first_command[instance.bucket] + atomicAdd(counts[instance.bucket], 1u);
        records[command] = CullRecord(index, layer);
        commands[5 * command + 0] = instance.index_count;
        commands[5 * command + 1] = 1u;
        commands[5 * command + 2] = instance.first_index;
        commands[5 * command + 3] = uint(instance.vertex_offset);
        commands[5 * command + 4] = command;
    }
}
