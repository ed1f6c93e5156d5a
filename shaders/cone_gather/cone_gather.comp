// cone_gather: indirect light of every G-buffer pixel by voxel cone tracing (VCT paper 3.2).
//
// Diffuse (3.2.1): a set of cones around the normal; each returns the radiance L_k it
// gathers front to back through the mipped lightmap, and the output is
//     sum_k W_k L_k  with  W_k = (1/pi) * integral over cone k's cell of cos  (hybrid eq. 3-4),
// the incident radiance integral E_i / pi, which composite multiplies by the albedo. The
// weights sum to 1 (passes/sdk/cone.c), so a uniform incident radiance L gathers to L.
// Alpha holds the ambient visibility sum_k W_k (1 - a_k) (VCT paper 3.2.3: rough AO).
// With the G-buffer's material (CG_GATHER_MATERIAL, common/gather.glsl) the sum is multiplied by
// the diffuse lobe's share rho/pi (1 - F) leaves (cg_gather_diffuse_share; 1 for a Lambertian
// material) and not traced where rho = 0 (metals, clear glass: composite multiplies it by rho).
// Specular (3.2.2, with SPECULAR): one cone along the mirror direction, its aperture from
// the roughness, weighted by the lobe's directional albedo F0 A + F90 B (split sum); none where
// F0 = F90 = 0. Without the material: the parameter's roughness, weight 1.
// Refraction (3.2.2, with REFRACTION and the material): one cone by Snell's law through both faces
// of a solid, or straight on through a thin sheet, weighted (cg_gather_refraction_lobe); none where
// tau = 0.
// Shadow (3.2.3, with SHADOW_CONE): one narrow cone towards a light; its
// transmittance 1 - a is a soft visibility.
// Decoupled resolution (CG_GATHER_DOWNSAMPLE, common/upsample.glsl, whose entry points these are
// with CG_GATHER_LOWRES or CG_GATHER_DEFERRED): the diffuse cones at one pixel of each block (the
// blocks that trace listed, then traced packed), every pixel's diffuse light upsampled from them or,
// where no block's surface agrees with the pixel's, traced in a dispatch of those pixels alone; the
// other cones at every pixel (main below).
#version 450 core
#include "common/cone_trace.glsl"
#include "common/gather.glsl"
#include "common/lights.glsl"
#ifdef CG_GATHER_DOWNSAMPLE
#include "common/upsample.glsl"
#endif

#ifdef SPECULAR
layout(binding = 1, rgba32f) writeonly uniform image2D u_reflection;
#endif
#ifdef REFRACTION
layout(binding = 4, rgba32f) writeonly uniform image2D u_refraction;
#endif
#ifdef SHADOW_CONE
layout(binding = 2, r16f) writeonly uniform image2D u_visibility;
#endif
#ifdef CG_CONE_COUNT_READS
layout(binding = 3, r32f) writeonly uniform image2D u_reads;
#endif

// The cone set and march: cg_cone_set_block (common/cone_trace.glsl); the mirror and shadow cones:
CG_UNIFORM_BLOCK(CgConeGather, cg_cone_gather_block, CG_BINDING_GATHER, CG_CONE_GATHER_BLOCK);

// A material lobe's cone (common/gather.glsl), traced from the surface it leaves, the sky seen
// through what it left open; rgb x the lobe's weight, a its coverage.
vec4
trace_lobe(CgVolume v, CgMarch march, float t_max, CgGatherLobe lobe)
{
    CgCone c = CgCone(lobe.origin, lobe.direction, lobe.tan_half, v.voxel_size, t_max, march.step, march.lod_bias);
    vec4 traced = cg_sky_gather(cg_cone_trace_surface(CG_GATHER_LOBE_VOLUME, v, c, lobe.surface), c.direction, c.tan_half);
    return vec4(traced.rgb * lobe.weight, traced.a);
}

#ifdef CG_GATHER_MATERIAL
// cg_gather_reflection's march (common/gather.glsl): reach.x = t_max.
vec4
cg_gather_trace_lobe(CgGatherLobe lobe, vec4 reach)
{
    return trace_lobe(cg_volume(), cg_cone_march(), reach.x, lobe);
}
#endif

// The diffuse cones of the surface point `position` with unit normal `n` (before the material's
// diffuse share): rgb the incident radiance integral E_i / pi, a the ambient visibility.
vec4
trace_diffuse(vec3 position, vec3 n)
{
    CgVolume v = cg_volume();
    CgMarch march = cg_cone_march();
    float t_max = cg_cone_reach(v, march.max_distance);
    vec3 origin = cg_cone_origin(v, position, n, march.start_offset);
    float offset = march.start_offset * v.voxel_size;
    return cg_cone_gather_diffuse(cg_gather_volume, v, origin, cg_tangent_frame(n), t_max, offset);
}

#ifdef CG_GATHER_DOWNSAMPLE
// The cones of the listed blocks and pixels (common/upsample.glsl's entry points), their reads counted.
vec4
cg_upsample_trace(ivec2 pixel, vec3 position, vec3 n)
{
    vec4 diffuse = trace_diffuse(position, n);
#ifdef CG_CONE_COUNT_READS
    imageStore(u_reads, pixel, vec4(float(cg_reads)));
#endif
    return diffuse;
}

