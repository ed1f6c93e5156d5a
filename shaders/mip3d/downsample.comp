#version 450 core
// mip3d/downsample.comp: one level of a 3D lightmap's mip chain from the level below,
// a 2x2x2 box filter (VCT paper 3.1, figure 5), one invocation per output voxel.
//
// The volume stores premultiplied colour (rgb = opacity x radiance) and opacity (a).
// OPACITY_AVERAGE: all four channels averaged; the coarse opacity is the fraction of the
//   volume that is occupied and the colour the opacity-weighted mean (Crassin et al. 2011).
// OPACITY_MAX: the coarse opacity is the largest child opacity, the colour still the
//   opacity-weighted mean; a thin wall stays opaque at every level instead of fading to
//   1/2^level, which keeps closed rooms closed (see docs/vct.md for the measurements).
// Defines: FORMAT (rgba16f or rgba8), OPACITY_MAX or OPACITY_AVERAGE.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(FORMAT, binding = 0) readonly uniform image3D u_src;
layout(FORMAT, binding = 1) writeonly uniform image3D u_dst;

void
main()
{
    ivec3 dst = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(dst, imageSize(u_dst))))
        return;
    vec4 sum = vec4(0.0);
    float alpha_max = 0.0;
    for (int i = 0; i < 8; i++) {
        vec4 s = imageLoad(u_src, dst * 2 + ivec3(i & 1, (i >> 1) & 1, i >> 2));
        sum += s;
        alpha_max = max(alpha_max, s.a);
    }
#if defined(OPACITY_MAX)
    // Premultiplied colour of the opacity-weighted mean, re-multiplied by the max opacity.
    vec3 color = sum.a > 0.0 ? sum.rgb * (alpha_max / sum.a) : vec3(0.0);
    imageStore(u_dst, dst, vec4(color, alpha_max));
#else
    imageStore(u_dst, dst, sum * 0.125);
#endif
}
