/* Scenes, views and statistics for the path tracer's tests (see path_trace_fixture.h). */
#include "path_trace_fixture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

void *
ptf_grow(void *array, int count, size_t elem)
{
    void *p = realloc(array, (size_t)(count + 1) * elem);
    assert_non_null(p);
    memset((char *)p + (size_t)count * elem, 0, elem);
    return p;
}

int
ptf_add_material(cg_scene *s, float r, float g, float b, float emission)
{
    s->materials = ptf_grow(s->materials, s->material_count, sizeof *s->materials);
    cg_material *m = &s->materials[s->material_count];
    cg_test_material_default(m, s->material_count);
    m->base_color[0] = r, m->base_color[1] = g, m->base_color[2] = b;
    m->emissive[0] = m->emissive[1] = m->emissive[2] = emission;
    return s->material_count++;
}

void
ptf_scene_init(cg_scene *s)
{
    memset(s, 0, sizeof *s);
    strcpy(s->name, "test");
    ptf_add_material(s, 1.0f, 1.0f, 1.0f, 0.0f); /* the default white material at 0 */
}

/* The quad [-1,1]^2 in the xy plane facing +z, uv = (x+1)/2, (y+1)/2. */
int
ptf_add_quad_mesh(cg_scene *s, int material)
{
    static const float pos[] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    static const float nrm[] = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    static const float uv[] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    static const uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
    s->meshes = ptf_grow(s->meshes, s->mesh_count, sizeof *s->meshes);
    cg_mesh *m = &s->meshes[s->mesh_count];
    strcpy(m->name, "quad");
    m->vertex_count = 4;
    m->index_count = 6;
    m->positions = malloc(sizeof pos);
    m->normals = malloc(sizeof nrm);
    m->texcoords = malloc(sizeof uv);
    m->indices = malloc(sizeof idx);
    memcpy(m->positions, pos, sizeof pos);
    memcpy(m->normals, nrm, sizeof nrm);
    memcpy(m->texcoords, uv, sizeof uv);
    memcpy(m->indices, idx, sizeof idx);
    m->material = material;
    return s->mesh_count++;
}

void
ptf_add_instance(cg_scene *s, int mesh, mat4 world)
{
    s->instances = ptf_grow(s->instances, s->instance_count, sizeof *s->instances);
    s->instances[s->instance_count].mesh = mesh;
    memcpy(s->instances[s->instance_count].world, world, sizeof(float) * 16);
    s->instance_count++;
}

/* A quad of half extents (hx, hy) centred at (cx, cy, cz) in a plane z = cz, facing +z. */
void
ptf_add_quad_at(cg_scene *s, int material, float cx, float cy, float cz, float hx, float hy)
{
    mat4 m;
    glm_mat4_identity(m);
    glm_translate(m, (vec3){ cx, cy, cz });
    glm_scale(m, (vec3){ hx, hy, 1.0f });
    ptf_add_instance(s, ptf_add_quad_mesh(s, material), m);
}

cg_light *
ptf_add_light(cg_scene *s, cg_light_type type, float intensity)
{
    s->lights = ptf_grow(s->lights, s->light_count, sizeof *s->lights);
    cg_light *l = &s->lights[s->light_count++];
    l->type = type;
    l->intensity = intensity;
    l->color[0] = l->color[1] = l->color[2] = 1.0f;
    return l;
}

void
ptf_scene_release(cg_scene *s)
{
    for (int i = 0; i < s->mesh_count; i++) {
        free(s->meshes[i].positions);
        free(s->meshes[i].normals);
        free(s->meshes[i].texcoords);
        free(s->meshes[i].indices);
    }
    for (int i = 0; i < s->texture_count; i++)
        free(s->textures[i].rgba);
    free(s->meshes);
    free(s->instances);
    free(s->materials);
    free(s->textures);
    free(s->lights);
    memset(s, 0, sizeof *s);
}

void
ptf_view_finish(cg_view *v, mat4 view, mat4 proj)
{
    mat4 vp, inv;
    glm_mat4_mul(proj, view, vp);
    memcpy(v->view, view, sizeof v->view);
    memcpy(v->proj, proj, sizeof v->proj);
    memcpy(v->view_proj, vp, sizeof v->view_proj);
    glm_mat4_inv(view, inv);
    memcpy(v->inv_view, inv, sizeof v->inv_view);
    v->position[0] = inv[3][0], v->position[1] = inv[3][1], v->position[2] = inv[3][2];
    glm_mat4_inv(proj, inv);
    memcpy(v->inv_proj, inv, sizeof v->inv_proj);
    glm_mat4_inv(vp, inv);
    memcpy(v->inv_view_proj, inv, sizeof v->inv_view_proj);
}

