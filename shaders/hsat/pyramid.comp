#version 450 core
// hsat/pyramid.comp: one level of the exact min/max height pyramid (the hsat pass's
// conservative default, common/hsat.glsl): level 0 from the 2D lightmap's heights (alpha
// of level 0), level L from the 2 x 2 blocks of level L - 1. One invocation per texel.
// The floats are stored as their bits in RG32UI texels, so that the tracer reads every
// hsat mode through one usampler2D.
// Defines: LIGHTMAP_FORMAT (rgba16f or rgba32f), FIRST (level 0).
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef FIRST
layout(LIGHTMAP_FORMAT, binding = 0) readonly uniform image2D u_lightmap;
#else
layout(rg32ui, binding = 0) readonly uniform uimage2D u_src;

vec2
load(ivec2 p)
{
    return uintBitsToFloat(imageLoad(u_src, p).rg);
}
#endif
layout(rg32ui, binding = 1) writeonly uniform uimage2D u_dst;

void
main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(u_dst))))
        return;
#ifdef FIRST
    float h = imageLoad(u_lightmap, p).a;
    imageStore(u_dst, p, uvec4(floatBitsToUint(h), floatBitsToUint(h), 0u, 0u));
#else
    vec2 a = load(2 * p), b = load(2 * p + ivec2(1, 0)), c = load(2 * p + ivec2(0, 1)), d = load(2 * p + ivec2(1, 1));
    vec2 r = vec2(min(min(a.x, b.x), min(c.x, d.x)), max(max(a.y, b.y), max(c.y, d.y)));
    imageStore(u_dst, p, uvec4(floatBitsToUint(r), 0u, 0u));
#endif
}
