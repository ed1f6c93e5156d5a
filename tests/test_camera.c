/* Camera conventions: a point projected by view_proj lands at the expected pixel (GL window
 * coordinates, pixel centres at +0.5, y from the bottom), aspect follows the image, an
 * orthographic camera, a scaled camera node, the framed view of a camera-less scene, finite
 * far planes, camera selection by name, index and "auto", a camera's own aspect ratio fitted
 * inside the image instead of stretched, and views moved, aimed and zoomed by a cg_view_spec. */
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
    /* The material's other textures none too, and no attenuation (cg_scene_validate checks them). */
    s->materials[0].metallic_roughness_texture = s->materials[0].normal_texture = -1;
    s->materials[0].occlusion_texture = s->materials[0].transmission_texture = -1;
    s->materials[0].attenuation_distance = INFINITY;
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

/* glTF aspectRatio 1 in a 2:1 and a 1:2 image: the camera's square frame fits inside, its
 * corner lands on the image's edge, pixels stay square (no stretch). */
static void
own_aspect_ratio_is_fitted_not_stretched(void **state)
{
    (void)state;
    cg_camera cam = { .type = CG_CAMERA_PERSPECTIVE, .yfov = 0.6f, .aspect = 1.0f, .znear = 0.1f, .zfar = 100 };
    strcpy(cam.name, "square");
    for (int k = 0; k < 4; k++)
        cam.world[5 * k] = 1;
    cam.world[14] = 20;
    cg_scene s;
    one_triangle_scene(&s, &cam);
    double t = tan(0.3), d = 10;
    /* The top-right corner of the camera's square frame at depth d. */
    double corner[3] = { t * d, t * d, 20 - d }, px[2];
    cg_view v;
    cg_view_from_scene(&s, 0, 200, 100, &v);
    project(&v, corner, px, NULL);
    assert_float_equal(px[1], 100, 1e-3);           /* the vertical field of view is kept */
    assert_float_equal(px[0], 100 + 50, 1e-3);      /* square pixels: half the height to the right */
    cg_view_from_scene(&s, 0, 100, 200, &v);
    project(&v, corner, px, NULL);
    assert_float_equal(px[0], 100, 1e-3);           /* the horizontal one is kept, the vertical widened */
    assert_float_equal(px[1], 100 + 50, 1e-3);
    char note[512];
    cg_view_spec spec = { .camera = 0 };
    assert_true(cg_view_aspect_note(&s, &spec, 200, 100, note, sizeof note));
    assert_non_null(strstr(note, "camera 'square' has aspect ratio 1 and the 200x100 image 2"));
    assert_non_null(strstr(note, "horizontal field of view is widened from 34.4 to 63.5 degrees"));
    assert_true(cg_view_aspect_note(&s, &spec, 100, 200, note, sizeof note));
    assert_non_null(strstr(note, "vertical field of view is widened from 34.4 to 63.5 degrees"));
    assert_false(cg_view_aspect_note(&s, &spec, 100, 100, note, sizeof note));
    /* An orthographic camera: its 1:1 frame of half extent 2 inside a 1:2 image. */
    s.cameras[0] = (cg_camera){ .type = CG_CAMERA_ORTHOGRAPHIC, .xmag = 2, .ymag = 2, .aspect = 1, .znear = 0.1f,
                                .zfar = 50 };
    memcpy(s.cameras[0].world, cam.world, sizeof cam.world);
    cg_view_from_scene(&s, 0, 100, 200, &v);
    double edge[3] = { 2, 2, 0 };
    project(&v, edge, px, NULL);
    assert_float_equal(px[0], 100, 1e-3);
    assert_float_equal(px[1], 150, 1e-3);
    cg_scene_free(&s);
}

