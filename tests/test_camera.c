/* Camera conventions: a point projected by view_proj lands at the expected pixel (GL window
 * coordinates, pixel centres at +0.5, y from the bottom), aspect follows the image, an
 * orthographic camera, a scaled camera node, the framed view of a camera-less scene, finite
 * far planes, and camera selection by name and index. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/camera.h"
#include "cg/scene.h"
#include "test_support.h"

static void
project(const cg_view *v, const double p[3], double pixel[2], double *ndc_z)
{
    const float *m = v->view_proj;
    double c[4];
    for (int r = 0; r < 4; r++)
        c[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
    assert_true(c[3] > 0);
    pixel[0] = (c[0] / c[3] + 1) * 0.5 * v->width;
    pixel[1] = (c[1] / c[3] + 1) * 0.5 * v->height;
    if (ndc_z)
        *ndc_z = c[2] / c[3];
}

static void
cornell_point_lands_on_pixel(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:cornell", &s, &err), &err);
    int cam;
    assert_cg_ok(cg_camera_select(&s, NULL, &cam, &err), &err);
    assert_int_equal(cam, 0);
    cg_view v;
    cg_view_from_scene(&s, cam, 64, 64, &v);
    /* The camera sits at (0, 0.5, 1.85) looking down -z with yfov 0.7. A point at depth d
     * seen through the centre of pixel (40, 20) (window coordinates, from the bottom). */
    double d = 1.85, t = tan(0.35);
    double ndc[2] = { 2 * 40.5 / 64 - 1, 2 * 20.5 / 64 - 1 };
    double p[3] = { ndc[0] * d * t, 0.5 + ndc[1] * d * t, 0 };
    double px[2], z;
    project(&v, p, px, &z);
    assert_float_equal(px[0], 40.5, 1e-3);
    assert_float_equal(px[1], 20.5, 1e-3);
    assert_true(z > -1 && z < 1);
    /* Near and far planes map to NDC z -1 and +1 (GL clip space). */
    double near[3] = { 0, 0.5, 1.85 - s.cameras[0].znear }, far[3] = { 0, 0.5, 1.85 - s.cameras[0].zfar };
    project(&v, near, px, &z);
    assert_float_equal(z, -1, 1e-4);
    assert_float_equal(px[0], 32, 1e-4);
    project(&v, far, px, &z);
    assert_float_equal(z, 1, 1e-4);
    assert_float_equal(v.position[2], 1.85, 1e-6);
    /* Aspect 0 follows the image: at 128x64 the same point moves horizontally only by
     * the aspect, i.e. its NDC x halves. */
    cg_view wide;
    cg_view_from_scene(&s, cam, 128, 64, &wide);
    project(&wide, p, px, NULL);
    assert_float_equal(px[0], (ndc[0] / 2 + 1) * 0.5 * 128, 1e-3);
    assert_float_equal(px[1], 20.5, 1e-3);
    /* The inverses are inverses. */
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += (double)v.view_proj[k * 4 + r] * v.inv_view_proj[c * 4 + k];
            assert_float_equal(sum, c == r, 1e-4);
        }
    cg_scene_free(&s);
}

/* A scene of one triangle and the given camera (arrays from malloc, as cg_scene_free expects). */
static void
one_triangle_scene(cg_scene *s, const cg_camera *cam)
{
    memset(s, 0, sizeof *s);
    strcpy(s->name, "test");
    s->materials = calloc(1, sizeof *s->materials);
    s->material_count = 1;
    s->materials[0].base_color[0] = s->materials[0].base_color[1] = s->materials[0].base_color[2] = 1;
    s->materials[0].base_color_texture = s->materials[0].emissive_texture = -1;
    s->meshes = calloc(1, sizeof *s->meshes);
    s->mesh_count = 1;
    cg_mesh *m = &s->meshes[0];
    static const float pos[9] = { -10, 0, -10, 10, 0, -10, 0, 5, 10 };
    m->vertex_count = 3;
    m->index_count = 3;
    m->positions = malloc(sizeof pos);
    memcpy(m->positions, pos, sizeof pos);
    m->normals = calloc(9, sizeof(float));
    m->indices = malloc(3 * sizeof(uint32_t));
    for (uint32_t i = 0; i < 3; i++)
        m->indices[i] = i;
    for (int k = 0; k < 3; k++) {
        m->bounds_min[k] = fminf(fminf(pos[k], pos[3 + k]), pos[6 + k]);
        m->bounds_max[k] = fmaxf(fmaxf(pos[k], pos[3 + k]), pos[6 + k]);
    }
    s->instances = calloc(1, sizeof *s->instances);
    s->instance_count = 1;
    for (int k = 0; k < 4; k++)
        s->instances[0].world[5 * k] = 1;
    if (cam) {
        s->cameras = malloc(sizeof *cam);
        s->cameras[0] = *cam;
        s->camera_count = 1;
    }
    cg_scene_compute_bounds(s);
}

