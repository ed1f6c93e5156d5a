#version 450 core
// voxel_light/inject.comp: the light of each voxel of the surface model (docs/vct.md), level 0 of
// the three volumes the cone tracers read (common/cone_trace.glsl, CG_CONE_SURFACE).
//
// Each side of the voxel's surface has its own radiance: the side N points to (+) and the other
// (-). With the mean normal N (|N| <= 1) of the voxel's facets and their mean albedo rho,
//     L+- = emission + rho / pi sum_lights E V+- max(0, +-N . l) + rho G+-
// (the lights' term with u_direct)
// l towards the light, E its irradiance, V+- its visibility through the shadow map at the surface
// point on that side (the mean of 2 x 2 points a half voxel apart across the plane, the voxel's
// footprint on it), G+- the gathered light of a bounce (E_i / pi on that side, gather.comp), with
// u_gathered. Lambert's law is linear in the normal, so the unnormalised mean normal gives the
// mean of the facets' own cosines wherever every facet faces the light: exact for a plane and for a
// corner of two lit planes (docs/vct.md measures it against lighting every fragment).
//
// Stored (premultiplied by w = alpha_x + alpha_y + alpha_z, radiance / the region's scale):
//     radiance = (w L_lit, w)   sides = (w beta, w D, 0, alpha_y)   normals = (w N_lit, alpha_z)
// the lit side being the brighter (Rec. 709 Y), N_lit the normal turned towards it, D the constant of
// its plane N_lit . (x - m) = D voxel (m the volume's centre, in level-0 voxels), beta = Y(L_other) / Y(L_lit): the other side as a fraction of the lit side's
// luminance (its colour the lit side's; exact for one light or symmetric emitters).
// The glossy volume (u_radiance_only) adds the specular albedo rho_s times the lobe's GGX alpha
// (voxelize's `specular`, with u_specular) to rho in the lights' term, and rho_s G0+- (G(V_0), the
// sky's and the emitters' light, u_source_*, with u_source): a metal's light after a glossy bounce
// (passes/voxel_light's header).
// VOXEL_LIGHT_LISTED: one invocation per voxel of voxel_light_list (list.comp), the level cleared
// to 0 before, so that the cost follows the occupied voxels, not the volume (the open world's
// first-frame voxel_light 1412 -> 235 ms at 160x90, 128^3, llvmpipe). Otherwise one invocation per voxel of the volume, which
// writes 0 where no surface is (the fallback when the list overflows) and, with u_build_list, lists
// the occupied voxels for the bounce gathers (voxel_light_list).
#ifdef VOXEL_LIGHT_LISTED
layout(local_size_x = 64) in;
#else
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#endif

// cg_tangent_frame:


#include "common/cone_trace.glsl"
#include "common/lights.glsl"
#include "common/shadow.glsl"
#include "voxel_light/surface.glsl"

layout(binding = 0) uniform sampler3D u_albedo;
layout(binding = 1) uniform sampler3D u_coverage;
layout(binding = 2) uniform sampler3D u_normal;
layout(binding = 3) uniform sampler3D u_emission;
layout(binding = 4) uniform sampler3D u_gathered_front;
layout(binding = 5) uniform sampler3D u_gathered_back;
layout(binding = 6) uniform sampler2D u_shadow_map;

layout(rgba16f, binding = 0) writeonly uniform image3D u_radiance;
layout(rgba16f, binding = 1) writeonly uniform image3D u_sides;
layout(rgba16f, binding = 2) writeonly uniform image3D u_normals;

layout(location = 1) uniform bool u_gathered;
layout(location = 2) uniform bool u_build_list;
layout(location = 3) uniform uint u_list_capacity;
// false: the emission alone (V_0 of passes/voxel_light's recursion), without the lights' direct light.
layout(location = 4) uniform bool u_direct;
// true: voxel_light's `glossy` (bound as u_radiance): the radiance alone, on the side that the normals
// already written for the volume `radiance` chose (u_lit_normals), whose sides and normals it shares
// (the other side's luminance fraction beta is radiance's).
layout(location = 5) uniform bool u_radiance_only;
layout(binding = 7) uniform sampler3D u_lit_normals;
layout(location = 6) uniform bool u_specular;
layout(location = 7) uniform bool u_source;
layout(binding = 8) uniform sampler3D u_specular_albedo;
layout(binding = 9) uniform sampler3D u_source_front;
layout(binding = 10) uniform sampler3D u_source_back;

