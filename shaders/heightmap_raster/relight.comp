// heightmap_raster, cache=true: relights the 2D lightmap from the kept surface attributes
// (raster.frag with CG_HEIGHTMAP_GEOMETRY), one invocation per level-0 texel: the cost follows
// texels, not triangles. The texel is what raster.frag without CG_HEIGHTMAP_GEOMETRY writes
// for the same surface point: cg_surface_radiance (common/surface_light.glsl) / the radiance
// scale, and the height; a texel no mesh covers holds black at the lowest height, as the
// clear of the lit raster leaves it.
// LIGHTMAP_FORMAT (rgba16f or rgba32f) is defined by heightmap_raster.c.
#version 450 core
#include "common/surface_light.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 2) uniform sampler2D u_shadow_map;
layout(binding = 3) uniform sampler2D u_position;
layout(binding = 4) uniform sampler2D u_normal;
layout(binding = 5) uniform sampler2D u_albedo;
layout(binding = 6) uniform sampler2D u_emission;
layout(LIGHTMAP_FORMAT, binding = 0) writeonly uniform image2D u_lightmap;

layout(location = 10) uniform float u_radiance_scale;
layout(location = 11) uniform float u_lowest;   // the height of a texel no mesh covers

void
main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, imageSize(u_lightmap))))
        return;
    vec4 position = texelFetch(u_position, t, 0);
    vec4 texel = vec4(0.0, 0.0, 0.0, u_lowest);
    if (position.w > 0.5) {
        vec3 n = texelFetch(u_normal, t, 0).xyz;
        vec3 albedo = texelFetch(u_albedo, t, 0).rgb;
        vec3 emission = texelFetch(u_emission, t, 0).rgb;
        vec3 radiance = cg_surface_radiance(u_shadow_map, position.xyz, n, albedo, emission);
        texel = vec4(radiance / u_radiance_scale, position.y);
    }
    imageStore(u_lightmap, t, texel);
}