/* --from, --look-at, --fov on the framing and on a scene camera. */
static void
view_spec_moves_aims_and_zooms(void **state)
{
    (void)state;
    cg_camera cam = { .type = CG_CAMERA_PERSPECTIVE, .yfov = 0.6f, .znear = 0.1f, .zfar = 0 };
    strcpy(cam.name, "cam");
    for (int k = 0; k < 4; k++)
        cam.world[5 * k] = 1;
    cam.world[14] = 20;
    cg_scene s;
    one_triangle_scene(&s, &cam);
    cg_error err = { 0 };
    double px[2], z;
    /* The framing aimed from a chosen eye: the point looked at lands in the middle and the
     * whole scene lies between the planes. */
    cg_view_spec spec = { .camera = -1, .from_given = true, .from = { 30, 40, 50 }, .look_at_given = true,
                          .look_at = { 1, 2, 3 } };
    assert_cg_ok(cg_view_spec_check(&s, &spec, &err), &err);
    cg_view v;
    cg_view_from_spec(&s, &spec, 64, 32, &v);
    assert_float_equal(v.position[0], 30, 1e-5);
    assert_float_equal(v.position[2], 50, 1e-5);
    double target[3] = { 1, 2, 3 };
    project(&v, target, px, NULL);
    assert_float_equal(px[0], 32, 1e-3);
    assert_float_equal(px[1], 16, 1e-3);
    for (int c = 0; c < 8; c++) {
        double corner[3] = { (c & 1) ? s.bounds_max[0] : s.bounds_min[0], (c & 2) ? s.bounds_max[1] : s.bounds_min[1],
                             (c & 4) ? s.bounds_max[2] : s.bounds_min[2] };
        project(&v, corner, px, &z);
        assert_true(z > -1 && z < 1);
    }
    /* Straight down has an up vector too. */
    spec = (cg_view_spec){ .camera = -1, .from_given = true, .from = { 0, 50, 0 }, .look_at_given = true };
    cg_view_from_spec(&s, &spec, 64, 64, &v);
    project(&v, (double[3]){ 0, 0, 0 }, px, NULL);
    assert_float_equal(px[0], 32, 1e-3);
    assert_float_equal(px[1], 32, 1e-3);
    assert_true(isfinite(v.inv_view_proj[0]));
    /* A scene camera moved keeps its orientation; --fov sets the image's vertical field. */
    spec = (cg_view_spec){ .camera = 0, .from_given = true, .from = { 5, 1, 30 }, .yfov = 1.0f };
    assert_cg_ok(cg_view_spec_check(&s, &spec, &err), &err);
    cg_view_from_spec(&s, &spec, 64, 64, &v);
    double ahead[3] = { 5, 1 + 10 * tan(0.5), 20 };
    project(&v, ahead, px, NULL);
    assert_float_equal(px[0], 32, 1e-3);
    assert_float_equal(px[1], 64, 1e-3);
    /* Refused: a look-at point at the eye, a field of view out of range or for an
     * orthographic camera, a camera the scene lacks. */
    spec = (cg_view_spec){ .camera = 0, .look_at_given = true, .look_at = { 0, 0, 20 } };
    assert_cg_status(cg_view_spec_check(&s, &spec, &err), &err, CG_ERR_USAGE);
    spec = (cg_view_spec){ .camera = -1, .yfov = 3.2f };
    assert_cg_status(cg_view_spec_check(&s, &spec, &err), &err, CG_ERR_USAGE);
    spec = (cg_view_spec){ .camera = 1 };
    assert_cg_status(cg_view_spec_check(&s, &spec, &err), &err, CG_ERR_USAGE);
    s.cameras[0].type = CG_CAMERA_ORTHOGRAPHIC;
    s.cameras[0].ymag = 1;
    s.cameras[0].zfar = 50;
    spec = (cg_view_spec){ .camera = 0, .yfov = 1.0f };
    assert_cg_status(cg_view_spec_check(&s, &spec, &err), &err, CG_ERR_USAGE);
    assert_non_null(strstr(err.message, "orthographic"));
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
    /* auto: the framing, although the scene has a camera. */
    assert_cg_ok(cg_camera_select(&s, "auto", &cam, &err), &err);
    assert_int_equal(cam, -1);
    cg_scene_free(&s);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(cornell_point_lands_on_pixel),
             cmocka_unit_test(orthographic_and_scaled_cameras),
             cmocka_unit_test(framed_view_sees_the_bounds),
             cmocka_unit_test(camera_selection),
             cmocka_unit_test(own_aspect_ratio_is_fitted_not_stretched),
             cmocka_unit_test(view_spec_moves_aims_and_zooms))