void
cg_upsample_untraced(ivec2 pixel)
{
#ifdef CG_CONE_COUNT_READS
    imageStore(u_reads, pixel, vec4(0.0));
#endif
}

vec3
cg_upsample_camera()
{
    return cg_cone_gather_block.camera.xyz;
}
#endif

#if !defined(CG_GATHER_LOWRES) && !defined(CG_GATHER_DEFERRED)
void
main()
{
    ivec2 pixel;
    if (!cg_gather_pixel(pixel))
        return;
    vec3 position, n;
    vec4 diffuse = vec4(0.0, 0.0, 0.0, 1.0);
#ifdef CG_CONE_COUNT_READS
    float diffuse_reads = 0.0;
#endif
    vec4 reflection = vec4(0.0), refraction = vec4(0.0);
    float visibility = 1.0;
    bool traced = false;    // the pixel's own diffuse cones, here (downsample 1)
    if (cg_gather_surface(pixel, position, n)) {
        CgVolume v = cg_volume();
        CgMarch march = cg_cone_march();
        float t_max = cg_cone_reach(v, march.max_distance);
        vec3 origin = cg_cone_origin(v, position, n, march.start_offset);
        float offset = march.start_offset * v.voxel_size;
        vec3 view = normalize(position - cg_cone_gather_block.camera.xyz);
        // The surface every cone leaves: no sample may read its voxels (cg_cone_trace_surface).
        vec4 surface = vec4(n, offset);
#ifdef CG_GATHER_MATERIAL
        CgGatherMaterial m = cg_gather_material(pixel);
        bool diffuse_lobe = any(greaterThan(m.rho, vec3(0.0)));
#else
        bool diffuse_lobe = true;
#endif
#ifdef CG_GATHER_DOWNSAMPLE
        // No block agrees: its own cones, in the deferred dispatch (common/upsample.glsl).
        if (diffuse_lobe && !cg_upsample_diffuse(pixel, position, n, cg_cone_gather_block.camera.xyz, diffuse))
            cg_upsample_defer(pixel);
#else
        if (diffuse_lobe)
            diffuse = trace_diffuse(position, n);
        traced = diffuse_lobe;
#endif
#ifdef CG_CONE_COUNT_READS
        diffuse_reads = float(cg_reads);    // the diffuse cones' alone
#endif
#ifdef CG_GATHER_MATERIAL
        diffuse.rgb *= cg_gather_diffuse_share(m, cg_gather_brdf(max(dot(n, -view), 0.0), m.roughness));
#endif
#ifdef SPECULAR
#ifdef CG_GATHER_MATERIAL
        CgGatherLobe mirror = cg_gather_reflection_lobe(m, position, n, view, offset);
#else
        CgGatherLobe mirror = CgGatherLobe(origin, reflect(view, n), cg_cone_gather_block.tan_half.x, surface, vec3(1.0));
#endif
#ifdef CG_GATHER_MATERIAL
        if (any(greaterThan(mirror.weight, vec3(0.0))))
            reflection = cg_gather_reflection(m, mirror, view, vec4(t_max, 0.0, 0.0, 0.0));
#else
        reflection = trace_lobe(v, march, t_max, mirror);
#endif
#endif
#ifdef REFRACTION
        CgGatherLobe through = cg_gather_refraction_lobe(m, position, n, view, offset);
        if (any(greaterThan(through.weight, vec3(0.0))))
            refraction = trace_lobe(v, march, t_max, through);
#endif
#ifdef SHADOW_CONE
        int light = cg_cone_gather_block.shadow.x;
        if (light >= 0 && uint(light) < cg_light_count()) {
            CgLightSample s = cg_light_sample(cg_lights[light], position);
            float tan_half = cg_cone_gather_block.tan_half.y, reach = t_max;
            vec3 direction = s.to_light;
            if (!isinf(s.distance)) {
                // A light at a finite distance (point, spot), aimed at from the cone's origin: the
                // march ends where its footprint would reach the light, t (1 + tan) <= d, and at
                // least a voxel short of it, so that the surface the light hangs under (a ceiling)
                // does not shadow it.
                vec3 to = position + s.to_light * s.distance - origin;
                float d = length(to);
                direction = d > 0.0 ? to / d : s.to_light;
                reach = min(reach, min(d / (1.0 + tan_half), d - v.voxel_size));
            }
            CgCone towards = CgCone(origin, direction, tan_half, v.voxel_size, reach, march.step, march.lod_bias);
            visibility = 1.0 - cg_cone_trace_surface(cg_gather_volume, v, towards, surface).a;
        }
#endif
    }
    imageStore(cg_gather_radiance, pixel, diffuse);
#ifdef SPECULAR
    imageStore(u_reflection, pixel, reflection);
#endif
#ifdef REFRACTION
    imageStore(u_refraction, pixel, refraction);
#endif
#ifdef SHADOW_CONE
    imageStore(u_visibility, pixel, vec4(visibility));
#endif
#ifdef CG_CONE_COUNT_READS
#ifdef CG_GATHER_DOWNSAMPLE
    // A representative's reads are its block's, written by the blocks' dispatch.
    if (!cg_upsample_is_representative(pixel))
#endif
    imageStore(u_reads, pixel, vec4(diffuse_reads));
#endif
    cg_reads_commit(traced);
}
#endif
