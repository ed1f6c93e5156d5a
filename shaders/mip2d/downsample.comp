#version 450 core
// mip2d/downsample.comp: one level of a 2D lightmap's mip chain from the level below, a
// 2x2 box filter of all four channels, one invocation per output texel (hybrid paper V.B:
// "the lightmap is mipmapped"): rgb is the mean outgoing radiance over the texel and a
// the mean height, the paper's filtered geometry. The extreme heights of each block, which
// a mean loses, are the hsat pass's business.
// Defines: FORMAT (rgba16f or rgba32f).
layout(local_size_x = 8, local_size_y = 8) in;

layout(FORMAT, binding = 0) readonly uniform image2D u_src;
layout(FORMAT, binding = 1) writeonly uniform image2D u_dst;

void
main()
{
    ivec2 dst = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(dst, imageSize(u_dst))))
        return;
    vec4 sum = imageLoad(u_src, 2 * dst) + imageLoad(u_src, 2 * dst + ivec2(1, 0)) +
               imageLoad(u_src, 2 * dst + ivec2(0, 1)) + imageLoad(u_src, 2 * dst + ivec2(1, 1));
    imageStore(u_dst, dst, 0.25 * sum);
}
