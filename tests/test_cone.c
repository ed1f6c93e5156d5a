/* Cone sets (sdk/cone.h): weights integrate the cosine lobe to 1, each weight is its cell's
 * share of the lobe (checked by an independent quadrature), directions are unit and in the
 * hemisphere, and the tangent frame is orthonormal and finite for every normal. */
#include <math.h>
#include <stdio.h>

#include "cg/bsdf.h"
#include "sdk/cone.h"
#include "test_support.h"

static void
test_sizes(void **state)
{
    (void)state;
    int n = 0;
    const int *sizes = cgp_cone_set_sizes(&n);
    assert_int_equal(n, 5);
    assert_int_equal(sizes[0], 1);
    assert_int_equal(sizes[1], 6);
    assert_int_equal(sizes[2], 9);
    assert_int_equal(sizes[3], 16);
    assert_int_equal(sizes[4], 26);
    assert_true(sizes[4] <= CGP_CONE_MAX);
    cgp_cone_set set;
    assert_false(cgp_cone_set_make(0, &set));
    assert_false(cgp_cone_set_make(7, &set));
    assert_false(cgp_cone_set_make(17, &set));
    assert_false(cgp_cone_set_make(CGP_CONE_MAX, &set));
    assert_false(cgp_cone_set_valid_size(5));
}

/* Midpoint quadrature over (theta, phi) of cos(theta) sin(theta) / pi on cone k's cell: the band
 * [cell_lo, cell_hi] and the azimuth sector around the cone. Independent of the closed form in
 * cone.c. */
static double
quadrature_weight(const cgp_cone_set *set, int k)
{
    const cgp_cone *c = &set->cones[k];
    int ring = 0;
    for (int j = 0; j < set->count; j++)
        if (set->cones[j].cell_lo == c->cell_lo)
            ring++;
    double sector = 2.0 * M_PI / ring;
    const int steps = 2000;
    double dt = (c->cell_hi - c->cell_lo) / steps, integral = 0.0;
    for (int s = 0; s < steps; s++) {
        double t = c->cell_lo + (s + 0.5) * dt;
        integral += cos(t) * sin(t) * dt * sector;
    }
    return integral / M_PI;
}

/* Each set's weights are positive, match the quadrature of their cells and sum to one. */
static void
test_weights_sum_to_one(void **state)
{
    (void)state;
    int n = 0;
    const int *sizes = cgp_cone_set_sizes(&n);
    for (int i = 0; i < n; i++) {
        cgp_cone_set set;
        assert_true(cgp_cone_set_make(sizes[i], &set));
        assert_int_equal(set.count, sizes[i]);
        double sum = 0.0;
        for (int k = 0; k < set.count; k++) {
            const cgp_cone *c = &set.cones[k];
            sum += c->weight;
            assert_true(c->weight > 0.0f);
            double len = sqrt(c->direction[0] * c->direction[0] + c->direction[1] * c->direction[1] +
                              c->direction[2] * c->direction[2]);
            assert_float_equal(len, 1.0, 1e-6);
            assert_true(c->direction[2] > 0.0f);
            assert_true(c->half_angle > 0.0f && c->half_angle <= (float)(M_PI / 3.0 + 1e-6));
            double quadrature = quadrature_weight(&set, k);
            if (fabs(quadrature - c->weight) > 1e-5)
                fail_msg("%d cones, cone %d: weight %.7f, quadrature %.7f", sizes[i], k, c->weight, quadrature);
        }
        if (fabs(sum - 1.0) > 1e-6)
            fail_msg("%d cones: weights sum to %.9f", sizes[i], sum);
    }
}

/* The published weights of the 6-cone set (Crassin et al. 2011: pi/4 and 3 pi/20, over pi). */
static void
test_six_cone_weights(void **state)
{
    (void)state;
    cgp_cone_set set;
    assert_true(cgp_cone_set_make(6, &set));
    assert_float_equal(set.cones[0].weight, 0.25, 1e-6);
    for (int k = 1; k < 6; k++) {
        assert_float_equal(set.cones[k].weight, 0.15, 1e-6);
        assert_float_equal(acos(set.cones[k].direction[2]) * 180.0 / M_PI, 60.0, 1e-4);
    }
    assert_true(cgp_cone_set_make(9, &set));
    for (int k = 1; k < 9; k++)
        assert_float_equal(acos(set.cones[k].direction[2]) * 180.0 / M_PI, 45.0, 1e-4);
    assert_true(cgp_cone_set_make(16, &set));
    for (int k = 0; k < 16; k++)
        assert_float_equal(set.cones[k].weight, 1.0 / 16.0, 1e-6);
}

