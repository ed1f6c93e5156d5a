#version 450 core
// voxel_light/mip.comp: one level of the surface voxels (inject.comp's three volumes) from the
// level below, in place. For the 2 x 2 x 2 children c of a coarse cell:
//   alpha_i = 1/4 sum over the 4 columns along axis i of min(1, alpha_i(front) + alpha_i(back)):
//             a surface split over the two children of a column counts once (not twice, not
//             1 - (1 - a)^2), a wall across axis i stays opaque along i at every level, and the
//             same wall seen edge-on covers only the share of the columns it is in;
//   X = sum_c w_c X_c / sum_c w_c for X in {L_lit, beta, N}, stored premultiplied by the coarse w;
//   D likewise: the planes' constants N . (x - m) = D voxel (m the volume's centre) need no moving,
//             so that the mean plane of a level is the w-weighted mean of its children's.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(rgba16f, binding = 0) readonly uniform image3D u_src_radiance;
layout(rgba16f, binding = 1) readonly uniform image3D u_src_sides;
layout(rgba16f, binding = 2) readonly uniform image3D u_src_normals;
layout(rgba16f, binding = 3) writeonly uniform image3D u_dst_radiance;
layout(rgba16f, binding = 4) writeonly uniform image3D u_dst_sides;
layout(rgba16f, binding = 5) writeonly uniform image3D u_dst_normals;


void
main()
{
    ivec3 dst = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(dst, imageSize(u_dst_radiance))))
        return;
    vec4 ra[8], si[8], no[8];
    vec3 sum_l = vec3(0.0), sum_n = vec3(0.0);
    float sum_beta = 0.0, sum_delta = 0.0, sum_w = 0.0;
    for (int i = 0; i < 8; i++) {
        ivec3 p = dst * 2 + ivec3(i & 1, (i >> 1) & 1, i >> 2);
        ra[i] = imageLoad(u_src_radiance, p);
        si[i] = imageLoad(u_src_sides, p);
        no[i] = imageLoad(u_src_normals, p);
        sum_l += ra[i].rgb;
        sum_beta += si[i].r;
        sum_n += no[i].rgb;
        sum_w += ra[i].a;
        sum_delta += si[i].g;
    }
    // Child index bits: x = 1, y = 2, z = 4; the column along axis k pairs i and i + (1 << k).
    vec3 alpha = vec3(0.0);
    for (int k = 0; k < 3; k++) {
        int bit = 1 << k;
        float columns = 0.0;
        for (int i = 0; i < 8; i++) {
            if ((i & bit) != 0)
                continue;
            vec3 af = vec3(max(ra[i].a - si[i].a - no[i].a, 0.0), si[i].a, no[i].a);
            int j = i + bit;
            vec3 ab = vec3(max(ra[j].a - si[j].a - no[j].a, 0.0), si[j].a, no[j].a);
            columns += min(af[k] + ab[k], 1.0);
        }
        alpha[k] = 0.25 * columns;
    }
    float w = alpha.x + alpha.y + alpha.z;
    float k = sum_w > 0.0 ? w / sum_w : 0.0;
    imageStore(u_dst_radiance, dst, vec4(sum_l * k, w));
    imageStore(u_dst_sides, dst, vec4(sum_beta * k, sum_delta * k, 0.0, alpha.y));
    imageStore(u_dst_normals, dst, vec4(sum_n * k, alpha.z));
}
