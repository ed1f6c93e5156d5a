#version 450 core
// hsat/sat.comp: the summed-area tables of one level of a 2D lightmap's heights (hybrid
// eq. 13-14), for the hsat pass's SAT modes (common/hsat.glsl). Each texel contributes
// v = (x, x^p, (1 - x)^p), x the height normalised to [0, 1] over the map's height range.
//
// Precision (DESIGN.md, numerical hazards): an fp32 table of a 2048^2 level holds sums up to
// 4M, whose ulp (0.25) swamps a small rectangle's sum; subtracting the level mean (Hensley
// et al. 2005) is not enough where the terrain has a trend (measured: 2.6 m error in the
// mean height over small rectangles of a 200 m high terrain). So the sums are accumulated
// and stored in double: texel (2i, j) of the table holds the doubles (x, x^p) and texel
// (2i + 1, j) the double (1 - x)^p, as 32-bit halves (RGBA32UI), minus the level mean.
//
// One invocation per row, then one per column (PLATFORM.md: 16x faster than a shared-memory
// scan on llvmpipe). Stages (one define each):
//   ROW_SUMS   row j: the sum of v over the row into u_rows[j].
//   MEAN       one invocation: the level's mean of v from the row sums into the info buffer.
//   ROWS       row j: prefix sums of v - mean along the row into the table.
//   COLUMNS    column i: prefix sums of the ROWS result down the column, in place.
// Defines: LIGHTMAP_FORMAT, and one stage.
layout(local_size_x = 64) in;

#include "common/heightmap.glsl"

layout(LIGHTMAP_FORMAT, binding = 0) readonly uniform image2D u_lightmap;  // this level
layout(rgba32ui, binding = 1) uniform uimage2D u_table;                    // this level

// The info block that common/hsat.glsl reads, written here (the means).
CG_STORAGE_BLOCK(, CgHsatInfo, cg_hsat_info, CG_BINDING_HSAT, CG_HSAT_INFO_BLOCK);
layout(std430, binding = CG_BINDING_HSAT_ROWS) buffer HsatRows {
    dvec4 u_rows[];
};

layout(location = 0) uniform int u_size;
layout(location = 1) uniform int u_level;
layout(location = 2) uniform float u_p;

vec3
texel_value(ivec2 q)
{
    CgHeightmap m = cg_heightmap();
    float range = m.y_max - m.y_min;
    // Stored heights lie in [y_min, y_max] up to the raster's rounding.
    float x = range > 0.0 ? clamp((imageLoad(u_lightmap, q).a - m.y_min) / range, 0.0, 1.0) : 0.0;
    return vec3(x, pow(x, u_p), pow(1.0 - x, u_p));
}

void
store(ivec2 q, dvec3 v)
{
    imageStore(u_table, ivec2(2 * q.x, q.y), uvec4(unpackDouble2x32(v.x), unpackDouble2x32(v.y)));
    imageStore(u_table, ivec2(2 * q.x + 1, q.y), uvec4(unpackDouble2x32(v.z), 0u, 0u));
}

dvec3
load(ivec2 q)
{
    uvec4 a = imageLoad(u_table, ivec2(2 * q.x, q.y)), b = imageLoad(u_table, ivec2(2 * q.x + 1, q.y));
    return dvec3(packDouble2x32(a.xy), packDouble2x32(a.zw), packDouble2x32(b.xy));
}

void
main()
{
    int k = int(gl_GlobalInvocationID.x);
#if defined(MEAN)
    if (k != 0)
        return;
    dvec3 total = dvec3(0.0);
    for (int j = 0; j < u_size; j++)
        total += u_rows[j].xyz;
    cg_hsat_info.means[u_level] = vec4(vec3(total / (double(u_size) * double(u_size))), 0.0);
#else
    if (k >= u_size)
        return;
#if defined(ROW_SUMS)
    dvec3 sum = dvec3(0.0);
    for (int i = 0; i < u_size; i++)
        sum += dvec3(texel_value(ivec2(i, k)));
    u_rows[k] = dvec4(sum, 0.0);
#elif defined(ROWS)
    // The float mean the readers add back, so that table + count x mean is the sum.
    dvec3 mean = dvec3(cg_hsat_info.means[u_level].xyz);
    dvec3 sum = dvec3(0.0);
    for (int i = 0; i < u_size; i++) {
        sum += dvec3(texel_value(ivec2(i, k))) - mean;
        store(ivec2(i, k), sum);
    }
#elif defined(COLUMNS)
    dvec3 sum = dvec3(0.0);
    for (int j = 0; j < u_size; j++) {
        sum += load(ivec2(k, j));
        store(ivec2(k, j), sum);
    }
#endif
#endif
}
