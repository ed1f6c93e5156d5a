// gbuffer: world-space attributes of the visible surface.
#version 450 core
#include "common/world_vertex.glsl"

layout(location = 8) uniform mat4 view_proj;

// Locations 0..2: world position, normal and texcoord (common/world_vertex.glsl).

// xyz = the tangent in world space (a direction on the surface: the model's linear part), w = the
// bitangent's sign; 0 where the mesh has no tangents.
layout(location = 3) out vec4 world_tangent;
// World metres per mesh unit across the surface (KHR_materials_volume's thickness is in mesh units):
// the length the model gives a unit step along the mesh's normal.
layout(location = 4) out float thickness_scale;

void
main()
{
    vec4 world = cg_world_vertex();
    world_tangent = vec4(mat3(cg_model) * cg_tangent.xyz, cg_tangent.w);
    float n2 = dot(cg_normal, cg_normal);
    thickness_scale = n2 > 0.0 ? length(mat3(cg_model) * cg_normal) / sqrt(n2) : 1.0;
    gl_Position = view_proj * world;
}
