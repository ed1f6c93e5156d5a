// heightmap_raster: one texel of the 2D lightmap (hybrid paper V.B): rgb = outgoing diffuse
// radiance of the direct light at the surface point under the texel centre (shadowed
// through the shadow map when there is one) plus emission, a = its height (world y).
// The lighting is voxelize.frag's, through the same common/lights.glsl and shadow.glsl,
// so the 2D and the 3D lightmap agree where they meet.
#version 450 core
#include "common/scene.glsl"
#include "common/lights.glsl"
#include "common/shadow.glsl"

layout(location = 0) in vec3 vs_world;
layout(location = 1) in vec3 vs_normal;
layout(location = 2) in vec2 vs_texcoord;

layout(binding = 2) uniform sampler2D u_shadow_map;
// Stored rgb = radiance / u_radiance_scale (1 for RGBA32F; heightmap_raster.c).
layout(location = 10) uniform float u_radiance_scale;

layout(location = 0) out vec4 out_texel;

void
main()
{
    vec3 n = normalize(vs_normal);
    // The map stores the surface seen from above: its upper side.
    if (n.y < 0.0)
        n = -n;
    vec3 albedo = cg_material_albedo(cg_material_index, vs_texcoord).rgb;
    vec3 radiance = cg_material_emissive(cg_material_index, vs_texcoord);
    for (uint i = 0u; i < cg_light_count(); i++) {
        CgLightSample s = cg_light_sample(cg_lights[i], vs_world);
        float visibility = cg_shadow_visibility(u_shadow_map, int(i), vs_world, n);
        radiance += visibility * cg_lambert_radiance(albedo, n, s);
    }
    out_texel = vec4(max(radiance, vec3(0.0)) / u_radiance_scale, vs_world.y);
}