float
luminance(vec3 c)
{
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// Visibility of light i on the side n (unit) of the plane through x: 2 x 2 points across the
// voxel's footprint on the plane, lifted (1 - |N|^2) voxels to that side. A voxel whose facets
// disagree (|N| < 1: a floor-wall corner, |N| = 0.71) has its mean plane through the solid's
// corner, where half of the taps lie inside the other facet and see no light: a chrome block
// reflecting such a corner showed it at 0.21 of the floor's radiance, 1.03 with the lift (docs/vct.md,
// Per material). A plane's voxels (|N| = 1) are not moved.
float
visibility(int i, vec3 x, vec3 n, float coherence, float voxel)
{
    mat3 frame = cg_tangent_frame(n);
    vec3 lifted = x + n * max(1.0 - coherence * coherence, 0.0) * voxel;
    float v = 0.0;
    for (int k = 0; k < 4; k++) {
        vec2 o = (vec2(k & 1, k >> 1) - 0.5) * 0.5 * voxel;
        v += cg_shadow_visibility(u_shadow_map, i, lifted + frame[0] * o.x + frame[1] * o.y, n);
    }
    return 0.25 * v;
}

void
main()
{
    CgVolume vol = cg_volume();
#ifdef VOXEL_LIGHT_LISTED
    // The listed voxels alone (list.comp), the level cleared before: no empty voxel, no list to build.
    VOXEL_LIGHT_LISTED_VOXEL(voxel_light_list, u_list_capacity, v);
    vec4 albedo = texelFetch(u_albedo, v, 0);
#else
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(vol.dims))))
        return;
    vec4 albedo = texelFetch(u_albedo, v, 0);
    if (albedo.a <= 0.0) {
        imageStore(u_radiance, v, vec4(0.0));
        if (u_radiance_only)
            return;
        imageStore(u_sides, v, vec4(0.0));
        imageStore(u_normals, v, vec4(0.0));
        return;
    }
    if (u_build_list) {
        VOXEL_LIGHT_APPEND(voxel_light_list, u_list_capacity, v);
    }
#endif
    vec3 alpha = texelFetch(u_coverage, v, 0).xyz;
    vec4 nd = texelFetch(u_normal, v, 0);
    vec3 n = nd.xyz;
    float coherence = length(n);
    vec3 nh = coherence > 1e-4 ? n / coherence : vec3(0.0, 0.0, 1.0);
    vec3 x = voxel_light_point(vol, v, nd.xyz, nd.w);
    vec3 emission = texelFetch(u_emission, v, 0).rgb;   // / vol.radiance_scale already (voxelize)
    vec3 front = vec3(0.0), back = vec3(0.0);
    {
        vec3 e_front = vec3(0.0), e_back = vec3(0.0);
        for (uint i = 0u; u_direct && i < cg_light_count(); i++) {
            CgLightSample s = cg_light_sample(cg_lights[i], x);
            float c = dot(n, s.to_light);
            if (c > 0.0)
                e_front += s.irradiance * c * visibility(int(i), x, nh, coherence, vol.voxel_size);
            else if (c < 0.0)
                e_back += s.irradiance * -c * visibility(int(i), x, -nh, coherence, vol.voxel_size);
        }
        // The specular lobe sends a punctual light's reflection into a lobe about its mirror direction,
        // which a voxel (one radiance every way) cannot hold: its exitance spread evenly (rho_s) lit a
        // gold block's face in the chrome beside it, where the path tracer's lobe sends nothing towards
        // it (0.06; 1.16 spread). rho_s alpha (voxelize's `specular`, a = the GGX alpha) keeps a rough
        // lobe's light and drops a mirror's: relMSE 0.0087 against 0.069 spread and 0.0078 without the
        // term on the glossy room, 0.0125 against 0.047 and 0.014 on the spheres under its sun
        // (docs/vct.md, Per material).
        vec4 specular = u_radiance_only && u_specular ? texelFetch(u_specular_albedo, v, 0) : vec4(0.0);
        vec3 rho = albedo.rgb + specular.rgb * specular.a;
        front += rho * e_front / CG_PI;
        back += rho * e_back / CG_PI;
    }
    front = front / vol.radiance_scale + emission;
    back = back / vol.radiance_scale + emission;
    if (u_gathered) {
        // Stored in the volumes' units already (gather.comp).
        front += albedo.rgb * texelFetch(u_gathered_front, v, 0).rgb;
        back += albedo.rgb * texelFetch(u_gathered_back, v, 0).rgb;
    }
    if (u_radiance_only && u_specular && u_source) {
        vec3 specular = texelFetch(u_specular_albedo, v, 0).rgb;
        front += specular * texelFetch(u_source_front, v, 0).rgb;
        back += specular * texelFetch(u_source_back, v, 0).rgb;
    }
    bool front_lit = u_radiance_only ? dot(texelFetch(u_lit_normals, v, 0).xyz, n) >= 0.0
                                     : luminance(front) >= luminance(back);
    vec3 lit = front_lit ? front : back, other = front_lit ? back : front;
    float sign = front_lit ? 1.0 : -1.0;
    float y = luminance(lit);
    float beta = y > 0.0 ? clamp(luminance(other) / y, 0.0, 1.0) : 1.0;
    float w = alpha.x + alpha.y + alpha.z;
    imageStore(u_radiance, v, vec4(w * lit, w));
    if (u_radiance_only)
        return;
    // The plane N . (x - c) = delta voxel through the voxel's centre c, as N . (x - m) = D voxel.
    vec3 c = vol.origin + (vec3(v) + 0.5) * vol.voxel_size, m = vol.origin + 0.5 * cg_volume_extent(vol);
    float plane = sign * (dot(n, c - m) / vol.voxel_size + nd.w);
    imageStore(u_sides, v, vec4(w * beta, w * plane, 0.0, alpha.y));
    imageStore(u_normals, v, vec4(w * sign * n, alpha.z));
}
