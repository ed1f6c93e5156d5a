// common/hsat.glsl: the lowest and highest height of a height field over an axis-aligned
// rectangle in constant time, from the tables of the hsat pass (hybrid paper VI.A, eq. 13-14).
//
// Provides: CG_BINDING_HSAT, CG_HSAT_PYRAMID, CG_HSAT_PNORM, CG_HSAT_POWER_MEAN,
//           cg_hsat_mode(), cg_hsat_range().
// Requires: common/heightmap.glsl.
// The C side is passes/hsat/hsat.c; keep the info layout in step.
//
// Modes (the hsat pass's `mode` parameter, stored in the info buffer):
//   pyramid     RG32F mip chain: level L holds the exact min (r) and max (g) of the level-0
//               heights over each 2^L x 2^L block. A rectangle spanning at most 2^L texels
//               per axis meets at most 2 x 2 blocks of level L: 4 fetches give a range that
//               contains the true one (conservative) and is exact on aligned blocks.
//   pnorm       RGBA32F summed-area tables per level of the normalised height x in [0,1]
//               (r: x, g: x^p, b: (1 - x)^p); max ~ (sum x^p)^(1/p), the un-normalised
//               p-norm, which is never below the max (plus a margin for fp32 rounding and
//               for x^p flushed to zero), min = 1 - the same bound on 1 - x.
//   power_mean  the same tables read as eq. 14 says: max ~ (mean of x^p)^(1/p). It
//               under-estimates the max by up to a factor N^(-1/p) over N texels: not
//               conservative; offered because it is the paper's.
// Every table entry is stored minus the level's mean of that channel (Hensley et al. 2005),
// which keeps fp32 sums small far from the table's origin; the means are in the info buffer.
#ifndef CG_COMMON_HSAT_GLSL
#define CG_COMMON_HSAT_GLSL

#define CG_BINDING_HSAT 5
#define CG_HSAT_PYRAMID 0
#define CG_HSAT_PNORM 1
#define CG_HSAT_POWER_MEAN 2

layout(std430, binding = CG_BINDING_HSAT) readonly buffer CgHsatInfo {
    vec4 cg_hsat_params;      // x mode, y p, z levels, w unused
    vec4 cg_hsat_means[16];   // per level: means of x, x^p, (1 - x)^p subtracted from the tables
};

int
cg_hsat_mode()
{
    return int(cg_hsat_params.x);
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

vec4
cg_hsat_fetch(sampler2D table, ivec2 p, int level)
{
    return any(lessThan(p, ivec2(0))) ? vec4(0.0) : texelFetch(table, p, level);
}

// Eq. 13 without the division: the sum of the table's channels over the inclusive texel
// rectangle, the level's means added back.
vec3
cg_hsat_sum(sampler2D table, ivec4 r, int level, out float magnitude)
{
    vec4 a = cg_hsat_fetch(table, r.zw, level);                          // S_rt
    vec4 b = cg_hsat_fetch(table, ivec2(r.x - 1, r.y - 1), level);       // S_lb
    vec4 c = cg_hsat_fetch(table, ivec2(r.x - 1, r.w), level);           // S_lt
    vec4 d = cg_hsat_fetch(table, ivec2(r.z, r.y - 1), level);           // S_rb
    float count = float((r.z - r.x + 1) * (r.w - r.y + 1));
    vec3 mean = cg_hsat_means[level].xyz;
    magnitude = abs(a.g) + abs(b.g) + abs(c.g) + abs(d.g) + count * abs(mean.y);
    return (a.rgb + b.rgb - c.rgb - d.rgb) + count * mean;
}

// World heights (min, max) of the height field over the world rectangle [lo, hi] of the
// xz plane, read from the tables of lightmap level `level` (the pyramid mode reads level-0
// extremes whatever the level). Returns (1, 0) (min > max) when the rectangle misses the map.
vec2
cg_hsat_range(sampler2D table, CgHeightmap m, vec2 lo, vec2 hi, int level)
{
    int mode = cg_hsat_mode();
    ivec4 r;
    if (mode == CG_HSAT_PYRAMID) {
        if (!cg_hsat_texels(m, lo, hi, 0, r))
            return vec2(1.0, 0.0);
        int span = max(r.z - r.x, r.w - r.y) + 1;
        int top = int(cg_hsat_params.z) - 1;
        int L = min(span > 1 ? findMSB(span - 1) + 1 : 0, top);
        ivec4 q = r >> L;
        vec2 t00 = texelFetch(table, q.xy, L).rg, t10 = texelFetch(table, q.zy, L).rg;
        vec2 t01 = texelFetch(table, q.xw, L).rg, t11 = texelFetch(table, q.zw, L).rg;
        return vec2(min(min(t00.x, t10.x), min(t01.x, t11.x)), max(max(t00.y, t10.y), max(t01.y, t11.y)));
    }
    level = clamp(level, 0, int(cg_hsat_params.z) - 1);
    if (!cg_hsat_texels(m, lo, hi, level, r))
        return vec2(1.0, 0.0);
    float magnitude;
    vec3 sum = cg_hsat_sum(table, r, level, magnitude);
    float count = float((r.z - r.x + 1) * (r.w - r.y + 1));
    float p = cg_hsat_params.y;
    float hi_p, lo_p;
    if (mode == CG_HSAT_POWER_MEAN) {
        // Eq. 14 as written: the power mean.
        hi_p = max(sum.y, 0.0) / count;
        lo_p = max(sum.z, 0.0) / count;
    } else {
        // The un-normalised p-norm: sum x^p >= max^p. The margin covers fp32 rounding of the
        // four corners and the stored entries (a few ulps of the largest magnitude) and terms
        // x^p that flushed to zero (each below the smallest normal float).
        float margin = 8.0 * magnitude * 1.2e-7 + count * 1.2e-38;
        hi_p = max(sum.y, 0.0) + margin;
        lo_p = max(sum.z, 0.0) + margin;
    }
    float x_max = min(pow(hi_p, 1.0 / p), 1.0);
    float x_min = max(1.0 - pow(lo_p, 1.0 / p), 0.0);
    float range = m.y_max - m.y_min;
    return vec2(m.y_min + x_min * range, m.y_min + x_max * range);
}

// Eq. 13: the mean height over the world rectangle from the SAT modes' first channel
// (the pyramid mode has none: returns the midpoint of its range).
float
cg_hsat_mean(sampler2D table, CgHeightmap m, vec2 lo, vec2 hi, int level)
{
    if (cg_hsat_mode() == CG_HSAT_PYRAMID) {
        vec2 r = cg_hsat_range(table, m, lo, hi, level);
        return 0.5 * (r.x + r.y);
    }
    level = clamp(level, 0, int(cg_hsat_params.z) - 1);
    ivec4 r;
    if (!cg_hsat_texels(m, lo, hi, level, r))
        return m.y_min;
    float magnitude;
    vec3 sum = cg_hsat_sum(table, r, level, magnitude);
    float count = float((r.z - r.x + 1) * (r.w - r.y + 1));
    return m.y_min + clamp(sum.x / count, 0.0, 1.0) * (m.y_max - m.y_min);
}

#endif
