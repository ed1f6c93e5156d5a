// voxelize: world-space attributes for the geometry shader, which projects each triangle.
#version 450 core
#include "common/world_vertex.glsl"

void
main()
{
    gl_Position = cg_world_vertex();
}
