// gbuffer: world-space attributes of the visible surface.
#version 450 core
#define CG_SCENE_VERTEX
#include "common/scene.glsl"

layout(location = 8) uniform mat4 view_proj;

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) out vec2 texcoord;

void
main()
{
    vec4 world = cg_model * vec4(cg_position, 1.0);
    world_position = world.xyz;
    world_normal = cg_normal_matrix * cg_normal;
    texcoord = cg_texcoord;
    gl_Position = view_proj * world;
}
