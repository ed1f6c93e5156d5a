// voxelize: world-space attributes for the geometry shader, which projects each triangle.
#version 450 core
#define CG_SCENE_VERTEX
#include "common/scene.glsl"

layout(location = 0) out vec3 vs_world;
layout(location = 1) out vec3 vs_normal;
layout(location = 2) out vec2 vs_texcoord;

void
main()
{
    vec4 world = cg_model * vec4(cg_position, 1.0);
    vs_world = world.xyz;
    vs_normal = cg_normal_matrix * cg_normal;
    vs_texcoord = cg_texcoord;
    gl_Position = world;
}