/* Orthographic, from z = 5 looking down -z at the square [-1,1]^2: world x = NDC x, y = NDC y. */
cg_view
ptf_view_top_ortho(int w, int h)
{
    cg_view v = { .width = w, .height = h, .orthographic = true, .znear = 0.1f, .zfar = 10.0f };
    mat4 view, proj;
    glm_lookat((vec3){ 0, 0, 5 }, (vec3){ 0, 0, 0 }, (vec3){ 0, 1, 0 }, view);
    glm_ortho(-1, 1, -1, 1, 0.1f, 10.0f, proj);
    ptf_view_finish(&v, view, proj);
    return v;
}

cg_view
ptf_view_perspective(int w, int h, vec3 eye, vec3 at)
{
    cg_view v = { .width = w, .height = h, .znear = 0.01f, .zfar = 100.0f };
    mat4 view, proj;
    glm_lookat(eye, at, (vec3){ 0, 1, 0 }, view);
    glm_perspective(1.0f, (float)w / (float)h, 0.01f, 100.0f, proj);
    ptf_view_finish(&v, view, proj);
    return v;
}

/* World point on the plane z = 0 at the centre of pixel (x, y) of view_top_ortho. */
void
ptf_pixel_on_plane(int x, int y, int w, int h, double *px, double *py)
{
    *px = 2.0 * (x + 0.5) / w - 1.0;
    *py = 1.0 - 2.0 * (y + 0.5) / h;
}

float *
ptf_render(const cg_scene *scene, const cg_view *view, pt_settings st)
{
    float *img = malloc(sizeof(float) * 4 * (size_t)view->width * view->height);
    assert_non_null(img);
    pt_scene *pts;
    cg_error err = { 0 };
    assert_cg_ok(pt_scene_create(scene, &pts, &err), &err);
    assert_cg_ok(pt_render(pts, view, &st, img, NULL, &err), &err);
    pt_scene_destroy(pts);
    return img;
}

void
ptf_assert_rel(double got, double want, double tol, const char *what, int x, int y)
{
    double scale = fabs(want) > 1e-6 ? fabs(want) : 1.0;
    if (!(fabs(got - want) <= tol * scale))
        fail_msg("%s at pixel (%d,%d): got %.7g, expected %.7g", what, x, y, got, want);
}

/* Mean of the RGB channels of an image minus a per-pixel expectation (or 0), and the
 * standard error of that mean from the spread over pixels (each pixel has its own random
 * numbers, so pixels are independent). */
void
ptf_residual_mean(const float *img, const double *want, int n, double *mean, double *std_error)
{
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) {
        double r = 0.0;
        for (int c = 0; c < 3; c++)
            r += img[4 * i + c] - (want ? want[i] : 0.0);
        r /= 3.0;
        s += r;
        s2 += r * r;
    }
    *mean = s / n;
    double var = s2 / n - *mean * *mean;
    *std_error = sqrt(var > 0.0 ? var / n : 0.0);
}

/* Signed view factor from a point to the rectangle [0, X] x [0, Y] of a plane at height h
 * above it and parallel to its surface, the corner over the point (the differential area to
 * rectangle form factor, e.g. Howell's catalogue, case B-3); odd in X and Y, so rectangles
 * anywhere in the plane are sums of four corners. */
double
ptf_corner_view_factor(double x, double y, double h)
{
    double ax = sqrt(h * h + x * x), ay = sqrt(h * h + y * y);
    return (x / ax * atan(y / ax) + y / ay * atan(x / ay)) / (2.0 * PTF_PI);
}

pt_settings
ptf_settings(int spp, int bounces)
{
    pt_settings st = pt_settings_default();
    st.spp = spp;
    st.bounces = bounces;
    return st;
}

void
ptf_floor_scene(cg_scene *s, float albedo)
{
    ptf_scene_init(s);
    ptf_add_quad_at(s, ptf_add_material(s, albedo, albedo, albedo, 0.0f), 0, 0, 0, 10, 10);
}
