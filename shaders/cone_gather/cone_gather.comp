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
#include "common/lights.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler3D u_volume;
layout(binding = 1) uniform sampler2D u_position;
layout(binding = 2) uniform sampler2D u_normal;

layout(binding = 0, rgba16f) writeonly uniform image2D u_radiance;
#ifdef SPECULAR
layout(binding = 1, rgba16f) writeonly uniform image2D u_specular;
#endif
#ifdef SHADOW_CONE
layout(binding = 2, r16f) writeonly uniform image2D u_visibility;
#endif

#define MAX_CONES 16
layout(location = 0) uniform vec4 u_cones[MAX_CONES];       // xyz tangent-space direction, w weight
layout(location = 16) uniform float u_tan_half[MAX_CONES];
layout(location = 32) uniform int u_cone_count;
layout(location = 33) uniform float u_step;                  // fraction of the cone diameter
layout(location = 34) uniform float u_start_offset;          // voxels along the normal
layout(location = 35) uniform float u_max_distance;          // world; <= 0: the volume's diagonal
layout(location = 36) uniform vec3 u_camera;
layout(location = 37) uniform float u_specular_tan_half;
layout(location = 38) uniform int u_shadow_light;
layout(location = 39) uniform float u_shadow_tan_half;
layout(location = 40) uniform float u_lod_bias;

void
main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(u_radiance))))
        return;
    vec4 position = texelFetch(u_position, pixel, 0);
    vec3 normal = texelFetch(u_normal, pixel, 0).xyz;
    vec4 diffuse = vec4(0.0, 0.0, 0.0, 1.0);
    vec4 specular = vec4(0.0);
    float visibility = 1.0;
    // Background pixels (w = 0) and a degenerate normal gather nothing.
    if (position.w > 0.0 && dot(normal, normal) > 1e-12) {
        CgVolume v = cg_volume();
        vec3 n = normalize(normal);
        float t_max = cg_cone_reach(v, u_max_distance);
        vec3 origin = cg_cone_origin(v, position.xyz, n, u_start_offset);
        mat3 frame = cg_tangent_frame(n);
        // The surface every cone leaves: no sample may read its voxels (cg_cone_trace_surface).
        vec4 surface = vec4(n, u_start_offset * v.voxel_size);
        diffuse = cg_cone_gather_diffuse(u_volume, v, origin, frame, u_cones, u_tan_half, u_cone_count, t_max,
                                         u_step, u_lod_bias, surface.w);
#ifdef SPECULAR
        vec3 view = normalize(position.xyz - u_camera);
        CgCone mirror = CgCone(origin, reflect(view, n), u_specular_tan_half, v.voxel_size, t_max, u_step, u_lod_bias);
        specular = cg_cone_trace_surface(u_volume, v, mirror, surface);
#endif
#ifdef SHADOW_CONE
        if (u_shadow_light >= 0 && uint(u_shadow_light) < cg_light_count()) {
            CgLightSample s = cg_light_sample(cg_lights[u_shadow_light], position.xyz);
            CgCone towards = CgCone(origin, s.to_light, u_shadow_tan_half, v.voxel_size,
                                    min(t_max, s.distance), u_step, u_lod_bias);
            visibility = 1.0 - cg_cone_trace_surface(u_volume, v, towards, surface).a;
        }
#endif
    }
    imageStore(u_radiance, pixel, diffuse);
#ifdef SPECULAR
    imageStore(u_specular, pixel, specular);
#endif
#ifdef SHADOW_CONE
    imageStore(u_visibility, pixel, vec4(visibility));
#endif
}
