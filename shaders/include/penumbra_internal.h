// Push constants of Penumbra's own passes, shared by C++ and GLSL (src/passes/
// shader_interface.hpp checks the offsets). Not installed: callers see only
// penumbra/shadow_interface.h.
#ifndef PENUMBRA_INTERNAL_H
#define PENUMBRA_INTERNAL_H

#include "penumbra/shadow_interface.h"

// Descriptor sets of the caster passes: set 0 holds the frame's uniforms, set 1 the
// alpha mask of a masked caster.
#define PENUMBRA_SET_CASTER_FRAME 0
#define PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS 0  // PenumbraShadowUniforms
#define PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS 1    // PenumbraLocalShadows
#define PENUMBRA_SET_ALPHA_MASK 1
#define PENUMBRA_BINDING_ALPHA_MASK 0
// The layered strategy (GPU-driven culling, shaders/caster_cull.comp): set 2 of its caster
// pipelines and set 1 of the culling dispatch.
#define PENUMBRA_SET_CASTER_DRAWS 2
#define PENUMBRA_SET_CULL_DRAWS 1
#define PENUMBRA_BINDING_CULL_INSTANCES 0  // CullInstance per caster draw
#define PENUMBRA_BINDING_CULL_BUCKETS 1    // per bucket: its first command within a layer's commands
#define PENUMBRA_BINDING_CULL_RECORDS 2    // per command: CullRecord (gl_InstanceIndex reads it)
#define PENUMBRA_BINDING_CULL_COMMANDS 3   // VkDrawIndexedIndirectCommand per command
// PENUMBRA_BINDING_CULL_COUNTS: per layer and bucket, how many commands the dispatch wrote;
// then per layer, its draws and triangles (statistics for the host).
#define PENUMBRA_BINDING_CULL_COUNTS 4
// PENUMBRA_BINDING_CULL_TILES: the cascades' culling (PENUMBRA_CULL_CASCADE_TILES): per
// culled layer a CullTile, then the rectangles the tiles list (CullTiles).
#define PENUMBRA_BINDING_CULL_TILES 5
// The moments blur pass and the local moments pass: set 0 holds the image they read.
#define PENUMBRA_BINDING_BLUR_SOURCE 0

// Vertex inputs of the caster passes (one binding each: positions, uvs).
#define PENUMBRA_LOCATION_POSITION 0
#define PENUMBRA_LOCATION_UV 1

// One caster draw: its transform, the shadow map layer (a cascade, or a local light's
// layer; 0 with multiview, which adds gl_ViewIndex), its alpha test, and for a cascade
// which tile of the world's texel grid the draw renders (a toroidal cascade wraps around
// its layer's edges: bit 0, the columns past the right edge, drawn one layer side to the
// left; bit 1, the rows past the bottom edge; the pass scissors each tile).
struct CasterPushConstants {
    mat4 model;  // model -> world
    PENUMBRA_UINT layer;
    float alpha_cutoff;  // masked casters: a texel casts where alpha_scale * texture alpha >= cutoff
    float alpha_scale;
    PENUMBRA_UINT tile;
};

// One caster draw as the GPU culls it (the layered strategy): its transform, the world
// bounds the CPU's culling tests too (caster_footprint), the bucket of draws that share its
// pipeline state, and its mesh's indexed draw.
struct CullInstance {
    mat4 model;
    vec4 bounds_min;  // w unused
    vec4 bounds_max;
    PENUMBRA_UINT bucket;
    PENUMBRA_UINT index_count;
    PENUMBRA_UINT first_index;
    PENUMBRA_INT vertex_offset;
};

// What one culled command draws: a CullInstance into a culled layer (a cascade's tile, or a
// spot or point light's layer).
struct CullRecord {
    PENUMBRA_UINT instance;
    PENUMBRA_UINT layer;
};

// Layer 4 c + t is tile t of cascade c (PenumbraShadowUniforms; CasterPushConstants::tile's
// bits): a toroidal cascade's window wraps around its layer's edges, and each of its up to
// four pieces is drawn with its own offset under its own scissor.
#define PENUMBRA_CULL_CASCADE_TILES 0
#define PENUMBRA_CULL_LOCAL_LAYERS 1  // layers are spot/point light layers (PenumbraLocalShadows)

