#include "hybrid_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

void
hf_init(hf_scene *s)
{
    memset(s, 0, sizeof *s);
    snprintf(s->scene.name, sizeof s->scene.name, "hybrid test scene");
    for (int m = 0; m < 4; m++)
        cg_test_material_default(&s->materials[m], m);
    s->scene.materials = s->materials;
    s->scene.material_count = 4;
    s->scene.meshes = s->meshes;
    s->scene.instances = s->instances;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 4; k++)
            s->instances[i].world[5 * k] = 1.0f;
}

void
hf_material(hf_scene *s, int m, float albedo, float emission)
{
    cg_material *mat = &s->materials[m];
    mat->base_color[0] = mat->base_color[1] = mat->base_color[2] = albedo;
    mat->emissive[0] = mat->emissive[1] = mat->emissive[2] = emission;
}

static cg_mesh *
add_mesh(hf_scene *s, int slot, const char *name, uint32_t vertices, uint32_t indices)
{
    cg_mesh *mesh = &s->meshes[slot];
    memset(mesh, 0, sizeof *mesh);
    snprintf(mesh->name, sizeof mesh->name, "%s", name);
    mesh->vertex_count = vertices;
    mesh->index_count = indices;
    mesh->positions = calloc((size_t)vertices * 3, sizeof(float));
    mesh->normals = calloc((size_t)vertices * 3, sizeof(float));
    mesh->texcoords = calloc((size_t)vertices * 2, sizeof(float));
    mesh->indices = calloc(indices, sizeof(uint32_t));
    assert_true(mesh->positions && mesh->normals && mesh->texcoords && mesh->indices);
    return mesh;
}

void
hf_grid(hf_scene *s, int n, double x0, double z0, double size, hf_height_fn height, const void *user)
{
    uint32_t w = (uint32_t)n + 1;
    cg_mesh *mesh = add_mesh(s, 0, "terrain", w * w, (uint32_t)n * n * 6);
    mesh->kind = CG_MESH_HEIGHTFIELD;
    mesh->material = 1;
    double step = size / n, e = 1e-3 * step;
    for (uint32_t j = 0; j < w; j++)
        for (uint32_t i = 0; i < w; i++) {
            uint32_t v = j * w + i;
            double x = x0 + i * step, z = z0 + j * step;
            mesh->positions[3 * v + 0] = (float)x;
            mesh->positions[3 * v + 1] = (float)height(x, z, user);
            mesh->positions[3 * v + 2] = (float)z;
            double sx = (height(x + e, z, user) - height(x - e, z, user)) / (2 * e);
            double sz = (height(x, z + e, user) - height(x, z - e, user)) / (2 * e);
            double len = sqrt(sx * sx + 1 + sz * sz);
            mesh->normals[3 * v + 0] = (float)(-sx / len);
            mesh->normals[3 * v + 1] = (float)(1 / len);
            mesh->normals[3 * v + 2] = (float)(-sz / len);
            mesh->texcoords[2 * v] = (float)i / n;
            mesh->texcoords[2 * v + 1] = (float)j / n;
        }
    uint32_t k = 0;
    for (uint32_t j = 0; j < (uint32_t)n; j++)
        for (uint32_t i = 0; i < (uint32_t)n; i++) {
            uint32_t v00 = j * w + i, v10 = v00 + 1, v01 = v00 + w, v11 = v01 + 1;
            mesh->indices[k++] = v00, mesh->indices[k++] = v01, mesh->indices[k++] = v10;
            mesh->indices[k++] = v10, mesh->indices[k++] = v01, mesh->indices[k++] = v11;
        }
}

void
hf_quad(hf_scene *s, const double corner[3], const double e1[3], const double e2[3])
{
    int slot = s->meshes[1].index_count == 0 ? 1 : 2;
    assert_int_equal(s->meshes[slot].index_count, 0);
    cg_mesh *mesh = add_mesh(s, slot, "quad", 4, 6);
    mesh->kind = CG_MESH_COMPLEX;
    mesh->material = slot + 1;
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int v = 0; v < 4; v++)
        for (int k = 0; k < 3; k++) {
            mesh->positions[3 * v + k] =
                (float)(corner[k] + ((v == 1 || v == 2) ? e1[k] : 0) + ((v == 2 || v == 3) ? e2[k] : 0));
            mesh->normals[3 * v + k] = (float)(n[k] / len);
        }
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    memcpy(mesh->indices, idx, sizeof idx);
}

void
hf_sun(hf_scene *s, const double direction[3], float irradiance)
{
    cg_light *l = &s->light;
    memset(l, 0, sizeof *l);
    snprintf(l->name, sizeof l->name, "sun");
    l->type = CG_LIGHT_DIRECTIONAL;
    l->color[0] = l->color[1] = l->color[2] = 1.0f;
    l->intensity = irradiance;
    double len = sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    for (int k = 0; k < 3; k++)
        l->direction[k] = (float)(direction[k] / len);
    s->scene.lights = &s->light;
    s->scene.light_count = 1;
}

