// common/surface_light.glsl: the outgoing diffuse radiance of one surface point, as the 2D
// lightmap stores it: its emission plus, for every punctual light of the scene, the Lambertian
// radiance (common/lights.glsl) times the light's visibility through the shadow map
// (common/shadow.glsl), clamped at 0.
//
// Provides: cg_surface_radiance().
//
// Written once because two programs must agree on it to the bit: heightmap_raster's raster
// (raster.frag, cache=false: lit while rasterized) and its relight (relight.comp, cache=true:
// lit every frame from the kept surface attributes). Same inputs, same operations, same order.
#ifndef CG_SURFACE_LIGHT_GLSL
#define CG_SURFACE_LIGHT_GLSL

#include "common/lights.glsl"
#include "common/shadow.glsl"

// p: world position; n: unit normal (the side that faces the viewer of the map); albedo and
// emission as the material gives them at p.
vec3
cg_surface_radiance(sampler2D shadow_map, vec3 p, vec3 n, vec3 albedo, vec3 emission)
{
    vec3 radiance = emission;
    for (uint i = 0u; i < cg_light_count(); i++) {
        CgLightSample s = cg_light_sample(cg_lights[i], p);
        float visibility = cg_shadow_visibility(shadow_map, int(i), p, n);
        radiance += visibility * cg_lambert_radiance(albedo, n, s);
    }
    return max(radiance, vec3(0.0));
}

#endif
