// voxel_light/spacing.glsl: the gathers at the voxels with bounce_spacing = S > 1 (passes/voxel_light's
// header). Indirect diffuse light changes slowly along a surface, as on the screen (common/upsample.glsl):
// the volume is cut into blocks of S^3 voxels, and one occupied voxel of each block, its representative
// (the one nearest the block's centre among those with a side to gather on), traces its cones. Every
// other occupied voxel takes the mean of the representatives of the blocks around it, weighted by a
// tent over the distance of the block's centre (trilinear, or VOXEL_LIGHT_WIDE_REACH) times how well the
// representative's surface agrees with the voxel's (voxel_light_agreement: normal and plane, the plane
// tolerance VOXEL_LIGHT_PLANE_TOLERANCE). A voxel that no representative agrees with (a thin object between
// them, a surface too small to hold one) traces its own cones: its light is never another surface's.
// pick.comp chooses the representatives, planes.comp keeps their planes, sort.comp lists the voxels
// that trace (`traced`: the representatives and those) and the others (`mixed`), gather.comp traces
// the first list and fill.comp mixes the second.
//
// Provides: voxel_light_spacing (each block's key and plane), voxel_light_traced,
//           voxel_light_mixed (lists of CG_VOXEL_LIST_BLOCK), voxel_light_blocks(),
//           voxel_light_block_index(), voxel_light_block_key(), voxel_light_key_voxel(),
//           voxel_light_agreement(), voxel_light_mix_blocks(), voxel_light_mix().
#ifndef CG_VOXEL_LIGHT_SPACING_GLSL
#define CG_VOXEL_LIGHT_SPACING_GLSL

#include "common/agreement.glsl"
#include "voxel_light/surface.glsl"

#ifndef VOXEL_LIGHT_SPACING
#error "voxel_light/spacing.glsl needs VOXEL_LIGHT_SPACING (passes/voxel_light defines it)"
#endif

// The least coherence |N| of a voxel that gathers (gather.comp: below it the facets face both ways).
#define VOXEL_LIGHT_MIN_COHERENCE 0.1
// A block with no representative.
#define VOXEL_LIGHT_NO_KEY 0xffffffffu

// Per block (x + bx (y + by z), bx = ceil(dims.x / S)): the least key of its occupied voxels
// (pick.comp), and its representative's tangent plane (planes.comp): unit normal m and m . q (q its
// surface point), which every voxel that mixes from the block compares with its own (voxel_light_mix);
// kept here, not read from the volumes, as the blocks around each voxel would read them again and again.
// One buffer, so that voxel_light's storage bindings stay within GL's guaranteed 8.
struct VoxelLightBlock {
    vec4 plane;
    uint key;
};
layout(std430, binding = CG_BINDING_VOXEL_BLOCKS) buffer VoxelLightSpacing {
    VoxelLightBlock blocks[];
} voxel_light_spacing;

layout(std430, binding = CG_BINDING_VOXEL_TRACED) buffer VoxelLightTraced {
    CG_VOXEL_LIST_BLOCK(CG_GLSL_MEMBER, CG_GLSL_ARRAY)
    uint voxels[];
} voxel_light_traced;

layout(std430, binding = CG_BINDING_VOXEL_MIXED) buffer VoxelLightMixed {
    CG_VOXEL_LIST_BLOCK(CG_GLSL_MEMBER, CG_GLSL_ARRAY)
    uint voxels[];
} voxel_light_mixed;

ivec3
voxel_light_blocks(CgVolume vol)
{
    return (ivec3(vol.dims) + VOXEL_LIGHT_SPACING - 1) / VOXEL_LIGHT_SPACING;
}

uint
voxel_light_block_index(CgVolume vol, ivec3 b)
{
    ivec3 n = voxel_light_blocks(vol);
    return uint(b.x + n.x * (b.y + n.y * b.z));
}

// Voxel v's key in its block: its squared distance from the block's centre (in half voxels) above its
// index in the block, so that the least key is the voxel nearest the centre, ties broken by index.
uint
voxel_light_block_key(ivec3 v)
{
    ivec3 l = v % VOXEL_LIGHT_SPACING;
    ivec3 d = 2 * l - (VOXEL_LIGHT_SPACING - 1);
    uint index = uint(l.x + VOXEL_LIGHT_SPACING * (l.y + VOXEL_LIGHT_SPACING * l.z));
    return (uint(dot(d, d)) << 9) | index;
}

// The voxel of block b whose key is `key`.
ivec3
voxel_light_key_voxel(ivec3 b, uint key)
{
    uint index = key & 511u;
    ivec3 l = ivec3(index % uint(VOXEL_LIGHT_SPACING), (index / uint(VOXEL_LIGHT_SPACING)) % uint(VOXEL_LIGHT_SPACING),
                    index / uint(VOXEL_LIGHT_SPACING * VOXEL_LIGHT_SPACING));
    return b * VOXEL_LIGHT_SPACING + l;
}

