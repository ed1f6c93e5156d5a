// gbuffer: world position (w = 1 where a surface covers the pixel), world normal facing
// the camera, linear albedo and emitted radiance.
#version 450 core
#include "common/scene.glsl"

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 texcoord;

// 1 while the pass draws the height-field meshes (gbuffer.c), 0 for the others.
layout(location = 9) uniform int cg_gbuffer_heightfield;

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
    // A height field (hybrid eq. 5: one surface over the ground plane) is seen from above. At a
    // crest's silhouette the slope behind it, back-facing, meets the front slope at the crest
    // and can win the depth test at a pixel; turned to the viewer, its normal points into the
    // ground, and a cone gather from there reads the terrain's lit top from below (the hybrid's
    // 2D lightmap has no underside: 0.069 where the path tracer has 0.007, docs/hybrid.md).
    // Where the viewer sees a height field's triangle from below, its upper side is the one
    // shaded. The geometric normal towards the viewer is cross(dFdx, dFdy) in GL's window
    // coordinates; 0.01 keeps a vertical cliff, seen from either side, turned to the viewer.
    if (cg_gbuffer_heightfield != 0) {
        vec3 towards_viewer = normalize(cross(dFdx(world_position), dFdy(world_position)));
        if (towards_viewer.y < -0.01)
            n = -n;
    }
    out_position = vec4(world_position, 1.0);
    out_normal = vec4(n, 1.0);
    out_albedo = vec4(cg_material_albedo(cg_material_index, texcoord).rgb, 1.0);
    out_emissive = vec4(cg_material_emissive(cg_material_index, texcoord), 1.0);
}
