#version 450 core
// tests/data/hsat_query.comp: evaluates common/hsat.glsl for a list of world rectangles,
// so that the test checks the very functions the hybrid tracer calls.
// In: u_queries[i] = (lo.x, lo.z, hi.x, hi.z), u_levels[i]; out: (min, max, mean, 0).
#include "common/heightmap.glsl"
#include "common/hsat.glsl"

layout(local_size_x = 64) in;

layout(binding = 4) uniform usampler2D u_table;
layout(std430, binding = 6) readonly buffer Queries { vec4 u_queries[]; };
layout(std430, binding = 7) readonly buffer Levels { int u_levels[]; };
layout(std430, binding = 8) writeonly buffer Results { vec4 u_results[]; };
layout(location = 0) uniform int u_count;

void
main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    CgHeightmap m = cg_heightmap();
    vec4 q = u_queries[i];
    vec2 r = cg_hsat_range(u_table, m, q.xy, q.zw, u_levels[i]);
    u_results[i] = vec4(r, cg_hsat_mean(u_table, m, q.xy, q.zw, u_levels[i]), 0.0);
}
