#include "pass_fixtures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "sdk/builtin.h"
#include "cg/graphfile.h"
#include "test_support.h"

void
fx_scene_init(fx_scene *s)
{
    memset(s, 0, sizeof *s);
    snprintf(s->scene.name, sizeof s->scene.name, "test scene");
    s->scene.meshes = s->meshes;
    s->scene.instances = s->instances;
    s->scene.materials = s->materials;
    s->scene.lights = s->lights;
    s->scene.textures = s->textures;
    fx_add_material(s, 1.0f, 1.0f, 1.0f);
}

int
fx_add_material(fx_scene *s, float r, float g, float b)
{
    assert_true(s->scene.material_count < FX_MAX);
    cg_material *m = &s->materials[s->scene.material_count];
    cg_test_material_default(m, s->scene.material_count);
    m->base_color[0] = r;
    m->base_color[1] = g;
    m->base_color[2] = b;
    return s->scene.material_count++;
}

void
fx_add_quad(fx_scene *s, int axis, float at, float lo0, float hi0, float lo1, float hi1, int material)
{
    int i = s->scene.mesh_count;
    assert_true(i < FX_MAX);
    int a0 = (axis + 1) % 3, a1 = (axis + 2) % 3;
    const float corners[4][2] = { { lo0, lo1 }, { hi0, lo1 }, { hi0, hi1 }, { lo0, hi1 } };
    cg_mesh *m = &s->meshes[i];
    snprintf(m->name, sizeof m->name, "quad %d", i);
    for (int v = 0; v < 4; v++) {
        float *p = &s->positions[i][3 * v], *n = &s->normals[i][3 * v];
        p[axis] = at;
        p[a0] = corners[v][0];
        p[a1] = corners[v][1];
        n[0] = n[1] = n[2] = 0.0f;
        n[axis] = 1.0f;
        s->texcoords[i][2 * v] = (float)(v == 1 || v == 2);
        s->texcoords[i][2 * v + 1] = (float)(v >= 2);
    }
    /* (a0, a1, axis) is right-handed, so this winding is counter-clockwise seen from +axis. */
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    memcpy(s->indices[i], idx, sizeof idx);
    m->vertex_count = 4;
    m->index_count = 6;
    m->positions = s->positions[i];
    m->normals = s->normals[i];
    m->texcoords = s->texcoords[i];
    m->indices = s->indices[i];
    m->material = material;
    m->kind = CG_MESH_COMPLEX;
    for (int c = 0; c < 3; c++) {
        m->bounds_min[c] = fminf(fminf(m->positions[c], m->positions[3 + c]), m->positions[6 + c]);
        m->bounds_max[c] = fmaxf(fmaxf(m->positions[c], m->positions[3 + c]), m->positions[6 + c]);
    }
    cg_instance *inst = &s->instances[s->scene.instance_count++];
    inst->mesh = i;
    for (int k = 0; k < 16; k++)
        inst->world[k] = (k % 5 == 0) ? 1.0f : 0.0f;
    s->scene.mesh_count++;
}

cg_light *
fx_add_light(fx_scene *s, cg_light_type type, float intensity)
{
    assert_true(s->scene.light_count < FX_MAX);
    cg_light *l = &s->lights[s->scene.light_count++];
    memset(l, 0, sizeof *l);
    snprintf(l->name, sizeof l->name, "light %d", s->scene.light_count - 1);
    l->type = type;
    l->color[0] = l->color[1] = l->color[2] = 1.0f;
    l->intensity = intensity;
    l->direction[1] = -1.0f;
    return l;
}

void
fx_scene_finish(fx_scene *s)
{
    for (int c = 0; c < 3; c++) {
        s->scene.bounds_min[c] = INFINITY;
        s->scene.bounds_max[c] = -INFINITY;
    }
    /* Instances are identities here: world bounds are the meshes' own. */
    for (int i = 0; i < s->scene.mesh_count; i++)
        for (int c = 0; c < 3; c++) {
            s->scene.bounds_min[c] = fminf(s->scene.bounds_min[c], s->meshes[i].bounds_min[c]);
            s->scene.bounds_max[c] = fmaxf(s->scene.bounds_max[c], s->meshes[i].bounds_max[c]);
        }
}

