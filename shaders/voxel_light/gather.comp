#version 450 core
// voxel_light/gather.comp: one bounce at the voxels. For each occupied voxel (voxel_light_list) and
// each side of its mean plane, the diffuse cones of the surface point on that side are traced
// through the current volumes by the very march of the screen's gather (cg_cone_gather_diffuse,
// common/cone_trace.glsl with CG_CONE_SURFACE), from start_offset voxels off the plane; the result,
// E_i / pi in the volumes' units, is the G+- that inject.comp adds times the albedo. A voxel whose
// facets face both ways (|N| < 0.1) has no side to gather on and gathers nothing.
// u_source: the volumes hold V_0 (the emitters' light); the result, G(V_0), is also written to
// u_source_front and u_source_back, which inject.comp reads for the glossy volume's specular albedo
// (passes/voxel_light's header).
// VOXEL_LIGHT_WHOLE: one invocation per voxel of the volume instead of the list, for a list that
// overflowed (more occupied voxels than it holds): an empty voxel has no side to gather on and writes
// 0, as inject.comp's whole-volume fallback does.
#ifdef VOXEL_LIGHT_WHOLE
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#else
layout(local_size_x = 64) in;
#endif

#include "common/cone_trace.glsl"
#include "voxel_light/surface.glsl"

layout(binding = CG_UNIT_VOLUME) uniform sampler3D u_radiance;
layout(binding = 2) uniform sampler3D u_normal;     // voxelize's normal: N, delta

layout(rgba16f, binding = 0) writeonly uniform image3D u_gathered_front;
layout(rgba16f, binding = 1) writeonly uniform image3D u_gathered_back;

layout(location = 3) uniform uint u_list_capacity;
layout(location = 4) uniform bool u_source;
layout(r11f_g11f_b10f, binding = 2) writeonly uniform image3D u_source_front;
layout(r11f_g11f_b10f, binding = 3) writeonly uniform image3D u_source_back;

void
main()
{
#ifdef VOXEL_LIGHT_WHOLE
    CgVolume vol = cg_volume();
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(vol.dims))))
        return;
#else
    VOXEL_LIGHT_LISTED_VOXEL(voxel_light_list, u_list_capacity, v);
    CgVolume vol = cg_volume();
#endif
    vec4 nd = texelFetch(u_normal, v, 0);
    float coherence = length(nd.xyz);
    vec4 gathered[2] = vec4[2](vec4(0.0), vec4(0.0));
    if (coherence >= 0.1) {
        vec3 nh = nd.xyz / coherence;
        vec3 x = voxel_light_point(vol, v, nd.xyz, nd.w);
        CgMarch march = cg_cone_march();
        float t_max = cg_cone_reach(vol, march.max_distance);
        for (int side = 0; side < 2; side++) {
            vec3 n = side == 0 ? nh : -nh;
            vec3 origin = cg_cone_origin(vol, x, n, march.start_offset);
            vec4 g = cg_cone_gather_diffuse(u_radiance, vol, origin, cg_tangent_frame(n), t_max,
                                            march.start_offset * vol.voxel_size);
            gathered[side] = vec4(g.rgb / vol.radiance_scale, 1.0);
        }
    }
    imageStore(u_gathered_front, v, gathered[0]);
    imageStore(u_gathered_back, v, gathered[1]);
    if (u_source) {
        imageStore(u_source_front, v, gathered[0]);
        imageStore(u_source_back, v, gathered[1]);
    }
    cg_reads_commit(coherence >= 0.1);
}
