#include "vct_fixture.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/builtin.h"
#include "cg/fs.h"
#include "cg/graphfile.h"
#include "test_support.h"

void
vf_scene_init(vf_scene *s, float albedo, float emission)
{
    memset(s, 0, sizeof *s);
    snprintf(s->scene.name, sizeof s->scene.name, "vct test scene");
    for (int m = 0; m < 2; m++) {
        cg_material *mat = &s->materials[m];
        cg_test_material_default(mat, m);
        float a = m == 0 ? 1.0f : albedo;
        mat->base_color[0] = mat->base_color[1] = mat->base_color[2] = a;
        if (m == 1)
            mat->emissive[0] = mat->emissive[1] = mat->emissive[2] = emission;
    }
    s->scene.materials = s->materials;
    s->scene.material_count = 2;
    s->scene.lights = s->lights;
    s->scene.meshes = &s->mesh;
    s->scene.instances = &s->instance;
    s->mesh.positions = s->positions;
    s->mesh.normals = s->normals;
    s->mesh.texcoords = s->texcoords;
    s->mesh.indices = s->indices;
    s->mesh.material = 1;
    s->mesh.kind = CG_MESH_COMPLEX;
    snprintf(s->mesh.name, sizeof s->mesh.name, "triangles");
    s->instance.mesh = 0;
    for (int i = 0; i < 4; i++)
        s->instance.world[5 * i] = 1.0f;
}

void
vf_add_triangle(vf_scene *s, const double a[3], const double b[3], const double c[3])
{
    assert_true(s->mesh.index_count < VF_MAX_TRIANGLES * 3);
    const double *v[3] = {a, b, c};
    uint32_t base = s->mesh.vertex_count;
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++)
            s->positions[3 * (base + i) + k] = (float)v[i][k];
        s->indices[s->mesh.index_count++] = base + (uint32_t)i;
    }
    s->mesh.vertex_count += 3;
}

void
vf_finish(vf_scene *s)
{
    for (uint32_t t = 0; t < s->mesh.vertex_count; t += 3) {
        float *p = &s->positions[3 * t];
        float e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++)
            e1[k] = p[3 + k] - p[k], e2[k] = p[6 + k] - p[k];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                s->normals[3 * (t + i) + k] = len > 0 ? n[k] / len : (k == 1);
    }
    for (int k = 0; k < 3; k++) {
        s->mesh.bounds_min[k] = INFINITY;
        s->mesh.bounds_max[k] = -INFINITY;
        for (uint32_t v = 0; v < s->mesh.vertex_count; v++) {
            s->mesh.bounds_min[k] = fminf(s->mesh.bounds_min[k], s->positions[3 * v + k]);
            s->mesh.bounds_max[k] = fmaxf(s->mesh.bounds_max[k], s->positions[3 * v + k]);
        }
        /* An empty scene has empty bounds at the origin (what a camera can be framed from). */
        s->scene.bounds_min[k] = s->mesh.vertex_count ? s->mesh.bounds_min[k] : 0.0f;
        s->scene.bounds_max[k] = s->mesh.vertex_count ? s->mesh.bounds_max[k] : 0.0f;
    }
    s->scene.mesh_count = s->mesh.index_count > 0 ? 1 : 0;
    s->scene.instance_count = s->scene.mesh_count;
}

void
vf_start(vf_runner *r, const cg_scene *scene, int width, int height, const char *json,
         const char *const *overrides)
{
    cg_error err = {0};
    memset(r, 0, sizeof *r);
    r->registry = fg_registry_create();
    assert_non_null(r->registry);
    assert_cg_ok(cg_builtin_passes_register(r->registry, &err), &err);
    assert_cg_ok(cg_gpu_scene_upload(scene, &r->gpu, &err), &err);
    r->uploaded = true;
    r->graph = fg_graph_create(r->registry);
    assert_non_null(r->graph);
    assert_cg_ok(fg_graph_load_string(r->graph, json, "test graph", &err), &err);
    for (int i = 0; overrides && overrides[i]; i++)
        assert_cg_ok(fg_graph_apply_override(r->graph, overrides[i], &err), &err);
    r->frame.scene = scene;
    r->frame.gpu_scene = &r->gpu;
    int camera = scene->camera_count > 0 ? 0 : -1;
    cg_view_from_scene(scene, camera, width, height, &r->frame.view);
    r->frame.width = width;
    r->frame.height = height;
    fg_compile_options options = {0};
    assert_cg_ok(fg_graph_compile(r->graph, &r->frame, &options, &err), &err);
    assert_cg_ok(fg_graph_prepare(r->graph, &err), &err);
}