static void
orthographic_and_scaled_cameras(void **state)
{
    (void)state;
    cg_camera cam = { .type = CG_CAMERA_ORTHOGRAPHIC, .xmag = 3, .ymag = 2, .znear = 0.1f, .zfar = 50 };
    strcpy(cam.name, "ortho");
    for (int k = 0; k < 4; k++)
        cam.world[5 * k] = 1;
    cam.world[14] = 20; /* at z = 20 looking down -z */
    cg_scene s;
    one_triangle_scene(&s, &cam);
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_validate(&s, &err), &err);
    cg_view v;
    cg_view_from_scene(&s, 0, 80, 40, &v);
    assert_true(v.orthographic);
    /* ymag is the vertical half extent; horizontally ymag x (80/40) = 4. */
    double p[3] = { 1, 0.5, -5 }, px[2];
    project(&v, p, px, NULL);
    assert_float_equal(px[0], (1.0 / 4 + 1) * 0.5 * 80, 1e-3);
    assert_float_equal(px[1], (0.5 / 2 + 1) * 0.5 * 40, 1e-3);
    cg_scene_free(&s);

    /* A perspective camera whose node scales by 3: scale does not change what it sees. */
    cg_camera persp = { .type = CG_CAMERA_PERSPECTIVE, .yfov = 1.0f, .znear = 0.5f, .zfar = 0 };
    strcpy(persp.name, "scaled");
    for (int k = 0; k < 3; k++)
        persp.world[5 * k] = 3;
    persp.world[15] = 1;
    persp.world[12] = 1;
    persp.world[13] = 2;
    persp.world[14] = 30;
    one_triangle_scene(&s, &persp);
    cg_view_from_scene(&s, 0, 64, 64, &v);
    double q[3] = { 1 + 4 * tan(0.5) * 0.25, 2, 26 }, z;
    project(&v, q, px, &z);
    assert_float_equal(px[0], (0.25 + 1) * 32, 1e-3);
    assert_float_equal(px[1], 32, 1e-3);
    /* zfar 0 becomes a finite far plane beyond the whole scene. */
    assert_true(isfinite(v.zfar) && v.zfar > v.znear);
    for (int c = 0; c < 8; c++) {
        double corner[3] = { (c & 1) ? s.bounds_max[0] : s.bounds_min[0],
                             (c & 2) ? s.bounds_max[1] : s.bounds_min[1],
                             (c & 4) ? s.bounds_max[2] : s.bounds_min[2] };
        double dz = 30 - corner[2];
        if (dz <= v.znear)
            continue;
        project(&v, corner, px, &z);
        assert_true(z < 1);
    }
    cg_scene_free(&s);
}

static void
framed_view_sees_the_bounds(void **state)
{
    (void)state;
    cg_scene s;
    one_triangle_scene(&s, NULL);
    int cam;
    cg_error err = { 0 };
    assert_cg_ok(cg_camera_select(&s, "", &cam, &err), &err);
    assert_int_equal(cam, -1);
    int sizes[3][2] = { { 64, 64 }, { 200, 50 }, { 30, 90 } };
    for (int i = 0; i < 3; i++) {
        cg_view v;
        cg_view_from_scene(&s, -1, sizes[i][0], sizes[i][1], &v);
        for (int c = 0; c < 8; c++) {
            double corner[3] = { (c & 1) ? s.bounds_max[0] : s.bounds_min[0],
                                 (c & 2) ? s.bounds_max[1] : s.bounds_min[1],
                                 (c & 4) ? s.bounds_max[2] : s.bounds_min[2] };
            double px[2], z;
            project(&v, corner, px, &z);
            assert_true(px[0] >= 0 && px[0] <= sizes[i][0]);
            assert_true(px[1] >= 0 && px[1] <= sizes[i][1]);
            assert_true(z > -1 && z < 1);
        }
    }
    cg_scene_free(&s);
}

static void
camera_selection(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:openworld?triangles=10000", &s, &err), &err);
    int cam = -5;
    assert_cg_ok(cg_camera_select(&s, "overview", &cam, &err), &err);
    assert_int_equal(cam, 0);
    assert_cg_ok(cg_camera_select(&s, "0", &cam, &err), &err);
    assert_int_equal(cam, 0);
    assert_cg_status(cg_camera_select(&s, "1", &cam, &err), &err, CG_ERR_USAGE);
    assert_cg_status(cg_camera_select(&s, "nobody", &cam, &err), &err, CG_ERR_USAGE);
    assert_non_null(strstr(err.message, "overview"));
    cg_scene_free(&s);
}

int
main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cornell_point_lands_on_pixel),
        cmocka_unit_test(orthographic_and_scaled_cameras),
        cmocka_unit_test(framed_view_sees_the_bounds),
        cmocka_unit_test(camera_selection),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