// The cascades' culled layers (tiles) and what their casters must reach, in window texels
// ([xy, zw): texels from the cascade's texel 0). A static caster is culled into a tile when
// its footprint meets one of the tile's rectangles (the whole piece, or with a cache only
// the texels drawn again this frame); a dynamic one when it meets the tile's piece (dynamic
// casters are drawn over the cached static ones every frame).
#define PENUMBRA_MAX_CULL_TILES (4 * PENUMBRA_MAX_CASCADES)
// Rectangles all tiles list at most: a cascade redraws at most 16 rectangles
// (core/shadow_cache.hpp kMaxRedrawRects), each in up to four pieces.
#define PENUMBRA_MAX_CULL_RECTS (64 * PENUMBRA_MAX_CASCADES)
struct CullTile {
    ivec4 piece;  // the tile's part of the window; empty (z <= x) when the window does not reach it
    uvec4 rects;  // x: the first of its rectangles in CullTiles::rects, y: how many
};

// The commands of layer L, bucket B start at L * instance_count + the bucket's first
// command, and its count is counts[L * bucket_count + B].
struct CullPushConstants {
    PENUMBRA_UINT instance_count;
    PENUMBRA_UINT layer_count;
    PENUMBRA_UINT cull;  // 0: every draw into every culled layer (Settings::shadow.cull_casters off)
    PENUMBRA_UINT mode;  // PENUMBRA_CULL_*
    PENUMBRA_UINT bucket_count;
    // Buckets from this one on hold dynamic casters (CasterDraw::dynamic; they sort last).
    PENUMBRA_UINT first_dynamic_bucket;
    PENUMBRA_UINT resolution;  // PENUMBRA_CULL_CASCADE_TILES: the cascades' texels per side
    PENUMBRA_UINT padding0;
    // Bit L % 32 of word L / 32: layer L is culled and drawn (0: kept from an earlier frame,
    // or nothing can reach it).
    uvec4 layer_mask[2];
};

// The moments compute passes (shaders/moments_convert.comp, moments_blur.comp), per layer.
struct MomentsPushConstants {
    // x: layer, y: texels per side the layer uses from its top-left corner, z: blur radius
    // in texels, w: blur direction (1 horizontal, 0 vertical)
    uvec4 layer;
    // x: near plane, y: far plane (the light's range; 0: orthographic, distance = 1 - depth),
    // zw: EVSM exponents (positive, negative)
    vec4 depth_range;
    // xy: the layer texel of the used texels' first one (a toroidal cascade's
    // layer_origin; 0 for local lights), z: the layer's side. The used texels wrap around
    // the layer's edges from there; filters clamp at the used texels' own edges.
    uvec4 window;
    // The used texels this dispatch writes: x, y the first, z, w how many (all of them
    // unless a cached cascade changed only some).
    uvec4 region;
};

// The screen-space resolve (shaders/visibility_resolve.comp).
struct ResolvePushConstants {
    mat4 inverse_view_projection;  // the caller's clip -> world
    PENUMBRA_UINT width;
    PENUMBRA_UINT height;
    PENUMBRA_UINT has_normals;       // 0: normals from the depth
    PENUMBRA_UINT normal_encoding;   // NormalEncoding: 0 signed float, 1 unsigned normalized, 2 octahedral
    float background_depth;          // no geometry: visibility 1
    PENUMBRA_UINT slot_count;        // 1 (the sun) + the shadowed local lights
    PENUMBRA_UINT has_face_normals;  // 0: each pixel's plane from its neighbours' depths
    PENUMBRA_UINT padding;
};

// ---------------------------------------------------------------- virtual shadow maps
// The sun's virtual shadow map (core/virtual_clipmap.hpp): page marking from the screen
// and page allocation (shaders/virtual_mark.comp, virtual_pages.comp).
// Least-recently-used eviction sorts unrequested pages by age in frames, the last bucket
// holding every older page.
#define PENUMBRA_VIRTUAL_AGE_BUCKETS 64
// A page is requested in a frame when its request word holds that frame's stamp: the
// marking writes the stamp, and nothing clears the requests between frames. Frame numbers
// start at 0 in tests, 1 in the library; the stamp is never 0, the buffer's first contents.
#define PENUMBRA_VIRTUAL_REQUEST_STAMP(frame) ((frame) + 1u)

