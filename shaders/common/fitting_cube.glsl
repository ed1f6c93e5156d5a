// common/fitting_cube.glsl: the axis-aligned cube that stands for one step of a cone
// (hybrid paper VI.A, eq. 10-11, figure 2): the unit cube centred at the origin, scaled by
// S and translated by T, so the cube is [T - S/2, T + S/2]^3.
//
// Provides: CgFittingCube, cg_fitting_cube().
//
// Eq. 10 (cone axis v parallel to a coordinate axis): S = d / sqrt(2), the square inscribed
// in the cone's cross-section of diameter d, T = sp + v (dis + S/2) on the axis.
// Eq. 11 (any other v): f1 = the body diagonal of the unit cube nearest v, theta1 = the
// angle between them; the cube's body diagonal, of length d1 + d2 = S sqrt(3), runs along
// f1 from the point of the cross-section circle at dis (d1 = d / 2 / sin theta1 behind the
// axis point P0 = sp + v (dis + cos theta1 d1)) to the cone's surface (d2 ahead of P0, by
// the law of sines in the triangle apex, P0, exit point). T = P0 + (d2 - d1)/2 f1.
//
// Hazards: eq. 11 needs theta1 > theta/2 (a diagonal inside the cone never meets its
// surface: d2 is infinite or negative), and as theta1 nears theta/2 the cube grows without
// bound. Where eq. 11 gives no cube or one wider than CG_FIT_MAX_RATIO cone diameters,
// eq. 10's inscribed cube is used instead (`equation` says which). Axis-parallel means
// within 1e-4 of an axis, where eq. 11's f1 is ambiguous anyway.
#ifndef CG_COMMON_FITTING_CUBE_GLSL
#define CG_COMMON_FITTING_CUBE_GLSL

#define CG_FIT_MAX_RATIO 4.0

struct CgFittingCube {
    vec3 centre;    // T
    float side;     // S
    int equation;   // 10 or 11
};

// sp: cone apex; v: unit axis; half_angle: theta / 2 (radians); dis: forward distance;
// d: the cone's diameter at dis (2 dis tan(theta/2), or more where the caller guards it);
// eq11: false to use eq. 10 for every direction.
CgFittingCube
cg_fitting_cube(vec3 sp, vec3 v, float half_angle, float dis, float d, bool eq11)
{
    vec3 av = abs(v);
    float along = max(av.x, max(av.y, av.z));
    CgFittingCube inscribed;
    inscribed.side = d / sqrt(2.0);
    inscribed.centre = sp + v * (dis + 0.5 * inscribed.side);
    inscribed.equation = 10;
    if (!eq11 || along > 1.0 - 1e-4)
        return inscribed;
    vec3 f1 = vec3(v.x < 0.0 ? -1.0 : 1.0, v.y < 0.0 ? -1.0 : 1.0, v.z < 0.0 ? -1.0 : 1.0) / sqrt(3.0);
    float cos1 = clamp(dot(v, f1), -1.0, 1.0);
    float theta1 = acos(cos1);
    float sin1 = sin(theta1);
    float opening = theta1 - half_angle;
    if (opening < 1e-3 || sin1 < 1e-6)
        return inscribed;
    float d1 = 0.5 * d / sin1;
    float along_p0 = dis + cos1 * d1;
    float d2 = along_p0 * sin(half_angle) / sin(opening);
    float side = (d1 + d2) / sqrt(3.0);
    if (!(side <= CG_FIT_MAX_RATIO * d))
        return inscribed;
    CgFittingCube c;
    c.side = side;
    c.centre = sp + v * along_p0 + 0.5 * (d2 - d1) * f1;
    c.equation = 11;
    return c;
}

#endif