static void
normalise(double v[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

void
hf_camera_looking(hf_scene *s, const double eye[3], const double forward[3], const double up[3], float yfov)
{
    double z[3] = {-forward[0], -forward[1], -forward[2]};
    normalise(z);
    double x[3] = {up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]};
    normalise(x);
    double y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
    cg_camera *c = &s->camera;
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "test camera");
    c->type = CG_CAMERA_PERSPECTIVE;
    c->yfov = yfov;
    c->znear = 0.01f;
    c->zfar = 1000.0f;
    for (int k = 0; k < 3; k++) {
        c->world[k] = (float)x[k];
        c->world[4 + k] = (float)y[k];
        c->world[8 + k] = (float)z[k];
        c->world[12 + k] = (float)eye[k];
    }
    c->world[15] = 1.0f;
    s->scene.cameras = &s->camera;
    s->scene.camera_count = 1;
}

static double
town_terrain(double x, double z, const void *user)
{
    (void)user;
    return 0.3 * sin(1.3 * x) * cos(0.9 * z) + 0.05 * x;
}

void
hf_plate_under_sun(hf_scene *s, float irradiance, float angular_diameter)
{
    hf_init(s);
    hf_material(s, 1, 0.5f, 0.0f);
    hf_material(s, 2, 0.5f, 0.0f);
    hf_grid(s, 8, -50.0, -50.0, 100.0, hf_flat, NULL);
    const double corner[3] = {-40, 10, 40}, e1[3] = {40, 0, 0}, e2[3] = {0, 0, -80};
    hf_quad(s, corner, e1, e2);
    const double down[3] = {0.05, -1, 0.02};
    hf_sun(s, down, irradiance);
    s->light.angular_diameter = angular_diameter;
}

void
hf_town(hf_scene *s, int n, float wall_emission)
{
    hf_init(s);
    hf_material(s, 1, 0.4f, 0.0f);
    hf_material(s, 2, 0.8f, wall_emission);
    hf_material(s, 3, 0.6f, 0.0f);
    hf_grid(s, n, -3.9, -3.9, 7.8, town_terrain, NULL);
    const double wall[3] = {-1.0, -0.6, 0.2}, wall_e1[3] = {1.3, 0.0, 0.4}, wall_e2[3] = {0.0, 1.7, 0.0};
    hf_quad(s, wall, wall_e1, wall_e2);
    const double roof[3] = {1.5, 1.8, -2.5}, roof_e1[3] = {1.5, 0.3, 0.0}, roof_e2[3] = {0.0, 0.2, 1.2};
    hf_quad(s, roof, roof_e1, roof_e2);
}

void
hf_finish(hf_scene *s)
{
    /* The mesh slots in use must be contiguous from 0: without a terrain, the quads move down. */
    if (s->meshes[0].index_count == 0) {
        s->meshes[0] = s->meshes[1];
        s->meshes[1] = s->meshes[2];
        memset(&s->meshes[2], 0, sizeof s->meshes[2]);
    }
    int count = 0;
    while (count < 3 && s->meshes[count].index_count > 0)
        count++;
    for (int m = 0; m < count; m++) {
        cg_mesh *mesh = &s->meshes[m];
        for (int k = 0; k < 3; k++) {
            mesh->bounds_min[k] = INFINITY;
            mesh->bounds_max[k] = -INFINITY;
            for (uint32_t v = 0; v < mesh->vertex_count; v++) {
                mesh->bounds_min[k] = fminf(mesh->bounds_min[k], mesh->positions[3 * v + k]);
                mesh->bounds_max[k] = fmaxf(mesh->bounds_max[k], mesh->positions[3 * v + k]);
            }
        }
        s->instances[m].mesh = m;
    }
    s->scene.mesh_count = count;
    s->scene.instance_count = count;
    cg_scene_compute_bounds(&s->scene);
}

void
hf_free(hf_scene *s)
{
    for (int m = 0; m < 3; m++) {
        free(s->meshes[m].positions);
        free(s->meshes[m].normals);
        free(s->meshes[m].texcoords);
        free(s->meshes[m].indices);
    }
    memset(s, 0, sizeof *s);
}

void
hf_turn_sun(vf_runner *r, hf_scene *s, double degrees)
{
    double a = degrees * M_PI / 180.0, c = cos(a), sn = sin(a);
    float *d = s->light.direction;
    float x = d[0], z = d[2];
    d[0] = (float)(c * x + sn * z);
    d[2] = (float)(-sn * x + c * z);
    cg_scene_lights_changed(&s->scene);
    cg_error err = {0};
    assert_cg_ok(cg_gpu_scene_update_lights(&r->gpu, &err), &err);
}

float *
hf_read_2d(const vf_runner *r, const char *source, int level, int *w, int *h)
{
    GLuint tex = fg_graph_texture(r->graph, source);
    assert_true(tex != 0);
    int d = 0;
    float *data = cg_test_read_texture(tex, level, w, h, &d);
    assert_non_null(data);
    return data;
}

float *
hf_read_2d_sized(const vf_runner *r, const char *source, int width, int height)
{
    int w = 0, h = 0;
    float *data = hf_read_2d(r, source, 0, &w, &h);
    assert_int_equal(w, width);
    assert_int_equal(h, height);
    return data;
}

double
hf_flat(double x, double z, const void *user)
{
    (void)x, (void)z, (void)user;
    return 0.0;
}
