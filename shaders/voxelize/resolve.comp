#version 450 core
// voxelize/resolve.comp: turns the fixed-point sums of the voxelization into the lightmap's
// level 0: mean radiance of the fragments that fell in each voxel (averaged, never
// last-writer-wins, so the result does not depend on rasterization order), opacity 1
// where any fragment fell and 0 elsewhere (premultiplied colour: rgb = radiance there).
// The accumulation volume stacks four R32UI slabs along z: red, green, blue sums and the
// fragment count, each `resolution` deep.
// Defines: FORMAT (rgba16f or rgba8).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(r32ui, binding = 0) readonly uniform uimage3D u_accum;
layout(FORMAT, binding = 1) writeonly uniform image3D u_radiance;

layout(location = 0) uniform int u_resolution;
// Fixed-point units per unit of radiance (see voxelize.frag).
layout(location = 1) uniform float u_fixed_scale;
// Stored value = radiance / u_radiance_scale (1 for RGBA16F; a bound for RGBA8).
layout(location = 2) uniform float u_radiance_scale;

void
main()
{
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(u_resolution))))
        return;
    int slab = u_resolution;
    uint count = imageLoad(u_accum, v + ivec3(0, 0, 3 * slab)).r;
    vec4 result = vec4(0.0);
    if (count > 0u) {
        vec3 sum = vec3(imageLoad(u_accum, v).r,
                        imageLoad(u_accum, v + ivec3(0, 0, slab)).r,
                        imageLoad(u_accum, v + ivec3(0, 0, 2 * slab)).r);
        vec3 radiance = sum / (float(count) * u_fixed_scale);
        result = vec4(radiance / u_radiance_scale, 1.0);
    }
    imageStore(u_radiance, v, result);
}
