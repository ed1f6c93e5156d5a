// common/hsat.glsl: the lowest and highest height of a height field over an axis-aligned
// rectangle in constant time, from the tables of the hsat pass (hybrid paper VI.A, eq. 13-14).
//
// Provides: CG_HSAT_PYRAMID, CG_HSAT_PNORM, CG_HSAT_POWER_MEAN,
//           cg_hsat_mode(), cg_hsat_range().
// Requires: common/heightmap.glsl.
// The info block's layout, CG_HSAT_INFO_BLOCK, is common/blocks.h's (hsat/sat.comp and
// passes/hsat/hsat.c write it).
//
// Modes (the hsat pass's `mode` parameter, stored in the info buffer):
//   pyramid     RG32UI mip chain (float bits): level L holds the exact min (r) and max (g) of the level-0
//               heights over each 2^L x 2^L block. A rectangle spanning at most 2^L texels
//               per axis meets at most 2 x 2 blocks of level L: 4 fetches give a range that
//               contains the true one (conservative) and is exact on aligned blocks.
//   pnorm       summed-area tables per level of the normalised height x in [0,1] of x,
//               x^p and (1 - x)^p, in double (RGBA32UI texels 2i and 2i + 1 of a 2n-wide
//               level, hsat/sat.comp); max ~ (sum x^p)^(1/p), the un-normalised
//               p-norm, which is never below the max (plus a margin for fp32 rounding and
//               for x^p flushed to zero), min = 1 - the same bound on 1 - x.
//   power_mean  the same tables read as eq. 14 says: max ~ (mean of x^p)^(1/p). It
//               under-estimates the max by up to a factor N^(-1/p) over N texels: not
//               conservative; offered because it is the paper's.
// Every table entry is stored minus the level's mean of that channel (Hensley et al. 2005);
// the means are in the info buffer. The four corners are combined in double, so a small
// rectangle far from the table's origin keeps its precision.
#ifndef CG_COMMON_HSAT_GLSL
#define CG_COMMON_HSAT_GLSL

#include "common/blocks.h"
#include "common/reads.glsl"

#define CG_HSAT_PYRAMID 0
#define CG_HSAT_PNORM 1
#define CG_HSAT_POWER_MEAN 2

CG_STORAGE_BLOCK(readonly, CgHsatInfo, cg_hsat_info, CG_BINDING_HSAT, CG_HSAT_INFO_BLOCK);

int
cg_hsat_mode()
{
    return int(cg_hsat_info.params.x);
}

// Inclusive texel rectangle of level `level` (size n) under the world rectangle [lo, hi];
// false when it misses the map.
bool
cg_hsat_texels(CgHeightmap m, vec2 lo, vec2 hi, int level, out ivec4 rect)
{
    vec2 size = m.texel * m.resolution;
    if (any(greaterThan(m.origin, hi)) || any(lessThan(m.origin + size, lo)))
        return false;
    int n = max(int(m.resolution) >> level, 1);
    vec2 scale = float(n) / size;
    ivec2 a = clamp(ivec2(floor((lo - m.origin) * scale)), ivec2(0), ivec2(n - 1));
    ivec2 b = clamp(ivec2(floor((hi - m.origin) * scale)), ivec2(0), ivec2(n - 1));
    rect = ivec4(a, b);
    return true;
}

// The three doubles of the SAT at texel p of `level`; zero left of or below the table.
dvec3
cg_hsat_fetch(usampler2D table, ivec2 p, int level)
{
    if (any(lessThan(p, ivec2(0))))
        return dvec3(0.0);
    CG_READ(2);
    uvec4 a = texelFetch(table, ivec2(2 * p.x, p.y), level);
    uvec4 b = texelFetch(table, ivec2(2 * p.x + 1, p.y), level);
    return dvec3(packDouble2x32(a.xy), packDouble2x32(a.zw), packDouble2x32(b.xy));
}

// Eq. 13 without the division: the sum of the table's channels over the inclusive texel
// rectangle, the level's means added back. `rounding` bounds its absolute error: each table
// entry is a sum of up to 2n terms in double (n the level's size), so it is off by at most
// 2n ulps of the largest magnitude involved.
vec3
cg_hsat_sum(usampler2D table, ivec4 r, int level, out vec3 rounding)
{
    dvec3 a = cg_hsat_fetch(table, r.zw, level);                         // S_rt
    dvec3 b = cg_hsat_fetch(table, ivec2(r.x - 1, r.y - 1), level);      // S_lb
    dvec3 c = cg_hsat_fetch(table, ivec2(r.x - 1, r.w), level);          // S_lt
    dvec3 d = cg_hsat_fetch(table, ivec2(r.z, r.y - 1), level);          // S_rb
    double count = double((r.z - r.x + 1) * (r.w - r.y + 1));
    dvec3 mean = dvec3(cg_hsat_info.means[level].xyz);
    dvec3 magnitude = abs(a) + abs(b) + abs(c) + abs(d) + count * abs(mean);
    double n = double(max(int(cg_heightmap_block.info.x) >> level, 1));
    rounding = vec3(magnitude * (2.0 * n + 4.0) * 1.1102230246251565e-16);
    return vec3((a + b - c - d) + count * mean);
}