// Set 0 of the virtual page passes.
#define PENUMBRA_BINDING_VIRTUAL_CLIPMAP 0        // PenumbraVirtualClipmap (uniform buffer)
#define PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE 1     // uint per level and slot
#define PENUMBRA_BINDING_VIRTUAL_REQUESTS 2       // uint per level and slot: stamp of the last frame reading it
#define PENUMBRA_BINDING_VIRTUAL_PHYSICAL 3       // VirtualPhysicalPage per page of the pool
#define PENUMBRA_BINDING_VIRTUAL_COUNTERS 4       // VirtualCounters
#define PENUMBRA_BINDING_VIRTUAL_NEEDS 5          // per level, its entries requested without a page
#define PENUMBRA_BINDING_VIRTUAL_FREE 6           // physical pages free for them, in any order
#define PENUMBRA_BINDING_VIRTUAL_RENDER 7         // per level, pool_pages places: its entries drawn this frame
#define PENUMBRA_BINDING_VIRTUAL_INVALIDATIONS 8  // VirtualInvalidation per rectangle of stale pages
#define PENUMBRA_BINDING_VIRTUAL_DRAWS 9          // VirtualPageDraw per caster instance drawn into a page
// The virtual casters' pipelines: set 3 is the pages set (vertex shaders read the table,
// the clipmap and their VirtualPageDraw); the culling dispatch takes it as set 0 and the
// GPU culling's draws set as set 1.
#define PENUMBRA_SET_VIRTUAL_PAGES 3
// Set 1 of the marking pass: the caller's depth.
#define PENUMBRA_BINDING_VIRTUAL_DEPTH 0

// Pages of one level whose texels are stale (a static caster changed within them, or a
// dynamic caster reaches them): world pages [pages.xy, pages.zw).
struct VirtualInvalidation {
    ivec4 pages;
    PENUMBRA_UINT level;
    PENUMBRA_UINT padding0;
    PENUMBRA_UINT padding1;
    PENUMBRA_UINT padding2;
};

struct VirtualPhysicalPage {
    PENUMBRA_UINT owner;      // the page table entry holding it, or PENUMBRA_PAGE_NO_OWNER
    PENUMBRA_UINT last_used;  // the last frame a pixel requested it
};

// A VkDispatchIndirectCommand the allocation writes: no workgroups for a step with
// nothing to do (a walking camera's frame evicts, assigns and draws nothing).
struct VirtualDispatch {
    PENUMBRA_UINT x;
    PENUMBRA_UINT y;
    PENUMBRA_UINT z;
};

// A VkDrawIndirectCommand of the pass that clears the pages drawn this frame: one per level,
// a quad (6 vertices) per page, whose instances are the level's places in the list of pages
// drawn (first_instance = level * pool_pages). instance_count counts the level's pages
// drawn while the allocation lists them.
struct VirtualClearDraw {
    PENUMBRA_UINT vertex_count;
    PENUMBRA_UINT instance_count;
    PENUMBRA_UINT first_vertex;
    PENUMBRA_UINT first_instance;
};

