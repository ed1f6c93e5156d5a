// heightmap_raster: the height-field meshes seen from above, orthographic, looking down -y
// (hybrid paper V.B): x maps to the map's columns, z to its rows, and depth is the height
// from the top of the meshes' bounds, so the depth test keeps the highest surface.
#version 450 core
#include "common/world_vertex.glsl"

layout(location = 8) uniform vec4 u_map;     // x0, z0, 1 / Dx, 1 / Dz
layout(location = 9) uniform vec2 u_depth;   // top y, 1 / depth range

void
main()
{
    vec4 world = cg_world_vertex();
    vec2 uv = (world.xz - u_map.xy) * u_map.zw;
    gl_Position = vec4(uv * 2.0 - 1.0, (u_depth.x - world.y) * u_depth.y * 2.0 - 1.0, 1.0);
}