// World heights (min, max) of the height field over the world rectangle [lo, hi] of the
// xz plane, read from the tables of lightmap level `level` (the pyramid mode reads level-0
// extremes whatever the level). Returns (1, 0) (min > max) when the rectangle misses the map.
vec2
cg_hsat_range(usampler2D table, CgHeightmap m, vec2 lo, vec2 hi, int level)
{
    int mode = cg_hsat_mode();
    ivec4 r;
    if (mode == CG_HSAT_PYRAMID) {
        if (!cg_hsat_texels(m, lo, hi, 0, r))
            return vec2(1.0, 0.0);
        int span = max(r.z - r.x, r.w - r.y) + 1;
        int top = int(cg_hsat_info.params.z) - 1;
        int L = min(span > 1 ? findMSB(span - 1) + 1 : 0, top);
        ivec4 q = r >> L;
        CG_READ(4);
        vec2 t00 = uintBitsToFloat(texelFetch(table, q.xy, L).rg), t10 = uintBitsToFloat(texelFetch(table, q.zy, L).rg);
        vec2 t01 = uintBitsToFloat(texelFetch(table, q.xw, L).rg), t11 = uintBitsToFloat(texelFetch(table, q.zw, L).rg);
        return vec2(min(min(t00.x, t10.x), min(t01.x, t11.x)), max(max(t00.y, t10.y), max(t01.y, t11.y)));
    }
    level = clamp(level, 0, int(cg_hsat_info.params.z) - 1);
    if (!cg_hsat_texels(m, lo, hi, level, r))
        return vec2(1.0, 0.0);
    vec3 rounding;
    vec3 sum = cg_hsat_sum(table, r, level, rounding);
    float count = float((r.z - r.x + 1) * (r.w - r.y + 1));
    float p = cg_hsat_info.params.y;
    float hi_p, lo_p;
    if (mode == CG_HSAT_POWER_MEAN) {
        // Eq. 14 as written: the power mean.
        hi_p = max(sum.y, 0.0) / count;
        lo_p = max(sum.z, 0.0) / count;
    } else {
        // The un-normalised p-norm: sum x^p >= max^p. The margin covers the table's
        // rounding (a small rectangle's sum cancels between large corners: x^p of 1e-20
        // is lost against corners of 1e3), terms x^p that flushed to zero (each below the
        // smallest normal float) and the rounding of the fp32 pow() (relative to each
        // term; 1e-5 allows pow() 80 ulps).
        hi_p = max(sum.y, 0.0) + rounding.y + count * 1.2e-38 + 1e-5 * abs(sum.y);
        lo_p = max(sum.z, 0.0) + rounding.z + count * 1.2e-38 + 1e-5 * abs(sum.z);
    }
    float x_max = min(pow(hi_p, 1.0 / p), 1.0);
    float x_min = max(1.0 - pow(lo_p, 1.0 / p), 0.0);
    float range = m.y_max - m.y_min;
    return vec2(m.y_min + x_min * range, m.y_min + x_max * range);
}

// Eq. 13: the mean height over the world rectangle from the SAT modes' first channel
// (the pyramid mode has none: returns the midpoint of its range).
float
cg_hsat_mean(usampler2D table, CgHeightmap m, vec2 lo, vec2 hi, int level)
{
    if (cg_hsat_mode() == CG_HSAT_PYRAMID) {
        vec2 r = cg_hsat_range(table, m, lo, hi, level);
        return 0.5 * (r.x + r.y);
    }
    level = clamp(level, 0, int(cg_hsat_info.params.z) - 1);
    ivec4 r;
    if (!cg_hsat_texels(m, lo, hi, level, r))
        return m.y_min;
    vec3 rounding;
    vec3 sum = cg_hsat_sum(table, r, level, rounding);
    float count = float((r.z - r.x + 1) * (r.w - r.y + 1));
    return m.y_min + clamp(sum.x / count, 0.0, 1.0) * (m.y_max - m.y_min);
}

#endif
