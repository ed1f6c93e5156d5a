#version 450 core
// mip3d/directional.comp: one level of one direction of the anisotropic mip chain
// (Crassin et al. 2011, 3D MIP-map pyramid of anisotropic voxels). For a cone travelling
// along +axis or -axis, a coarse voxel looks like its 2x2 columns of children composited
// front to back along that direction (c = c_front + (1 - a_front) c_back, likewise a), averaged
// over the columns: a wall across the direction stays opaque at every level, while the same
// wall seen edge-on covers only its share of the cross-section.
// Defines: FORMAT (rgba16f or rgba8).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(FORMAT, binding = 0) readonly uniform image3D u_src;
layout(FORMAT, binding = 1) writeonly uniform image3D u_dst;

layout(location = 0) uniform int u_axis;    // 0 x, 1 y, 2 z
layout(location = 1) uniform int u_sign;    // +1: travelling towards +axis (front = low side)

void
main()
{
    ivec3 dst = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(dst, imageSize(u_dst))))
        return;
    ivec3 step = ivec3(0);
    step[u_axis] = 1;
    int front = u_sign > 0 ? 0 : 1;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; i++) {
        // The two axes across the direction.
        ivec3 c = ivec3(0);
        c[(u_axis + 1) % 3] = i & 1;
        c[(u_axis + 2) % 3] = i >> 1;
        ivec3 base = dst * 2 + c;
        vec4 f = imageLoad(u_src, base + step * front);
        vec4 b = imageLoad(u_src, base + step * (1 - front));
        sum += f + (1.0 - f.a) * b;
    }
    imageStore(u_dst, dst, sum * 0.25);
}