void
fx_view_look_at(const float eye[3], const float target[3], const float up[3], float fovy_degrees,
                int width, int height, cg_view *out)
{
    memset(out, 0, sizeof *out);
    out->width = width;
    out->height = height;
    out->znear = 0.05f;
    out->zfar = 100.0f;
    mat4 view, proj, vp, inv;
    glm_lookat((float *)eye, (float *)target, (float *)up, view);
    glm_perspective(glm_rad(fovy_degrees), (float)width / (float)height, out->znear, out->zfar, proj);
    glm_mat4_mul(proj, view, vp);
    memcpy(out->view, view, sizeof view);
    memcpy(out->proj, proj, sizeof proj);
    memcpy(out->view_proj, vp, sizeof vp);
    glm_mat4_inv(view, inv);
    memcpy(out->inv_view, inv, sizeof inv);
    glm_mat4_inv(proj, inv);
    memcpy(out->inv_proj, inv, sizeof inv);
    glm_mat4_inv(vp, inv);
    memcpy(out->inv_view_proj, inv, sizeof inv);
    memcpy(out->position, eye, 3 * sizeof(float));
}

void
fx_pixel_of(const cg_view *view, const float p[3], int *x, int *y)
{
    /* cglm wants aligned matrices; cg_view's arrays are plain floats. */
    mat4 vp;
    memcpy(vp, view->view_proj, sizeof vp);
    vec4 clip;
    glm_mat4_mulv(vp, (vec4){ p[0], p[1], p[2], 1.0f }, clip);
    *x = (int)floorf((clip[0] / clip[3] * 0.5f + 0.5f) * (float)view->width);
    *y = (int)floorf((clip[1] / clip[3] * 0.5f + 0.5f) * (float)view->height);
    assert_in_range(*x, 0, view->width - 1);
    assert_in_range(*y, 0, view->height - 1);
}

void
fx_run(fx_runner *r, const fx_scene *s, const cg_view *view, const char *json, const fg_pass_type *extra)
{
    cg_error err = { 0 };
    memset(r, 0, sizeof *r);
    r->registry = fg_registry_create();
    assert_non_null(r->registry);
    assert_cg_ok(cg_builtin_passes_register(r->registry, &err), &err);
    if (extra)
        assert_cg_ok(fg_registry_add(r->registry, extra, &err), &err);
    assert_cg_ok(cg_gpu_scene_upload(&s->scene, &r->gpu, &err), &err);
    r->graph = fg_graph_create(r->registry);
    assert_non_null(r->graph);
    assert_cg_ok(fg_graph_load_string(r->graph, json, "test graph", &err), &err);
    r->frame.scene = &s->scene;
    r->frame.gpu_scene = &r->gpu;
    r->frame.view = *view;
    r->frame.width = view->width;
    r->frame.height = view->height;
    fg_compile_options options = { 0 };
    assert_cg_ok(fg_graph_compile(r->graph, &r->frame, &options, &err), &err);
    assert_cg_ok(fg_graph_prepare(r->graph, &err), &err);
    assert_cg_ok(fg_graph_execute(r->graph, &r->frame, FG_TIMING_SYNC, &err), &err);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void
fx_runner_free(fx_runner *r)
{
    fg_graph_destroy(r->graph);
    cg_gpu_scene_destroy(&r->gpu);
    fg_registry_destroy(r->registry);
    memset(r, 0, sizeof *r);
}

float *
fx_read_depth(GLuint texture, int *w, int *h)
{
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, w);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, h);
    size_t count = (size_t)*w * (size_t)*h;
    float *data = malloc(count * sizeof *data);
    assert_non_null(data);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(count * sizeof *data), data);
    return data;
}
