// common/upsample.glsl: decoupled GI resolution of a cone gather (passes/sdk/upsample.h).
//
// With CG_GATHER_DOWNSAMPLE = D (2 or 4) a gather traces its diffuse cones at one pixel of each
// D x D block of the image, the block's representative, in a first dispatch (the shader compiled
// with CG_GATHER_LOWRES, one invocation a block, writing an image of blocks), and its
// full-resolution dispatch rebuilds every pixel's diffuse light from the four nearest blocks by
// joint bilateral upsampling (Kopf et al. 2007, "Joint Bilateral Upsampling", eq. 2: the low
// resolution solution's samples weighted by a spatial filter on the low resolution grid times a
// range filter on the full-resolution guide image). Here the spatial filter is the bilinear
// weight of the four blocks around the pixel, and the guide is the G-buffer's full-resolution
// surface: a block's weight is multiplied by how well its representative's surface agrees with
// the pixel's, its normal (cos^32 of the angle between them) and its distance from the pixel's
// tangent plane (1 at 0, falling linearly to 0 at a fraction of the pixel's distance from the
// camera, so that the tolerance follows the spacing of the blocks on the screen). A coplanar
// neighbour agrees at any angle of view; a surface in front of or behind the pixel does not.
//
// Indirect diffuse light changes slowly along a surface and abruptly only where the surface does,
// so this keeps the light of one surface from reaching another across a depth or normal edge.
// Where no block agrees well enough (a thin object between blocks, a silhouette whose block
// centres fell on the background), the pixel traces its own cones: the answer there is the
// full-resolution gather's, never a neighbour's light. It traces them in a dispatch of its own
// (CG_GATHER_DEFERRED, the third entry point, over the list the full-resolution dispatch made:
// cg_upsample_defer), not in the full-resolution dispatch: a lockstep group of pixels waits for its
// slowest lane, so each such pixel held up its whole group for a trace (0.55% of the open world's
// pixels at 640x360 cost about 70 ms of a 480 ms gather on llvmpipe; docs/results/gi-resolution.md).
//
// Provides: cg_upsample_tolerance(), cg_upsample_block_kept(), cg_upsample_defer(), with
//           CG_GATHER_LOWRES or CG_GATHER_DEFERRED the entry point main() (which calls the gather's
//           cg_upsample_trace(), cg_upsample_untraced() and cg_upsample_camera(), declared here),
//           cg_upsample_representative(), cg_upsample_is_representative(), cg_upsample_diffuse().
#ifndef CG_COMMON_UPSAMPLE_GLSL
#define CG_COMMON_UPSAMPLE_GLSL

#include "common/agreement.glsl"
#include "common/cone_trace.glsl"
#include "common/gather.glsl"
#include "common/reads.glsl"

#ifndef CG_GATHER_DOWNSAMPLE
#error "common/upsample.glsl needs CG_GATHER_DOWNSAMPLE (passes/sdk/upsample.h defines it)"
#endif

// The blocks' diffuse light: rgb the incident radiance integral E_i/pi before the material's
// diffuse share, a the ambient visibility, one texel a block (cgp_gather_blocks_trace).
layout(binding = CG_UNIT_GATHER_BLOCKS) uniform sampler2D cg_upsample_blocks;

// The pixels no block agrees with, which trace their own cones in the CG_GATHER_DEFERRED dispatch.
layout(std430, binding = CG_BINDING_GATHER_DEFERRED) buffer CgUpsampleDeferred {
    CG_GATHER_DEFERRED_BLOCK(CG_GLSL_MEMBER, CG_GLSL_ARRAY)
    uint pixels[];
} cg_upsample_deferred;

// Lists `pixel` for the CG_GATHER_DEFERRED dispatch (the list holds a pixel of the image each).
void
cg_upsample_defer(ivec2 pixel)
{
    uint i = atomicAdd(cg_upsample_deferred.dispatch.w, 1u);
    cg_upsample_deferred.pixels[i] = uint(pixel.x) | (uint(pixel.y) << 16);
    if (i % 64u == 0u)
        atomicAdd(cg_upsample_deferred.dispatch.x, 1u);
}

// The plane distance at which a block's agreement with a pixel `position` seen from `camera`
// falls to 0: it follows the spacing of the blocks on the screen.
float
cg_upsample_tolerance(vec3 position, vec3 camera)
{
    return CG_UPSAMPLE_PLANE_PER_BLOCK * float(CG_GATHER_DOWNSAMPLE) * distance(position, camera);
}

