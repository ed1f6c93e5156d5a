// shadow_map: scene geometry into the light's depth map.
#version 450 core
#define CG_SCENE_VERTEX
#include "common/scene.glsl"

layout(location = 8) uniform mat4 light_view_proj;

void
main()
{
    // cg_normal_matrix and cg_material_index are declared by scene.glsl and unused here.
    gl_Position = light_view_proj * (cg_model * vec4(cg_position, 1.0));
}