static void
check_frame(const float n[3])
{
    float t[3], b[3];
    cgp_cone_frame(n, t, b);
    for (int i = 0; i < 3; i++)
        assert_true(isfinite(t[i]) && isfinite(b[i]));
    float tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
    float bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
    float tb = t[0] * b[0] + t[1] * b[1] + t[2] * b[2];
    float tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    float bn = b[0] * n[0] + b[1] * n[1] + b[2] * n[2];
    assert_float_equal(tt, 1.0, 1e-5);
    assert_float_equal(bb, 1.0, 1e-5);
    assert_float_equal(tb, 0.0, 1e-5);
    assert_float_equal(tn, 0.0, 1e-5);
    assert_float_equal(bn, 0.0, 1e-5);
}

static void
test_frame_axes_and_grazing(void **state)
{
    (void)state;
    const float axes[][3] = {
        {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 0, -0.0f},
    };
    for (size_t i = 0; i < sizeof axes / sizeof axes[0]; i++) {
        check_frame(axes[i]);
    }
    /* Normals a hair off -z, where the naive frame divides by 1 + n.z = 0. */
    for (int i = 0; i < 50; i++) {
        float e = powf(10.0f, -(float)i / 5.0f);
        float n[3] = {e, 0.0f, -sqrtf(1.0f - e * e)};
        check_frame(n);
    }
}

/* The specular lobe's hemispherical albedo terms (what voxelize stores per voxel) are the
 * cosine-weighted means over n.v of the path tracer's directional albedo terms, integrated here on a
 * finer grid than the table's 32 columns; a smooth lobe returns all of uniform light with F0 = F90 = 1,
 * a rough one less (the single-scattering GGX loses energy), never more. */
static void
test_hemispherical_albedo(void **state)
{
    (void)state;
    float rg[2 * CGP_BRDF_TABLE_SIZE];
    cgp_brdf_hemispherical_fill(CGP_BRDF_TABLE_SIZE, rg);
    const int columns[] = {0, 9, 18, CGP_BRDF_TABLE_SIZE - 1};
    for (size_t c = 0; c < sizeof columns / sizeof columns[0]; c++) {
        int j = columns[c];
        float roughness = (float)j / (CGP_BRDF_TABLE_SIZE - 1);
        double a = 0.0, b = 0.0;
        const int steps = 96;
        for (int i = 0; i < steps; i++) {
            double nv = ((double)i + 0.5) / steps;
            float scale = 0.0f, bias = 0.0f;
            cg_bsdf_specular_albedo_terms(roughness * roughness, (float)nv, &scale, &bias);
            a += 2.0 * nv * scale / steps;
            b += 2.0 * nv * bias / steps;
        }
        fprintf(stderr, "# roughness %.3f: Abar %.4f (integrated %.4f), Bbar %.4f (%.4f)\n", roughness, rg[2 * j], a,
                rg[2 * j + 1], b);
        assert_true(fabs(rg[2 * j] - a) < 0.01 && fabs(rg[2 * j + 1] - b) < 0.01);
        assert_true(rg[2 * j] + rg[2 * j + 1] <= 1.0f + 1e-4f);
    }
    /* Smooth (roughness 0, the first texel): F0 + (1 - F0) times the hemispherical mean of
     * (1 - n.v)^5, 1/21. */
    assert_true(fabs(rg[0] + rg[1] - 1.0) < 0.01 && fabs(rg[1] - 1.0 / 21.0) < 0.01);
    /* Rough: the lobe loses what bounces between microfacets. */
    assert_true(rg[2 * (CGP_BRDF_TABLE_SIZE - 1)] + rg[2 * (CGP_BRDF_TABLE_SIZE - 1) + 1] < 0.95f);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_sizes),
             cmocka_unit_test(test_weights_sum_to_one),
             cmocka_unit_test(test_six_cone_weights),
             cmocka_unit_test(test_frame_axes_and_grazing),
             cmocka_unit_test(test_hemispherical_albedo))
