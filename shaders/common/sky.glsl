// common/sky.glsl: the scene's sky as the pass SDK bakes it (cgp_sky, passes/sdk/sky.h): a
// lat-long texture per cone aperture, layer 0 the sky's radiance, layer k > 0 its cosine-weighted
// mean over a cone of half angle theta_1 2^(k-1).
//
// Provides: cg_sky_present(), cg_sky_radiance(), cg_sky_gather().
//
// The cone tracers end every cone with cg_sky_gather: a cone that leaves the lightmaps with
// transmittance 1 - a left sees the sky through it (VCT paper 3.2.3: the occlusion a cone
// gathers is the sky's visibility), so it gathers (1 - a) x the sky's mean over its aperture in
// its direction. composite shows cg_sky_radiance(dir, 0) where the G-buffer has no surface.
#ifndef CG_COMMON_SKY_GLSL
#define CG_COMMON_SKY_GLSL

#include "common/blocks.h"

layout(binding = CG_UNIT_SKY) uniform sampler3D cg_sky_map;
CG_UNIFORM_BLOCK(CgSkyBlock, cg_sky_block, CG_BINDING_SKY, CG_SKY_BLOCK);

bool
cg_sky_present()
{
    return cg_sky_block.info.x != 0.0;
}

// The sky's radiance arriving from the unit direction `dir`, its cosine-weighted mean over a cone
// of half angle atan(tan_half) (0: the radiance in that direction). The layer is linear in theta
// up to layer 1, then in log2 theta (each layer twice the angle of the one before).
vec3
cg_sky_radiance(vec3 dir, float tan_half)
{
    // atan(0, 0) is undefined in GLSL: the zenith and the nadir take phi = 0.
    float phi = (dir.x == 0.0 && dir.z == 0.0) ? 0.0 : atan(dir.x, dir.z);
    float theta = acos(clamp(dir.y, -1.0, 1.0));
    float x = atan(max(tan_half, 0.0)) / cg_sky_block.info.z;
    float layers = cg_sky_block.info.y;
    float layer = clamp(x < 1.0 ? x : 1.0 + log2(x), 0.0, layers - 1.0);
    vec3 uvw = vec3(phi / (2.0 * 3.14159265358979) + 0.5, theta / 3.14159265358979, (layer + 0.5) / layers);
    // The horizon is a row boundary (the height is even): a direction reads only the rows on
    // its own side, so that the filter does not blend a daylight sky's bright horizon into the
    // black below it (or back). Smooth (convolved) layers lose at most half a row by this.
    float rows = float(textureSize(cg_sky_map, 0).y);
    float half_row = 0.5 / rows;
    uvw.y = dir.y >= 0.0 ? min(uvw.y, 0.5 - half_row) : max(uvw.y, 0.5 + half_row);
    return textureLod(cg_sky_map, uvw, 0.0).rgb;
}

// What a cone gathered, `traced` = (radiance, coverage a), with the sky seen through what it
// left open: rgb += (1 - a) sky(dir, aperture). A cone that stopped opaque (CG_CONE_OPAQUE) saw
// nothing past its last sample. With no sky, `traced` is returned as it came.
vec4
cg_sky_gather(vec4 traced, vec3 dir, float tan_half)
{
    if (cg_sky_present() && traced.a < 0.999)
        traced.rgb += (1.0 - max(traced.a, 0.0)) * cg_sky_radiance(dir, tan_half);
    return traced;
}

#endif