// What the allocation found this frame (the host reads a copy, FrameInfo's statistics).
struct VirtualCounters {
    PENUMBRA_UINT needed;     // requested entries without a page
    PENUMBRA_UINT free;       // physical pages free for them before eviction (the free list's length)
    PENUMBRA_UINT rendered;   // entries whose page is drawn this frame (new or stale)
    PENUMBRA_UINT unserved;   // requested entries left without a page: the pool is full
    PENUMBRA_UINT requested;  // entries a pixel requested
    PENUMBRA_UINT cached;     // requested entries whose page was valid already
    PENUMBRA_UINT resident;   // physical pages held by an entry, after allocation
    PENUMBRA_UINT evicted;    // unrequested pages taken from their entries for new ones
    // Eviction: every evictable page older than this bucket goes, and take_at_threshold of
    // this bucket's (taken counts them).
    PENUMBRA_UINT threshold_bucket;
    PENUMBRA_UINT take_at_threshold;
    PENUMBRA_UINT taken;
    PENUMBRA_UINT evictable;  // unrequested pages held by an entry
    // The dispatches of assignment (and eviction) and of the casters' culling, sized by the plan.
    VirtualDispatch assign_groups;
    VirtualDispatch cull_groups;
    PENUMBRA_UINT scan_groups_done;  // workgroups of the scan finished: the last one plans
    PENUMBRA_UINT render_claims;     // pages that asked to be drawn (rendered + deferred)
    PENUMBRA_UINT deferred;          // pages left stale for a later frame by render_budget
    PENUMBRA_UINT padding0;
    PENUMBRA_UINT padding1;
    PENUMBRA_UINT padding2;
    // Requested entries without a page, per level: coarser levels are served first, since a
    // receiver whose page is unserved falls back to the next coarser level.
    PENUMBRA_UINT level_needs[PENUMBRA_MAX_VIRTUAL_LEVELS];
    PENUMBRA_UINT age_histogram[PENUMBRA_VIRTUAL_AGE_BUCKETS];
    // Per level, the clear pass's draw; its instance_count is the level's pages drawn, which
    // the casters' culling scans level by level.
    VirtualClearDraw level_clears[PENUMBRA_MAX_VIRTUAL_LEVELS];
    // Kept from frame to frame (each frame clears the counters before these). How many pages
    // a frame may draw, 0 for every page asked: the plan lowers it after a frame whose page
    // draws overflowed their buffer and raises it again after frames that fit, so that the
    // pages drawn in a frame get all their draws and a small buffer still catches up.
    PENUMBRA_UINT render_budget;
    PENUMBRA_UINT last_rendered;  // pages the previous frame drew (the plan's count)
    // The casters' culling: VirtualPageDraws written, and the ones beyond the buffer's room
    // (their pages lose VALID and are drawn again); the next frame's plan reads and clears them.
    PENUMBRA_UINT page_draws;
    PENUMBRA_UINT dropped_page_draws;
};

// One caster instance drawn into one page (gl_InstanceIndex of the virtual caster draws).
struct VirtualPageDraw {
    PENUMBRA_UINT instance;  // CullInstance
    PENUMBRA_UINT entry;     // the page table entry: level and slot
};

// The casters' culling against the pages drawn this frame (shaders/virtual_cull.comp).
struct VirtualCullPushConstants {
    PENUMBRA_UINT instance_count;
    PENUMBRA_UINT bucket_count;
    PENUMBRA_UINT draw_capacity;  // VirtualPageDraws the buffer holds
    // The levels the commands have room for: a bucket's commands of every level lie together,
    // from bucket_first_command * level_count on, and one indirect draw draws them.
    PENUMBRA_UINT level_count;
};

// The marking pass: the caller's depth buffer as ScreenInputs describes it.
struct VirtualMarkPushConstants {
    mat4 inverse_view_projection;  // the caller's clip -> world
    PENUMBRA_UINT width;
    PENUMBRA_UINT height;
    float background_depth;
    PENUMBRA_UINT padding;
};

// The allocation passes (shaders/virtual_pages.comp): which step a dispatch runs.
#define PENUMBRA_VIRTUAL_STEP_SCAN 0    // per entry and per physical page; the last workgroup plans
#define PENUMBRA_VIRTUAL_STEP_ASSIGN 1  // per level and need, and per physical page to evict

struct VirtualStepPushConstants {
    PENUMBRA_UINT step;  // PENUMBRA_VIRTUAL_STEP_*
    // The scan's threads from this one on scan the physical pages (the ones before, the
    // page table's entries).
    PENUMBRA_UINT first_page_thread;
    // The casters' culling dispatch when pages are drawn (VirtualCounters::cull_groups):
    // workgroups in x and y, one per culled instance.
    PENUMBRA_UINT cull_columns;
    PENUMBRA_UINT cull_rows;
    PENUMBRA_UINT draw_capacity;  // VirtualPageDraws the casters' culling has room for (the render budget)
    PENUMBRA_UINT padding0;
    PENUMBRA_UINT padding1;
    PENUMBRA_UINT padding2;
};

#endif