// The blocks a voxel mixes from: those whose centres are within one block of it along each axis,
// weighted by the tent of that reach (trilinear weights, the 2 x 2 x 2 nearest); where none of them has
// a representative that agrees, those within VOXEL_LIGHT_WIDE_REACH blocks (the 3 x 3 x 3 around its
// own). The trilinear weights alone left voxels with no representative of their own surface where
// the volume's border cut the blocks: on Debian's BoxTextured, which fills its volume, 7 775 of
// 190 150 voxels traced at bounce_spacing 8 for want of one. The wide reach everywhere blurs: the
// floor's light under the middle half of a shelf came out 1.17 times its light with every voxel
// tracing, 1.10 with the trilinear weights (test_voxel_light_spacing's scene).
#define VOXEL_LIGHT_WIDE_REACH 1.5

// The distance from a representative's tangent plane, in voxels, at which its agreement with a voxel
// falls to 0. Not a block's spacing, as on the screen: a voxel's surface point lies on its own plane
// (voxel_light_point), so a plane's voxels agree at any spacing, while a shelf three voxels above a
// floor, a block away at bounce_spacing 4, lent its sky to the floor beneath it with a tolerance of 4
// voxels: 1.08 times the floor's light with every voxel tracing, 1.0000 with 2 (test_voxel_light_spacing).
#define VOXEL_LIGHT_PLANE_TOLERANCE 2.0

// How well a representative, whose tangent plane is `plane` (unit normal m, m . q), agrees with a voxel
// (surface point x, mean normal N, |N| = c >= VOXEL_LIGHT_MIN_COHERENCE): common/agreement.glsl's rule,
// with the angle measured against the facets the mean stands for (N^ . m / c, at most 1: two or three
// perpendicular facets of equal share, an edge or a corner, each make N^ . m = c with N), and x's
// distance from the representative's tangent plane (an edge voxel's point lies on both of its facets'
// planes). For a plane's voxel (c = 1) this is the screen's test.
float
voxel_light_agreement(vec4 plane, vec3 x, vec3 n, float tolerance)
{
    float c = length(n);
    return cg_agreement(min(dot(n, plane.xyz) / (c * c), 1.0), abs(dot(plane.xyz, x) - plane.w), tolerance);
}

// The weighted sum of the representatives of the blocks first + (0..count-1)^3, each weighted by the
// tent of `reach` blocks about its centre (at f, v on the grid of block centres) times its agreement;
// with VOXEL_LIGHT_FILL their light into front and back.
float
voxel_light_mix_blocks(CgVolume vol, vec3 f, ivec3 first, int count, float reach, vec3 x, vec3 n,
                       inout vec4 front, inout vec4 back)
{
    ivec3 blocks = voxel_light_blocks(vol);
    float tolerance = VOXEL_LIGHT_PLANE_TOLERANCE * vol.voxel_size;
    float sum = 0.0;
    for (int k = 0; k < count * count * count; k++) {
        ivec3 b = first + ivec3(k % count, (k / count) % count, k / (count * count));
        if (any(lessThan(b, ivec3(0))) || any(greaterThanEqual(b, blocks)))
            continue;
        uint index = voxel_light_block_index(vol, b);
        uint key = voxel_light_spacing.blocks[index].key;
        if (key == VOXEL_LIGHT_NO_KEY)
            continue;
        vec3 tent = max(vec3(1.0) - abs(f - vec3(b)) / reach, vec3(0.0));
        float w = tent.x * tent.y * tent.z * voxel_light_agreement(voxel_light_spacing.blocks[index].plane, x, n, tolerance);
        if (w == 0.0)
            continue;
        sum += w;
#ifdef VOXEL_LIGHT_FILL
        ivec3 r = voxel_light_key_voxel(b, key);
        front += w * imageLoad(u_gathered_front, r);
        back += w * imageLoad(u_gathered_back, r);
#endif
    }
    return sum;
}

// The mix of the representatives around voxel v (surface point x, mean normal n): returns the sum of
// their weights (0 where none agrees: v traces). With VOXEL_LIGHT_FILL it also sums their weighted
// light from u_gathered_front and u_gathered_back (fill.comp) into front and back. The trilinear
// blocks first; the wide reach only where none of them agrees.
float
voxel_light_mix(CgVolume vol, ivec3 v, vec3 x, vec3 n, out vec4 front, out vec4 back)
{
    vec3 f = (vec3(v) + 0.5) / float(VOXEL_LIGHT_SPACING) - 0.5;    // v on the grid of block centres
    front = vec4(0.0);
    back = vec4(0.0);
    float sum = voxel_light_mix_blocks(vol, f, ivec3(floor(f)), 2, 1.0, x, n, front, back);
    if (sum > 0.0)
        return sum;
    return voxel_light_mix_blocks(vol, f, v / VOXEL_LIGHT_SPACING - 1, 3, VOXEL_LIGHT_WIDE_REACH, x, n, front, back);
}

#endif
