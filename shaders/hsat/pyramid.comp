#version 450 core
// hsat/pyramid.comp: one level of the exact min/max height pyramid (the hsat pass's
// conservative default, common/hsat.glsl): level 0 from the 2D lightmap's heights (alpha
// of level 0), level L from the 2 x 2 blocks of level L - 1. One invocation per texel.
// Defines: LIGHTMAP_FORMAT (rgba16f or rgba32f), FIRST (level 0).
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef FIRST
layout(LIGHTMAP_FORMAT, binding = 0) readonly uniform image2D u_lightmap;
#else
layout(rg32f, binding = 0) readonly uniform image2D u_src;
#endif
layout(rg32f, binding = 1) writeonly uniform image2D u_dst;

void
main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(u_dst))))
        return;
#ifdef FIRST
    float h = imageLoad(u_lightmap, p).a;
    imageStore(u_dst, p, vec4(h, h, 0.0, 0.0));
#else
    vec2 a = imageLoad(u_src, 2 * p).rg, b = imageLoad(u_src, 2 * p + ivec2(1, 0)).rg;
    vec2 c = imageLoad(u_src, 2 * p + ivec2(0, 1)).rg, d = imageLoad(u_src, 2 * p + ivec2(1, 1)).rg;
    imageStore(u_dst, p, vec4(min(min(a.x, b.x), min(c.x, d.x)), max(max(a.y, b.y), max(c.y, d.y)), 0.0, 0.0));
#endif
}
