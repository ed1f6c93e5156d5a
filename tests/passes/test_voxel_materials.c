/* voxelize's surface model with glTF materials: a voxel holds the diffuse albedo a cone tracer's
 * bounce needs, rho = (1-m)(1-T) baseColor x the diffuse lobe's hemispherical (1 - F)
 * (cg_bsdf_diffuse_hemispherical), and is opaque whatever the material: a metal's voxel and a
 * glass's hold no diffuse light but still block (caustics off: DESIGN.md); alphaMode MASK below the
 * cutoff leaves no voxel at all, and a Lambertian material keeps its base colour. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/bsdf.h"
#include "cg/gl.h"
#include "test_support.h"
#include "vct_fixture.h"

#define RES 16

static const char graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"vox\": { \"type\": \"voxelize\", \"params\": { \"model\": \"surface\", \"resolution\": 16,"
    "   \"voxelizer\": \"%s\" } } },"
    " \"outputs\": [ \"vox.albedo\", \"vox.coverage\" ] }";

/* The voxels of one large triangle in the plane z = 0.3 with material 1 set up by `setup`: the mean
 * albedo over the occupied voxels and their count. */
static int
voxelize_with(cg_context *ctx, void (*setup)(cg_material *), const char *voxelizer, double albedo[3])
{
    vf_scene *s = calloc(1, sizeof *s);
    assert_non_null(s);
    vf_scene_init(s, 0.8f, 0.0f);
    s->materials[1].base_color[1] = 0.6f;
    s->materials[1].base_color[2] = 0.4f;
    setup(&s->materials[1]);
    vf_add_triangle(s, (double[3]){ -1, -1, 0.3 }, (double[3]){ 1, -1, 0.3 }, (double[3]){ 0, 1, 0.3 });
    vf_finish(s);
    vf_runner r;
    vf_run_format(&r, &s->scene, 16, 16, graph, voxelizer);
    int size = 0;
    float *vox = vf_read_volume(&r, "vox.albedo", 0, &size);
    int count = 0;
    albedo[0] = albedo[1] = albedo[2] = 0.0;
    for (int i = 0; i < size * size * size; i++)
        if (vox[4 * i + 3] > 0.0f) {
            count++;
            for (int c = 0; c < 3; c++)
                albedo[c] += vox[4 * i + c];
        }
    for (int c = 0; c < 3 && count > 0; c++)
        albedo[c] /= count;
    free(vox);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    free(s);
    return count;
}

static void
lambertian(cg_material *m)
{
    (void)m;
}

static void
dielectric(cg_material *m)
{
    m->specular = 1.0f;
    m->roughness = 0.5f;
}

static void
metal(cg_material *m)
{
    m->specular = 1.0f;
    m->metallic = 1.0f;
}

static void
glass(cg_material *m)
{
    m->specular = 1.0f;
    m->transmission = 1.0f;
}

static void
masked_out(cg_material *m)
{
    m->alpha_mode = CG_ALPHA_MASK;
    m->base_color[3] = 0.2f;    /* below the cutoff 0.5 everywhere */
}

static void
check_voxelizer(void **state, const char *voxelizer)
{
    cg_context *ctx = cg_test_gl_context(state);
    double a[3];
    int lambert_count = voxelize_with(ctx, lambertian, voxelizer, a);
    assert_true(lambert_count > 20);
    const double base[3] = { 0.8, 0.6, 0.4 };
    for (int c = 0; c < 3; c++)
        assert_float_equal(a[c], base[c], 1.0 / 255.0);

    /* A dielectric of ior 1.5: F0 = 0.04, F90 = 1; the hemispherical (1 - F) from the C terms. */
    int count = voxelize_with(ctx, dielectric, voxelizer, a);
    assert_int_equal(count, lambert_count);
    double ha = 0.0, hb = 0.0;
    for (int i = 0; i < 256; i++) {
        float ta, tb;
        cg_bsdf_diffuse_albedo_terms(sqrtf(((float)i + 0.5f) / 256.0f), &ta, &tb);
        ha += ta / 256.0;
        hb += tb / 256.0;
    }
    double keep = 1.0 - 0.04 * ha - hb;
    print_message("# %s: dielectric voxel albedo / base colour %.4f (expected %.4f)\n", voxelizer, a[0] / base[0],
                  keep);
    for (int c = 0; c < 3; c++)
        assert_float_equal(a[c], base[c] * keep, 1.0 / 255.0);

    /* Metal and glass: opaque voxels (the same ones) of no diffuse albedo. */
    count = voxelize_with(ctx, metal, voxelizer, a);
    assert_int_equal(count, lambert_count);
    for (int c = 0; c < 3; c++)
        assert_float_equal(a[c], 0.0, 0.0);
    count = voxelize_with(ctx, glass, voxelizer, a);
    assert_int_equal(count, lambert_count);
    for (int c = 0; c < 3; c++)
        assert_float_equal(a[c], 0.0, 0.0);

    /* MASK below the cutoff: nothing. */
    assert_int_equal(voxelize_with(ctx, masked_out, voxelizer, a), 0);
}

static void
test_geometry_voxelizer(void **state)
{
    check_voxelizer(state, "geometry");
}

static void
test_compute_voxelizer(void **state)
{
    check_voxelizer(state, "compute");
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_geometry_voxelizer),
             cmocka_unit_test(test_compute_voxelizer))