void
vf_start_file(vf_runner *r, const cg_scene *scene, int width, int height, const char *graph,
              const char *const *overrides)
{
    char *json = NULL;
    size_t size = 0;
    cg_error err = {0};
    assert_cg_ok(cg_read_file(cg_test_graph_path(graph), &json, &size, &err), &err);
    vf_start(r, scene, width, height, json, overrides);
    free(json);
}

void
vf_run_format(vf_runner *r, const cg_scene *scene, int width, int height, const char *format, ...)
{
    char json[8192];
    va_list args;
    va_start(args, format);
    int length = vsnprintf(json, sizeof json, format, args);
    va_end(args);
    if (length < 0 || (size_t)length >= sizeof json)
        fail_msg("a graph of %d bytes: more than vf_run_format holds", length);
    vf_start(r, scene, width, height, json, NULL);
    vf_frame(r);
}

void
vf_frame(vf_runner *r)
{
    cg_error err = {0};
    if (r->uploaded)
        cg_gpu_scene_destroy(&r->gpu);
    assert_cg_ok(cg_gpu_scene_upload(r->frame.scene, &r->gpu, &err), &err);
    r->uploaded = true;
    assert_cg_ok(fg_graph_execute(r->graph, &r->frame, FG_TIMING_SYNC, &err), &err);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    r->frame.index++;
}

void
vf_next_frame(vf_runner *r)
{
    cg_error err = {0};
    assert_cg_ok(fg_graph_execute(r->graph, &r->frame, FG_TIMING_NONE, &err), &err);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    r->frame.index++;
}

void
vf_stop(vf_runner *r)
{
    fg_graph_destroy(r->graph);
    if (r->uploaded)
        cg_gpu_scene_destroy(&r->gpu);
    fg_registry_destroy(r->registry);
    memset(r, 0, sizeof *r);
}

const char *
vf_rebuilt(const vf_runner *r, const char *pass)
{
    const fg_pass *p = fg_graph_find_pass(r->graph, pass);
    if (!p)
        fail_msg("the graph has no pass %s", pass);
    return fg_pass_rebuilt(p);
}

double
vf_reads(const vf_runner *r, const char *pass, const char *item, double *items)
{
    double reads = -1.0;
    const char *counted = NULL;
    assert_true(fg_pass_reads(fg_graph_find_pass(r->graph, pass), &reads, items, &counted));
    assert_string_equal(counted, item);
    return reads;
}

float *
vf_read_image(const vf_runner *r, const char *source, int width, int height)
{
    GLuint tex = fg_graph_texture(r->graph, source);
    if (tex == 0)
        fail_msg("no output %s", source);
    int w = 0, h = 0, d = 0;
    float *data = cg_test_read_texture(tex, 0, &w, &h, &d);
    assert_non_null(data);
    assert_int_equal(w, width);
    assert_int_equal(h, height);
    return data;
}

float *
vf_read_volume(const vf_runner *r, const char *source, int level, int *size)
{
    GLuint tex = fg_graph_texture(r->graph, source);
    assert_true(tex != 0);
    int w = 0, h = 0, d = 0;
    float *data = cg_test_read_texture(tex, level, &w, &h, &d);
    assert_non_null(data);
    assert_int_equal(w, h);
    assert_int_equal(w, d);
    *size = w;
    return data;
}