#ifdef CG_GATHER_TEMPORAL
// Temporal reuse (sdk/upsample.h's `temporal` = N): each frame the blocks of one turn in N trace
// (N = 2: a checkerboard; 4: one block of each 2 x 2); each other block takes the light of the last
// frame's block in which the last camera saw its representative's point (a reprojection by the
// G-buffer's point and the last camera, so a moving camera keeps what it still sees), where that
// light was traced at a surface that agrees with the pixel's: the normal and the plane as the
// upsampling compares a block with a pixel, and the point no farther from the traced one than the
// plane tolerance (about a block's spacing), so that a kept light is what a neighbour's would be to
// the upsampling; and where it is at most N - 1 frames old, as on a still camera. A block whose pixel
// sees another surface (an object moved, or the camera uncovered it) traces whatever the turn. Each
// block keeps the surface its light was traced at, position (w: 1 where it saw a surface) and
// normal (w: the light's age in frames), this frame's written, the last frame's read. A still camera
// reprojects each block onto itself: its image is the one without reprojection, bit for bit.
layout(binding = CG_IMAGE_BLOCK_HISTORY, rgba32f) uniform image2D cg_upsample_history_position;
layout(binding = CG_IMAGE_BLOCK_HISTORY + 1, rgba32f) uniform image2D cg_upsample_history_normal;
layout(binding = CG_UNIT_BLOCK_PREVIOUS) uniform sampler2D cg_upsample_previous_position;
layout(binding = CG_UNIT_BLOCK_PREVIOUS + 1) uniform sampler2D cg_upsample_previous_normal;
// x: this frame's turn (the frame's index mod N); y: 1 when the last frame's blocks hold a traced frame.
layout(location = CG_UPSAMPLE_TEMPORAL_LOCATION) uniform ivec2 cg_upsample_temporal;
// The last frame's world-to-clip matrix.
layout(location = CG_UPSAMPLE_PREVIOUS_LOCATION) uniform mat4 cg_upsample_previous_view_proj;

// The last frame's block in which the last camera saw the world point `position`; -1 outside its
// image or behind it. Interleaved, a block holds its own subset of the cones: only itself.
ivec2
cg_upsample_reprojected(ivec2 b, vec3 position)
{
#ifdef CG_GATHER_INTERLEAVE
    return b;
#else
    vec4 clip = cg_upsample_previous_view_proj * vec4(position, 1.0);
    if (!(clip.w > 0.0))
        return ivec2(-1);
    vec2 size = vec2(textureSize(cg_gather_position, 0));
    vec2 pixel = (clip.xy / clip.w * 0.5 + 0.5) * size;
    if (any(lessThan(pixel, vec2(0.0))) || any(greaterThanEqual(pixel, size)))
        return ivec2(-1);
    return ivec2(pixel) / CG_GATHER_DOWNSAMPLE;
#endif
}
#endif

// Whether block `b`, whose representative pixel sees (`surface`) the point `position` with unit
// normal `n` from `camera`, keeps light instead of tracing (then written to the image of blocks
// here); where it traces, the surface it traces is remembered. Without CG_GATHER_TEMPORAL every
// block traces.
bool
cg_upsample_block_kept(ivec2 b, bool surface, vec3 position, vec3 n, vec3 camera)
{
#ifdef CG_GATHER_TEMPORAL
#if CG_GATHER_TEMPORAL == 2
    int turn = (b.x + b.y) & 1;
#else
    int turn = (b.x & 1) + 2 * (b.y & 1);
#endif
    if (cg_upsample_temporal.y != 0 && turn != cg_upsample_temporal.x) {
        // Outside the last frame's image (from = -1) nothing seen there is kept.
        ivec2 from = surface ? cg_upsample_reprojected(b, position) : b;
        if (from.x >= 0) {
            vec4 q = texelFetch(cg_upsample_previous_position, from, 0);
            vec4 m = texelFetch(cg_upsample_previous_normal, from, 0);
            bool kept = !surface && q.w == 0.0;    // the background then and now: nothing to trace
            if (surface && q.w != 0.0 && m.w + 1.0 <= float(CG_GATHER_TEMPORAL - 1)) {
                float tolerance = cg_upsample_tolerance(position, camera);
                kept = cg_upsample_agreement(q.xyz, m.xyz, position, n, tolerance) > 0.0 &&
                       distance(q.xyz, position) < tolerance;
            }
            if (kept) {
                imageStore(cg_upsample_history_position, b, q);
                imageStore(cg_upsample_history_normal, b, vec4(m.xyz, m.w + 1.0));
                imageStore(cg_gather_radiance, b, texelFetch(cg_upsample_blocks, from, 0));
                return true;
            }
        }
    }
    imageStore(cg_upsample_history_position, b, vec4(position, surface ? 1.0 : 0.0));
    imageStore(cg_upsample_history_normal, b, vec4(n, 0.0));
#endif
    return false;
}

