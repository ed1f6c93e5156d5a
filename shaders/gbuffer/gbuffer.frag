// gbuffer: world position (w = 1 where a surface covers the pixel), world normal facing
// the camera, linear albedo and emitted radiance.
#version 450 core
#include "common/scene.glsl"

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 texcoord;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_emissive;

void
main()
{
    // Surfaces are shaded on both sides (glTF meshes here are not closed): the normal
    // is turned towards the viewer.
    vec3 n = normalize(world_normal);
    if (!gl_FrontFacing)
        n = -n;
    out_position = vec4(world_position, 1.0);
    out_normal = vec4(n, 1.0);
    out_albedo = vec4(cg_material_albedo(cg_material_index, texcoord).rgb, 1.0);
    out_emissive = vec4(cg_material_emissive(cg_material_index, texcoord), 1.0);
}
