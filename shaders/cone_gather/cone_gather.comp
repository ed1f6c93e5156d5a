// cone_gather: indirect light of every G-buffer pixel by voxel cone tracing (VCT paper 3.2).
//
// Diffuse (3.2.1): a set of cones around the normal; each returns the radiance L_k it
// gathers front to back through the mipped lightmap, and the output is
//     sum_k W_k L_k  with  W_k = (1/pi) * integral over cone k's cell of cos  (hybrid eq. 3-4),
// the incident radiance integral E_i / pi, which composite multiplies by the albedo. The
// weights sum to 1 (passes/sdk/cone.c), so a uniform incident radiance L gathers to L.
// Alpha holds the ambient visibility sum_k W_k (1 - a_k) (VCT paper 3.2.3: rough AO).
// Specular (3.2.2, with SPECULAR): one cone along the mirror direction, its aperture from
// the roughness. Shadow (3.2.3, with SHADOW_CONE): one narrow cone towards a light; its
// transmittance 1 - a is a soft visibility.
#version 450 core
#include "common/cone_trace.glsl"
#include "common/gather.glsl"
#include "common/lights.glsl"

#ifdef SPECULAR
layout(binding = 1, rgba32f) writeonly uniform image2D u_specular;
#endif
#ifdef SHADOW_CONE
layout(binding = 2, r16f) writeonly uniform image2D u_visibility;
#endif
#ifdef CG_CONE_COUNT_READS
layout(binding = 3, r32f) writeonly uniform image2D u_reads;
#endif

// The cone set and march: cg_cone_set_block (common/cone_trace.glsl); the mirror and shadow cones:
CG_UNIFORM_BLOCK(CgConeGather, cg_cone_gather_block, CG_BINDING_GATHER, CG_CONE_GATHER_BLOCK);

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
    vec4 specular = vec4(0.0);
    float visibility = 1.0;
    if (cg_gather_surface(pixel, position, n)) {
        CgVolume v = cg_volume();
        CgMarch march = cg_cone_march();
        float t_max = cg_cone_reach(v, march.max_distance);
        vec3 origin = cg_cone_origin(v, position, n, march.start_offset);
        mat3 frame = cg_tangent_frame(n);
        // The surface every cone leaves: no sample may read its voxels (cg_cone_trace_surface).
        vec4 surface = vec4(n, march.start_offset * v.voxel_size);
        diffuse = cg_cone_gather_diffuse(cg_gather_volume, v, origin, frame, t_max, surface.w);
#ifdef CG_CONE_COUNT_READS
        diffuse_reads = cg_cone_reads;    // the diffuse cones' alone
#endif
#ifdef SPECULAR
        vec3 view = normalize(position - cg_cone_gather_block.camera.xyz);
        CgCone mirror = CgCone(origin, reflect(view, n), cg_cone_gather_block.tan_half.x, v.voxel_size, t_max,
                               march.step, march.lod_bias);
        specular = cg_sky_gather(cg_cone_trace_surface(cg_gather_volume, v, mirror, surface), mirror.direction,
                                 mirror.tan_half);
#endif
#ifdef SHADOW_CONE
        int light = cg_cone_gather_block.shadow.x;
        if (light >= 0 && uint(light) < cg_light_count()) {
            CgLightSample s = cg_light_sample(cg_lights[light], position);
            CgCone towards = CgCone(origin, s.to_light, cg_cone_gather_block.tan_half.y, v.voxel_size,
                                    min(t_max, s.distance), march.step, march.lod_bias);
            visibility = 1.0 - cg_cone_trace_surface(cg_gather_volume, v, towards, surface).a;
        }
#endif
    }
    imageStore(cg_gather_radiance, pixel, diffuse);
#ifdef SPECULAR
    imageStore(u_specular, pixel, specular);
#endif
#ifdef SHADOW_CONE
    imageStore(u_visibility, pixel, vec4(visibility));
#endif
#ifdef CG_CONE_COUNT_READS
    imageStore(u_reads, pixel, vec4(diffuse_reads));
#endif
}