// The pixel that block `b` traces: its centre (for an even D the lower right of the four central
// pixels), clamped to the image for a last block that the image cuts.
ivec2
cg_upsample_representative(ivec2 b)
{
    ivec2 size = textureSize(cg_gather_position, 0);
    return min(b * CG_GATHER_DOWNSAMPLE + CG_GATHER_DOWNSAMPLE / 2, size - 1);
}

// Whether `pixel` is the pixel its block traces (the block holding it: pixel / D).
bool
cg_upsample_is_representative(ivec2 pixel)
{
    return cg_upsample_representative(pixel / CG_GATHER_DOWNSAMPLE) == pixel;
}

#ifdef CG_GATHER_INTERLEAVE
// Interleaved cone sets (sdk/upsample.h's `interleave`): block b traces the cones k = s, s + 4, ...
// of the set, s its place in the 2 x 2 of blocks it belongs to, so that any 2 x 2 blocks hold the
// four subsets once each. Called by a gather's block entry point before it traces.
int
cg_upsample_subset(ivec2 b)
{
    return (b.x & 1) + 2 * (b.y & 1);
}

void
cg_upsample_interleave(ivec2 b)
{
    cg_cone_first = cg_upsample_subset(b);
    cg_cone_stride = 4;
}

// The cone weights of block b's subset: W_k summed over its cones (the whole set sums to 1).
float
cg_upsample_subset_weight(ivec2 b)
{
    float w = 0.0;
    for (int k = cg_upsample_subset(b); k < cg_cone_count(); k += 4)
        w += cg_cone_set_block.cones[k].w;
    return w;
}
#endif

// The diffuse light of `pixel` (a surface point `position` with unit normal `n`, seen from
// `camera`) from the blocks around it; false where no block's surface agrees with the pixel's
// well enough, and the pixel must trace its own cones. A representative takes its own block's
// light exactly. Interleaved, the 2 x 2 blocks around the pixel hold the four subsets of the set:
// their sums, each times its agreement, over the agreeing subsets' cone weights (a subset that
// disagrees leaves its directions to the others, as a uniform radiance would fill them), without
// the bilinear weights, which would lean the light towards the nearest block's directions.
bool
cg_upsample_diffuse(ivec2 pixel, vec3 position, vec3 n, vec3 camera, out vec4 diffuse)
{
#ifndef CG_GATHER_INTERLEAVE
    if (cg_upsample_is_representative(pixel)) {
        diffuse = texelFetch(cg_upsample_blocks, pixel / CG_GATHER_DOWNSAMPLE, 0);
        return true;
    }
#endif
    // The four blocks around the pixel, by their representatives' positions on the screen.
    vec2 f = (vec2(pixel) - float(CG_GATHER_DOWNSAMPLE / 2)) / float(CG_GATHER_DOWNSAMPLE);
    ivec2 b0 = ivec2(floor(f));
    diffuse = vec4(0.0);
    vec2 t = f - vec2(b0);
    ivec2 blocks = textureSize(cg_upsample_blocks, 0);
    float tolerance = cg_upsample_tolerance(position, camera);
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec2 b = b0 + ivec2(i, j);
            if (any(lessThan(b, ivec2(0))) || any(greaterThanEqual(b, blocks)))
                continue;
            vec3 q, m;
            if (!cg_gather_surface(cg_upsample_representative(b), q, m))
                continue;
            float agreement = cg_upsample_agreement(q, m, position, n, tolerance);
            if (agreement == 0.0)
                continue;   // another surface: none of its light, however near its block
#ifdef CG_GATHER_INTERLEAVE
            sum += agreement * texelFetch(cg_upsample_blocks, b, 0);
            weight += agreement * cg_upsample_subset_weight(b);
#else
            float w = (i == 0 ? 1.0 - t.x : t.x) * (j == 0 ? 1.0 - t.y : t.y) * agreement;
            sum += w * texelFetch(cg_upsample_blocks, b, 0);
            weight += w;
#endif
        }
    if (!(weight > 0.0))
        return false;
    diffuse = sum / weight;
    return true;
}

