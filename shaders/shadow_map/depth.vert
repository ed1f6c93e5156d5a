// shadow_map: scene geometry into the light's depth map.
#version 450 core
#define CG_SCENE_VERTEX
#include "common/scene.glsl"

layout(location = 8) uniform mat4 light_view;
layout(location = 12) uniform mat4 light_proj;

#ifdef CG_SHADOW_MASK
// For mask.frag: alphaMode MASK's texels below the cutoff cast no shadow.
layout(location = 0) out vec2 texcoord;
#endif

void
main()
{
    // cg_normal_matrix and cg_material_index are declared by scene.glsl and unused here.
    // The view first, then the projection: through one view_proj matrix, a perspective depth
    // came out of a sum of terms as large as the world coordinates cancelling to about the
    // near plane's size, and a scene 60 m from the origin was shadowed everywhere (its depths
    // off by centimetres, its bias millimetres). Light-space coordinates are small, so the
    // projection then rounds only what the depth format rounds anyway.
    gl_Position = light_proj * (light_view * (cg_model * vec4(cg_position, 1.0)));
#ifdef CG_SHADOW_MASK
    texcoord = cg_texcoord;
#endif
}
