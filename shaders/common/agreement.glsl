// common/agreement.glsl: how well one surface point agrees with another, the range filter of a
// joint bilateral upsampling (Kopf et al. 2007, "Joint Bilateral Upsampling", eq. 2): the light
// gathered at one point stands in for another's only where both lie on one surface. Shared by the
// screen's upsampling (common/upsample.glsl) and voxel_light's gathers at the voxels with
// bounce_spacing > 1 (voxel_light/spacing.glsl), so that both tell surfaces apart alike.
//
// Provides: cg_agreement(), cg_upsample_agreement(), CG_UPSAMPLE_NORMAL_POWER, CG_UPSAMPLE_PLANE_PER_BLOCK,
//           CG_UPSAMPLE_MIN_AGREEMENT.
#ifndef CG_COMMON_AGREEMENT_GLSL
#define CG_COMMON_AGREEMENT_GLSL

// The range filter's widths (docs/results/gi-resolution.md measures them): the normal's power, the
// plane distance at which a block's agreement falls to 0, per block of spacing and metre of
// distance from the camera, and the least agreement for which a block counts at all (below it
// its weight is 0, so that a near block of another surface cannot outweigh a far one of the
// pixel's own).
#define CG_UPSAMPLE_NORMAL_POWER 32.0
#define CG_UPSAMPLE_PLANE_PER_BLOCK 0.004
#define CG_UPSAMPLE_MIN_AGREEMENT 0.25

// How well two surface points agree for the range filter, from the cosine of the angle between
// their normals and the distance of one from the other's tangent plane: cos^CG_UPSAMPLE_NORMAL_POWER
// times the fall of that distance to 0 at `tolerance`; 0 below CG_UPSAMPLE_MIN_AGREEMENT (another
// surface).
float
cg_agreement(float cosine, float plane, float tolerance)
{
    float agreement = pow(max(cosine, 0.0), CG_UPSAMPLE_NORMAL_POWER) * max(1.0 - plane / tolerance, 0.0);
    return agreement < CG_UPSAMPLE_MIN_AGREEMENT ? 0.0 : agreement;
}

// How well a surface point q with unit normal m agrees with the pixel's (a point `position` with
// unit normal `n`): q's distance from the pixel's tangent plane.
float
cg_upsample_agreement(vec3 q, vec3 m, vec3 position, vec3 n, float tolerance)
{
    return cg_agreement(dot(n, m), abs(dot(n, q - position)), tolerance);
}

#endif
