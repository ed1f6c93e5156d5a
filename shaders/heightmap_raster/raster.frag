// heightmap_raster: one texel of the height-field meshes seen from above (hybrid paper V.B),
// the surface point under the texel centre.
//
// Without CG_HEIGHTMAP_GEOMETRY (cache=false, the paper's rebuild): the texel of the 2D
// lightmap itself, rgb = outgoing diffuse radiance of the direct light (shadowed through the
// shadow map when there is one) plus emission (common/surface_light.glsl), a = height (world y).
// The lighting is voxelize.frag's, through the same common/lights.glsl and shadow.glsl, so the
// 2D and the 3D lightmap agree where they meet.
//
// With CG_HEIGHTMAP_GEOMETRY (cache=true): the surface attributes that lighting needs, kept
// across frames and relit every frame by relight.comp, which computes the very same
// cg_surface_radiance from them:
//   0 position  xyz = world position, w = 1 (0 where no mesh covers the texel: the clear)
//   1 normal    xyz = unit normal of the upper side
//   2 albedo    rgb
//   3 emission  rgb
#version 450 core
#include "common/scene.glsl"
#include "common/surface_light.glsl"

layout(location = 0) in vec3 vs_world;
layout(location = 1) in vec3 vs_normal;
layout(location = 2) in vec2 vs_texcoord;

#ifdef CG_HEIGHTMAP_GEOMETRY
layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_emission;
#else
layout(binding = 2) uniform sampler2D u_shadow_map;
// Stored rgb = radiance / u_radiance_scale (1 for RGBA32F; heightmap_raster.c).
layout(location = 10) uniform float u_radiance_scale;

layout(location = 0) out vec4 out_texel;
#endif

void
main()
{
    // alphaMode MASK: below the cutoff the surface is not there (glTF 3.9.4), for the 2D lightmap
    // too, as for the G-buffer and the voxels: the height and the light are those of what lies
    // below, or the clear where nothing does.
    if (cg_material_masked_out(cg_material_index, vs_texcoord))
        discard;
    vec3 n = normalize(vs_normal);
    // The map stores the surface seen from above: its upper side.
    if (n.y < 0.0)
        n = -n;
    vec3 albedo = cg_material_albedo(cg_material_index, vs_texcoord).rgb;
    vec3 emission = cg_material_emissive(cg_material_index, vs_texcoord);
#ifdef CG_HEIGHTMAP_GEOMETRY
    out_position = vec4(vs_world, 1.0);
    out_normal = vec4(n, 0.0);
    out_albedo = vec4(albedo, 0.0);
    out_emission = vec4(emission, 0.0);
#else
    vec3 radiance = cg_surface_radiance(u_shadow_map, vs_world, n, albedo, emission);
    out_texel = vec4(radiance / u_radiance_scale, vs_world.y);
#endif
}
