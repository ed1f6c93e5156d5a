#version 450 core
// tests/data/fitting_cube.comp: evaluates common/fitting_cube.glsl (hybrid eq. 10-11) for a
// list of cones so that the test checks the very function the hybrid tracer calls.
// In: (v.xyz, half angle), (dis, d, eq11, 0); out: (T.xyz, S), (equation, 0, 0, 0).
#include "common/fitting_cube.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 6) readonly buffer Cones { vec4 u_cones[]; };
layout(std430, binding = 8) writeonly buffer Results { vec4 u_results[]; };
layout(location = 0) uniform int u_count;
layout(location = 1) uniform vec3 u_apex;

void
main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    vec4 a = u_cones[2 * i], b = u_cones[2 * i + 1];
    CgFittingCube c = cg_fitting_cube(u_apex, a.xyz, a.w, b.x, b.y, b.z > 0.5);
    u_results[2 * i] = vec4(c.centre, c.side);
    u_results[2 * i + 1] = vec4(float(c.equation), 0.0, 0.0, 0.0);
}