#if defined(CG_GATHER_DEFERRED) || defined(CG_GATHER_LOWRES)
// Defined by the gather after this file: the diffuse cones of the surface point `position` with
// unit normal `n` seen at `pixel` (before the material's diffuse share: rgb E_i / pi, a the ambient
// visibility), which also stores the pixel's count of reads where the gather keeps such an image;
// cg_upsample_untraced(pixel) stores 0 there for a representative that does not trace; and the
// camera's position.
vec4 cg_upsample_trace(ivec2 pixel, vec3 position, vec3 n);
void cg_upsample_untraced(ivec2 pixel);
vec3 cg_upsample_camera();
#endif

#if defined(CG_GATHER_LOWRES) && !defined(CG_GATHER_DEFERRED)
// The blocks' first entry point: one invocation a block says whether it traces this frame and lists
// it (cg_upsample_defer) for the listed entry point below; a block on the background is written at
// once (no light, visibility 1), a kept one (temporal) by cg_upsample_block_kept. The traces run
// packed, 64 listed blocks to a lockstep group: traced in place, a group of 8 blocks waited for its
// slowest trace, and with temporal 4 (one block in each 2 x 2 traces) 6 of its 8 lanes idled through
// it (the demo's gather on the open world at 640x360: docs/results/gi-resolution.md, "The blocks
// traced packed").
void
main()
{
    ivec2 block;
    if (!cg_gather_pixel(block))
        return;
    ivec2 pixel = cg_upsample_representative(block);
    vec3 position, n;
    bool surface = cg_gather_surface(pixel, position, n);
    bool kept = cg_upsample_block_kept(block, surface, position, n, cg_upsample_camera());
    if (!kept && surface) {
        cg_upsample_defer(block);
        return;
    }
    if (!kept)
        imageStore(cg_gather_radiance, block, vec4(0.0, 0.0, 0.0, 1.0));
    cg_upsample_untraced(pixel);
}
#endif

#ifdef CG_GATHER_DEFERRED
// The listed entry point, over the list that the block entry point (with CG_GATHER_LOWRES) or the
// full-resolution dispatch (cg_upsample_defer) made, 64 to a lockstep group.
// With CG_GATHER_LOWRES: each listed block's diffuse cones at its representative, for every surface
// (a block's light serves the pixels around it, whatever its own material), into the image of blocks.
// Otherwise: each listed pixel's diffuse light, its own cones times the material's diffuse share, as
// the full-resolution dispatch would have written it (which wrote the pixel's other outputs already,
// and its diffuse light 0).
void
main()
{
    uint i = gl_WorkGroupID.x * 64u + gl_LocalInvocationIndex;
    if (i >= cg_upsample_deferred.dispatch.w)
        return;
    uint listed = cg_upsample_deferred.pixels[i];
    ivec2 at = ivec2(listed & 0xffffu, listed >> 16);
#ifdef CG_GATHER_LOWRES
    ivec2 pixel = cg_upsample_representative(at);
#ifdef CG_GATHER_INTERLEAVE
    cg_upsample_interleave(at);
#endif
#else
    ivec2 pixel = at;
#endif
    vec3 position, n;
    cg_gather_surface(pixel, position, n);  // a surface: only those are listed
    vec4 diffuse = cg_upsample_trace(pixel, position, n);
#if defined(CG_GATHER_MATERIAL) && !defined(CG_GATHER_LOWRES)
    CgGatherMaterial m = cg_gather_material(pixel);
    vec3 view = normalize(position - cg_upsample_camera());
    diffuse.rgb *= cg_gather_diffuse_share(m, cg_gather_brdf(max(dot(n, -view), 0.0), m.roughness));
#endif
    imageStore(cg_gather_radiance, at, diffuse);
    cg_reads_commit(true);
}
#endif

#endif
