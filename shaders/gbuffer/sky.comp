// gbuffer's background: where no surface covers the pixel (emissive alpha 0 after the draw), the
// scene's sky in the view direction is the emission the camera sees, as the path tracer's camera
// rays that leave the scene see it (its `emitted` part). The ray is the path tracer's: through
// the near-plane point of the pixel centre, from the eye (perspective) or along -z (orthographic),
// turned into the world by the camera-to-world matrix. GL rows run bottom to top.
#version 450 core
#include "common/sky.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32f) uniform image2D u_emissive;

layout(location = 0) uniform mat4 u_inv_proj;   // clip -> camera
layout(location = 1) uniform mat4 u_inv_view;   // camera -> world
layout(location = 2) uniform int u_orthographic;

void
main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_emissive);
    if (any(greaterThanEqual(pixel, size)) || imageLoad(u_emissive, pixel).a != 0.0)
        return;
    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(size) - 1.0;
    vec4 near = u_inv_proj * vec4(ndc, -1.0, 1.0);
    vec3 d = u_orthographic != 0 ? vec3(0.0, 0.0, -1.0) : near.xyz / near.w;
    // Alpha stays 0: the pixel is still background for every reader of the G-buffer.
    imageStore(u_emissive, pixel, vec4(cg_sky_radiance(normalize(mat3(u_inv_view) * d), 0.0), 0.0));
}
