/* glTF loading: good scenes written here (a triangle with and without 8/16/32-bit indices,
 * strips and fans, a node hierarchy, lights and cameras, materials and textures, a .glb,
 * height-field classification) and the malformed corpus of tests/data/gltf/malformed,
 * where each defect gives its named error, a message naming the file, and no crash. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cg/camera.h"
#include "cg/fs.h"
#include "cg/image.h"
#include "cg/scene.h"
#include "test_support.h"

/* ------------------------------------------------------------------ writing test files */

typedef struct blob {
    unsigned char data[8192];
    size_t size;
} blob;

static size_t
blob_add(blob *b, const void *p, size_t n)
{
    while (b->size % 4)
        b->data[b->size++] = 0;
    size_t at = b->size;
    assert_true(at + n <= sizeof b->data);
    memcpy(b->data + at, p, n);
    b->size += n;
    return at;
}

static const char *
write_text(const char *name, const char *text)
{
    return cg_test_write_file(name, text, strlen(text));
}

/* A mesh file: positions, optional indices (component type 5121/5123/5125, 0 = none),
 * optional texture coordinates; `top` adds top-level members (each ending in ','),
 * `mesh_extra` members of the mesh (each starting with ','), `prim_extra` of the primitive,
 * `nodes` and `scene_nodes` replace the default one node holding mesh 0. */
typedef struct mesh_file {
    const float *positions;
    int vertex_count;
    const uint32_t *indices;
    int index_count;
    int index_type;
    int mode;
    const float *texcoords;
    const char *top, *mesh_extra, *prim_extra, *nodes, *scene_nodes;
} mesh_file;

static const char *
write_mesh_file(const char *name, const mesh_file *m)
{
    blob b = { .size = 0 };
    char views[1024], accessors[1024], attributes[256], bin_name[256], file[256];
    size_t pos_at = blob_add(&b, m->positions, 12 * (size_t)m->vertex_count);
    snprintf(views, sizeof views, "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%d}", pos_at,
             12 * m->vertex_count);
    /* glTF asks POSITION for exact bounds (as float). */
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], m->positions[3 * v + k]);
            hi[k] = fmaxf(hi[k], m->positions[3 * v + k]);
        }
    snprintf(accessors, sizeof accessors,
             "{\"bufferView\":0,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\","
             "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]}",
             m->vertex_count, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    snprintf(attributes, sizeof attributes, "\"POSITION\":0");
    int next = 1;
    char indices[64] = "";
    if (m->index_type) {
        size_t size = m->index_type == 5121 ? 1 : m->index_type == 5123 ? 2 : 4;
        unsigned char raw[1024];
        for (int i = 0; i < m->index_count; i++) {
            uint32_t v = m->indices[i];
            memcpy(raw + i * size, &v, size); /* little-endian machine: the low bytes */
        }
        size_t at = blob_add(&b, raw, size * (size_t)m->index_count);
        snprintf(views + strlen(views), sizeof views - strlen(views),
                 ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", at, size * (size_t)m->index_count);
        snprintf(accessors + strlen(accessors), sizeof accessors - strlen(accessors),
                 ",{\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"SCALAR\"}", next,
                 m->index_type, m->index_count);
        snprintf(indices, sizeof indices, ",\"indices\":%d", next);
        next++;
    }
    if (m->texcoords) {
        size_t at = blob_add(&b, m->texcoords, 8 * (size_t)m->vertex_count);
        snprintf(views + strlen(views), sizeof views - strlen(views),
                 ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%d}", at, 8 * m->vertex_count);
        snprintf(accessors + strlen(accessors), sizeof accessors - strlen(accessors),
                 ",{\"bufferView\":%d,\"componentType\":5126,\"count\":%d,\"type\":\"VEC2\"}", next,
                 m->vertex_count);
        snprintf(attributes + strlen(attributes), sizeof attributes - strlen(attributes),
                 ",\"TEXCOORD_0\":%d", next);
        next++;
    }
    snprintf(bin_name, sizeof bin_name, "%s.bin", name);
    cg_test_write_file(bin_name, b.data, b.size);
    static char json[16384];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},%s"
             "\"buffers\":[{\"uri\":\"%s\",\"byteLength\":%zu}],"
             "\"bufferViews\":[%s],\"accessors\":[%s],"
             "\"meshes\":[{\"name\":\"roof\"%s,\"primitives\":[{\"attributes\":{%s}%s,\"mode\":%d%s}]}],"
             "\"nodes\":%s,\"scenes\":[{\"nodes\":%s}],\"scene\":0}",
             m->top ? m->top : "", bin_name, b.size, views, accessors, m->mesh_extra ? m->mesh_extra : "",
             attributes, indices, m->mode, m->prim_extra ? m->prim_extra : "",
             m->nodes ? m->nodes : "[{\"mesh\":0}]", m->scene_nodes ? m->scene_nodes : "[0]");
    snprintf(file, sizeof file, "%s.gltf", name);
    return write_text(file, json);
}

static const float triangle[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };

static void
load_ok(const char *path, cg_scene *s)
{
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(path, s, &err), &err);
}

static void
transform(const float m[16], const double p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* ------------------------------------------------------------------ good scenes */

static void
triangle_with_and_without_indices(void **state)
{
    (void)state;
    cg_scene s;
    mesh_file m = { .positions = triangle, .vertex_count = 3, .mode = 4 };
    load_ok(write_mesh_file("plain", &m), &s);
    assert_int_equal(cg_scene_triangle_count(&s), 1);
    assert_int_equal(s.mesh_count, 1);
    const cg_mesh *mesh = &s.meshes[0];
    assert_string_equal(mesh->name, "roof");
    assert_int_equal(mesh->vertex_count, 3);
    for (int i = 0; i < 3; i++)
        assert_int_equal(mesh->indices[i], i);
    /* Generated normals: the counter-clockwise triangle in the xy plane faces +z. */
    for (int v = 0; v < 3; v++) {
        assert_float_equal(mesh->normals[3 * v + 2], 1, 1e-6);
        assert_float_equal(mesh->normals[3 * v + 0], 0, 1e-6);
    }
    assert_null(mesh->texcoords);
    assert_int_equal(mesh->material, 0);
    assert_int_equal(s.material_count, 1);
    assert_int_equal(mesh->kind, CG_MESH_COMPLEX);
    assert_float_equal(s.bounds_max[0], 1, 0);
    assert_float_equal(s.bounds_max[1], 1, 0);
    assert_float_equal(s.bounds_min[2], 0, 0);
    cg_scene_free(&s);

    const int types[3] = { 5121, 5123, 5125 };
    const uint32_t reversed[3] = { 2, 1, 0 };
    for (int t = 0; t < 3; t++) {
        mesh_file mi = { .positions = triangle, .vertex_count = 3, .mode = 4, .indices = reversed,
                         .index_count = 3, .index_type = types[t] };
        char name[32];
        snprintf(name, sizeof name, "indexed%d", types[t]);
        load_ok(write_mesh_file(name, &mi), &s);
        assert_int_equal(cg_scene_triangle_count(&s), 1);
        for (int i = 0; i < 3; i++)
            assert_int_equal(s.meshes[0].indices[i], reversed[i]);
        /* Wound the other way round: the generated normal flips. */
        assert_float_equal(s.meshes[0].normals[2], -1, 1e-6);
        cg_scene_free(&s);
    }
}

static void
strips_and_fans(void **state)
{
    (void)state;
    static const float five[15] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0 };
    cg_scene s;
    mesh_file strip = { .positions = five, .vertex_count = 4, .mode = 5 };
    load_ok(write_mesh_file("strip", &strip), &s);
    /* glTF 3.7.2.1: strip triangle i = (i, i+1+i%2, i+2-i%2). */
    const uint32_t strip_expected[6] = { 0, 1, 2, 1, 3, 2 };
    assert_int_equal(s.meshes[0].index_count, 6);
    for (int i = 0; i < 6; i++)
        assert_int_equal(s.meshes[0].indices[i], strip_expected[i]);
    cg_scene_free(&s);

    const uint32_t seq[5] = { 4, 3, 2, 1, 0 };
    mesh_file fan = { .positions = five, .vertex_count = 5, .mode = 6, .indices = seq, .index_count = 5,
                      .index_type = 5123 };
    load_ok(write_mesh_file("fan", &fan), &s);
    /* Fan triangle i = (i+1, i+2, 0) over the index sequence. */
    const uint32_t fan_expected[9] = { 3, 2, 4, 2, 1, 4, 1, 0, 4 };
    assert_int_equal(s.meshes[0].index_count, 9);
    for (int i = 0; i < 9; i++)
        assert_int_equal(s.meshes[0].indices[i], fan_expected[i]);
    cg_scene_free(&s);
}

static void
points_and_lines_are_skipped(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    mesh_file m = { .positions = triangle, .vertex_count = 3, .mode = 4,
                    .mesh_extra = "" };
    const char *path = write_mesh_file("lines", &m);
    /* Add a second primitive drawing lines over the same accessor. */
    char *json;
    size_t size;
    assert_cg_ok(cg_read_file(path, &json, &size, &err), &err);
    char *p = strstr(json, "\"mode\":4}");
    assert_non_null(p);
    char edited[16384];
    snprintf(edited, sizeof edited, "%.*s\"mode\":4},{\"attributes\":{\"POSITION\":0},\"mode\":1}%s",
             (int)(p - json), json, p + strlen("\"mode\":4}"));
    free(json);
    load_ok(write_text("lines.gltf", edited), &s);
    assert_int_equal(s.mesh_count, 1);
    assert_int_equal(cg_scene_triangle_count(&s), 1);
    cg_scene_free(&s);
    /* Only points: no triangles at all. */
    mesh_file pts = { .positions = triangle, .vertex_count = 3, .mode = 0 };
    assert_cg_status(cg_scene_load(write_mesh_file("points", &pts), &s, &err), &err, CG_ERR_GLTF_NO_TRIANGLES);
    assert_non_null(strstr(err.message, "points.gltf"));
}

static void
node_hierarchy(void **state)
{
    (void)state;
    cg_scene s;
    mesh_file m = {
        .positions = triangle, .vertex_count = 3, .mode = 4,
        .nodes = "[{\"translation\":[10,0,0],\"scale\":[2,2,2],\"children\":[1]},"
                 "{\"rotation\":[0,0.70710678,0,0.70710678],\"translation\":[0,1,0],\"children\":[2]},"
                 "{\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,3,1],\"mesh\":0},"
                 "{\"mesh\":0,\"translation\":[0,-5,0]}]",
        .scene_nodes = "[0,3]",
    };
    load_ok(write_mesh_file("hierarchy", &m), &s);
    assert_int_equal(s.mesh_count, 1);
    assert_int_equal(s.instance_count, 2);
    assert_int_equal(cg_scene_triangle_count(&s), 2);
    /* (1,0,0): +3 z by the matrix, 90 degrees about y, +1 y, scale 2, +10 x. */
    double p[3] = { 1, 0, 0 }, w[3];
    transform(s.instances[0].world, p, w);
    assert_float_equal(w[0], 16, 1e-5);
    assert_float_equal(w[1], 2, 1e-5);
    assert_float_equal(w[2], -2, 1e-5);
    transform(s.instances[1].world, p, w);
    assert_float_equal(w[0], 1, 1e-6);
    assert_float_equal(w[1], -5, 1e-6);
    /* World bounds cover both instances. */
    assert_float_equal(s.bounds_min[1], -5, 1e-5);
    assert_float_equal(s.bounds_max[0], 16, 1e-4);
    cg_scene_free(&s);
}

static const cg_light *
light_of_type(const cg_scene *s, cg_light_type t)
{
    for (int i = 0; i < s->light_count; i++)
        if (s->lights[i].type == t)
            return &s->lights[i];
    fail_msg("no light of type %d", t);
    return NULL;
}

static void
lights_and_cameras(void **state)
{
    (void)state;
    cg_scene s;
    mesh_file m = {
        .positions = triangle, .vertex_count = 3, .mode = 4,
        .top = "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensionsRequired\":[\"KHR_lights_punctual\"],"
               "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
               "{\"type\":\"directional\",\"intensity\":3,\"color\":[1,0.5,0.25],\"name\":\"sun\"},"
               "{\"type\":\"spot\",\"intensity\":20,\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.6}},"
               "{\"type\":\"point\",\"intensity\":5,\"range\":10}]}},"
               "\"cameras\":[{\"type\":\"perspective\",\"name\":\"main\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}},"
               "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":2,\"ymag\":1,\"znear\":0.01,\"zfar\":100}}],",
        .nodes = "[{\"mesh\":0},"
                 "{\"rotation\":[-0.70710678,0,0,0.70710678],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
                 "{\"translation\":[1,2,3],\"children\":[3]},"
                 "{\"translation\":[0,1,0],\"rotation\":[-0.70710678,0,0,0.70710678],"
                 "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
                 "{\"translation\":[0,0,5],\"camera\":0},"
                 "{\"translation\":[0,0,-4],\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},"
                 "{\"translation\":[0,0,10],\"camera\":1}]",
        .scene_nodes = "[0,1,2,4,5,6]",
    };
    load_ok(write_mesh_file("lights", &m), &s);
    assert_int_equal(s.light_count, 3);
    const cg_light *sun = light_of_type(&s, CG_LIGHT_DIRECTIONAL);
    assert_string_equal(sun->name, "sun");
    assert_float_equal(sun->intensity, 3, 0);
    assert_float_equal(sun->color[1], 0.5, 0);
    /* Rotated -90 degrees about x: its -z points down. */
    assert_float_equal(sun->direction[0], 0, 1e-6);
    assert_float_equal(sun->direction[1], -1, 1e-6);
    assert_float_equal(sun->direction[2], 0, 1e-6);
    const cg_light *spot = light_of_type(&s, CG_LIGHT_SPOT);
    assert_float_equal(spot->position[0], 1, 1e-6);
    assert_float_equal(spot->position[1], 3, 1e-6);
    assert_float_equal(spot->position[2], 3, 1e-6);
    assert_float_equal(spot->direction[1], -1, 1e-6);
    assert_float_equal(spot->inner_cone_angle, 0.2, 1e-6);
    assert_float_equal(spot->outer_cone_angle, 0.6, 1e-6);
    assert_float_equal(spot->color[0], 1, 0); /* default colour */
    const cg_light *point = light_of_type(&s, CG_LIGHT_POINT);
    assert_float_equal(point->position[2], -4, 1e-6);
    assert_float_equal(point->range, 10, 0);

    assert_int_equal(s.camera_count, 2);
    int cam;
    cg_error err = { 0 };
    assert_cg_ok(cg_camera_select(&s, "main", &cam, &err), &err);
    const cg_camera *c = &s.cameras[cam];
    assert_int_equal(c->type, CG_CAMERA_PERSPECTIVE);
    assert_float_equal(c->yfov, 0.8, 1e-6);
    assert_float_equal(c->aspect, 0, 0);
    assert_float_equal(c->zfar, 0, 0); /* glTF: no zfar = infinite */
    assert_float_equal(c->world[14], 5, 0);
    /* The view: a point at depth 5 lands where yfov and the image aspect (2) put it. */
    cg_view v;
    cg_view_from_scene(&s, cam, 64, 32, &v);
    double t = tan(0.4), ndc[2] = { 0.5 / (5 * t * 2), 0.25 / (5 * t) };
    const float *vp = v.view_proj;
    double q[3] = { 0.5, 0.25, 0 }, clip[4];
    for (int r = 0; r < 4; r++)
        clip[r] = vp[r] * q[0] + vp[4 + r] * q[1] + vp[8 + r] * q[2] + vp[12 + r];
    assert_float_equal((clip[0] / clip[3] + 1) * 32, (ndc[0] + 1) * 32, 1e-3);
    assert_float_equal((clip[1] / clip[3] + 1) * 16, (ndc[1] + 1) * 16, 1e-3);
    assert_true(isfinite(v.zfar) && v.zfar >= 5);
    const cg_camera *o = &s.cameras[1 - cam];
    assert_int_equal(o->type, CG_CAMERA_ORTHOGRAPHIC);
    assert_float_equal(o->ymag, 1, 0);
    assert_float_equal(o->zfar, 100, 0);
    cg_scene_free(&s);
}

/* A 2x2 PNG: top row red, green; bottom row blue, white. */
static const char *
write_png(const char *name)
{
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_alloc(&img, 2, 2, &err), &err);
    const float px[4][4] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, 1, 1 }, { 1, 1, 1, 1 } };
    memcpy(img.rgba, px, sizeof px);
    const char *path = cg_test_tmp_path(name);
    assert_cg_ok(cg_image_write(path, &img, CG_EXR_FLOAT, &err), &err);
    cg_image_free(&img);
    return path;
}

static void
check_texture(const cg_texture *t)
{
    assert_int_equal(t->width, 2);
    assert_int_equal(t->height, 2);
    assert_true(t->srgb);
    /* Rows top to bottom as in the file: row 0 is the PNG's top row (red, green), where glTF's
     * v = 0 lies and GL's t = 0 samples. */
    const uint8_t expected[16] = { 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255 };
    assert_memory_equal(t->rgba, expected, 16);
}

static const char material_json[] =
    "\"extensionsUsed\":[\"KHR_materials_emissive_strength\"],"
    "\"materials\":[{\"name\":\"mat\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,1,1],"
    "\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0.3,\"roughnessFactor\":0.7},"
    "\"emissiveFactor\":[1,0.5,0],\"emissiveTexture\":{\"index\":0},"
    "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}}],"
    "\"textures\":[{\"source\":0}],";

static void
materials_and_textures(void **state)
{
    (void)state;
    write_png("tex.png");
    static const float uv[6] = { 0, 0, 1, 0, 0, 1 };
    char top[2048];
    snprintf(top, sizeof top, "%s\"images\":[{\"uri\":\"tex.png\"}],", material_json);
    mesh_file m = { .positions = triangle, .vertex_count = 3, .mode = 4, .texcoords = uv, .top = top,
                    .prim_extra = ",\"material\":0" };
    cg_scene s;
    load_ok(write_mesh_file("material", &m), &s);
    assert_int_equal(s.material_count, 2);
    assert_int_equal(s.meshes[0].material, 1);
    const cg_material *mat = &s.materials[1];
    assert_string_equal(mat->name, "mat");
    assert_float_equal(mat->base_color[1], 0.25, 0);
    assert_float_equal(mat->metallic, 0.3, 1e-6);
    assert_float_equal(mat->roughness, 0.7, 1e-6);
    assert_float_equal(mat->emissive[1], 0.5, 0);
    assert_float_equal(mat->emissive_strength, 4, 0);
    assert_int_equal(mat->base_color_texture, 0);
    assert_int_equal(mat->emissive_texture, 0);
    assert_int_equal(s.texture_count, 1);
    check_texture(&s.textures[0]);
    assert_non_null(s.meshes[0].texcoords);
    assert_float_equal(s.meshes[0].texcoords[5], 1, 0);
    /* Material 0 stays the default white. */
    assert_float_equal(s.materials[0].base_color[0], 1, 0);
    assert_float_equal(s.materials[0].emissive[0], 0, 0);

    /* Export keeps textures (PNG inside the file) and emitted radiance: an emissive factor
     * above 1 moves into the strength, since glTF keeps the factor in [0, 1]. */
    s.materials[1].emissive[0] = 3;
    s.materials[1].emissive[1] = 1.5f;
    const char *outs[2] = { "material_out.gltf", "material_out.glb" };
    for (int i = 0; i < 2; i++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", cg_test_tmpdir(), outs[i]);
        cg_error err = { 0 };
        assert_cg_ok(cg_scene_export_gltf(&s, path, &err), &err);
        cg_scene back;
        load_ok(path, &back);
        assert_int_equal(back.texture_count, 1);
        check_texture(&back.textures[0]);
        const cg_material *b = &back.materials[1];
        assert_float_equal(b->emissive[0] * b->emissive_strength, 3 * 4, 1e-5);
        assert_float_equal(b->emissive[1] * b->emissive_strength, 1.5 * 4, 1e-5);
        assert_true(b->emissive[0] <= 1);
        assert_int_equal(b->base_color_texture, 0);
        assert_int_equal(b->emissive_texture, 0);
        assert_float_equal(back.meshes[0].texcoords[5], 1, 0);
        cg_scene_free(&back);
    }
    cg_scene_free(&s);
}

/* A .glb: JSON chunk then BIN chunk holding the triangle, its indices and a PNG image. */
static const char *
write_glb(const char *name, bool image_past_end)
{
    cg_error err = { 0 };
    char *png;
    size_t png_size;
    assert_cg_ok(cg_read_file(write_png("glbtex.png"), &png, &png_size, &err), &err);
    blob b = { .size = 0 };
    size_t pos_at = blob_add(&b, triangle, sizeof triangle);
    uint16_t idx[3] = { 0, 1, 2 };
    size_t idx_at = blob_add(&b, idx, sizeof idx);
    static const float uv[6] = { 0, 0, 1, 0, 0, 1 };
    size_t uv_at = blob_add(&b, uv, sizeof uv);
    size_t png_at = blob_add(&b, png, png_size);
    free(png);
    while (b.size % 4)
        b.data[b.size++] = 0;
    char image_view[64];
    snprintf(image_view, sizeof image_view, "\"byteLength\":%zu", image_past_end ? (size_t)100000 : png_size);
    char json[4096];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":36},"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":6},{\"buffer\":0,\"byteOffset\":%zu,%s},"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":24}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
             "\"min\":[0,0,0],\"max\":[1,1,0]},"
             "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
             "{\"bufferView\":3,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}],"
             "\"images\":[{\"bufferView\":2,\"mimeType\":\"image/png\"}],\"textures\":[{\"source\":0}],"
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":2},\"indices\":1,\"material\":0}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
             b.size, pos_at, idx_at, png_at, image_view, uv_at);
    size_t json_len = strlen(json);
    while (json_len % 4)
        json[json_len++] = ' ';
    static unsigned char glb[16384];
    uint32_t total = (uint32_t)(12 + 8 + json_len + 8 + b.size);
    uint32_t header[3] = { 0x46546C67u, 2, total };
    uint32_t json_chunk[2] = { (uint32_t)json_len, 0x4E4F534Au };
    uint32_t bin_chunk[2] = { (uint32_t)b.size, 0x004E4942u };
    size_t at = 0;
    memcpy(glb + at, header, 12), at += 12;
    memcpy(glb + at, json_chunk, 8), at += 8;
    memcpy(glb + at, json, json_len), at += json_len;
    memcpy(glb + at, bin_chunk, 8), at += 8;
    memcpy(glb + at, b.data, b.size), at += b.size;
    return cg_test_write_file(name, glb, at);
}

static void
binary_gltf(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    load_ok(write_glb("scene.glb", false), &s);
    assert_int_equal(cg_scene_triangle_count(&s), 1);
    assert_int_equal(s.texture_count, 1);
    check_texture(&s.textures[0]);
    assert_int_equal(s.materials[s.meshes[0].material].base_color_texture, 0);
    cg_scene_free(&s);
    /* The image's bufferView runs past the BIN chunk: checked before decoding. */
    assert_cg_status(cg_scene_load(write_glb("badimage.glb", true), &s, &err), &err,
                     CG_ERR_GLTF_BUFFER);
    assert_non_null(strstr(err.message, "badimage.glb"));
    assert_non_null(strstr(err.message, "bufferViews[2]"));
}

static void
heightfield_classification(void **state)
{
    (void)state;
    /* A 2x2-cell grid on a slope, counter-clockwise seen from above: faces up. */
    static const float grid[27] = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0.5f, 1, 1, 0.5f, 1, 2, 0.5f, 1,
                                    0, 1, 2, 1, 1, 2, 2, 1, 2 };
    static const uint32_t cells[24] = { 0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5,
                                        3, 6, 4, 4, 6, 7, 4, 7, 5, 5, 7, 8 };
    const struct {
        const char *name, *nodes, *extra;
        cg_mesh_kind kind;
    } cases[] = {
        { "up", "[{\"mesh\":0}]", "", CG_MESH_HEIGHTFIELD },
        { "mirrored", "[{\"mesh\":0,\"scale\":[-1,1,1]}]", "", CG_MESH_HEIGHTFIELD },
        /* Eq. 5 is purely geometric: a sheet facing down is a height field (the normal rule,
         * tests/test_classify.c, says complex). */
        { "flipped", "[{\"mesh\":0,\"rotation\":[1,0,0,0]}]", "", CG_MESH_HEIGHTFIELD },
        { "one_flipped_instance", "[{\"mesh\":0},{\"mesh\":0,\"rotation\":[1,0,0,0]}]", "", CG_MESH_HEIGHTFIELD },
        { "standing", "[{\"mesh\":0,\"rotation\":[0,0,0.70710678,0.70710678]}]", "", CG_MESH_COMPLEX },
        { "tagged", "[{\"mesh\":0}]", ",\"extras\":{\"conegraph_kind\":\"complex\"}", CG_MESH_COMPLEX },
        { "tagged_flipped", "[{\"mesh\":0,\"rotation\":[1,0,0,0]}]",
          ",\"extras\":{\"conegraph_kind\":\"heightfield\"}", CG_MESH_HEIGHTFIELD },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        mesh_file m = { .positions = grid, .vertex_count = 9, .mode = 4, .indices = cells,
                        .index_count = 24, .index_type = 5123, .nodes = cases[i].nodes,
                        .mesh_extra = cases[i].extra,
                        .scene_nodes = strstr(cases[i].nodes, "},{") ? "[0,1]" : "[0]" };
        cg_scene s;
        load_ok(write_mesh_file(cases[i].name, &m), &s);
        if (s.meshes[0].kind != cases[i].kind)
            fail_msg("%s: kind %d, expected %d", cases[i].name, s.meshes[0].kind, cases[i].kind);
        cg_scene_free(&s);
    }
}


/* Sparse accessors (glTF 3.6.2.3): substitutions over a bufferView and over implicit zeros. */
static const char sparse_json[] =
    "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"sparse.bin\",\"byteLength\":80}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
    "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":1},{\"buffer\":0,\"byteOffset\":40,\"byteLength\":12},"
    "{\"buffer\":0,\"byteOffset\":52,\"byteLength\":4},{\"buffer\":0,\"byteOffset\":56,\"byteLength\":24}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
    "\"min\":[0,0,0],\"max\":[1,1,0],\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5121},\"values\":{\"bufferView\":2}}},"
    "{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0],"
    "\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":3,\"componentType\":5123},\"values\":{\"bufferView\":4}}}],"
    "\"meshes\":[{\"name\":\"over_view\",\"primitives\":[{\"attributes\":{\"POSITION\":0}}]},"
    "{\"name\":\"over_zeros\",\"primitives\":[{\"attributes\":{\"POSITION\":1}}]}],"
    "\"nodes\":[{\"mesh\":0},{\"mesh\":1}],\"scenes\":[{\"nodes\":[0,1]}]}";

static void
sparse_accessors(void **state)
{
    (void)state;
    unsigned char bin[80] = { 0 };
    float base[9] = { 0, 0, 0, 1, 0, 0, 5, 5, 5 }, one[3] = { 0, 1, 0 }, two[6] = { 1, 0, 0, 0, 1, 0 };
    uint16_t two_at[2] = { 1, 2 };
    memcpy(bin, base, 36);
    bin[36] = 2;
    memcpy(bin + 40, one, 12);
    memcpy(bin + 52, two_at, 4);
    memcpy(bin + 56, two, 24);
    cg_test_write_file("sparse.bin", bin, sizeof bin);
    cg_scene s;
    load_ok(write_text("sparse.gltf", sparse_json), &s);
    assert_int_equal(s.mesh_count, 2);
    for (int m = 0; m < 2; m++)
        assert_memory_equal(s.meshes[m].positions, triangle, sizeof triangle);
    cg_scene_free(&s);

    /* Broken sparse accessors are in the malformed corpus (tests/data/gltf/malformed). */
}

/* ------------------------------------------------------------------ the malformed corpus */

/* The base file: a triangle mesh 'roof' with 16-bit indices in base.bin (44 bytes). */
static const char base_json[] =
    "{\"asset\":{\"version\":\"2.0\"},"
    "\"buffers\":[{\"uri\":\"base.bin\",\"byteLength\":44}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
    "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
    "\"min\":[0,0,0],\"max\":[1,1,0]},"
    "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}],"
    "\"meshes\":[{\"name\":\"roof\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
    "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}";

static void
write_base_bin(const char *name, float poison, uint16_t last_index, size_t size)
{
    unsigned char bin[44] = { 0 };
    float pos[9];
    memcpy(pos, triangle, sizeof pos);
    pos[4] = poison;
    uint16_t idx[3] = { 0, 1, last_index };
    memcpy(bin, pos, 36);
    memcpy(bin + 36, idx, 6);
    cg_test_write_file(name, bin, size);
}

static void
good_base_loads(void **state)
{
    (void)state;
    write_base_bin("base.bin", 0, 2, 44);
    cg_scene s;
    load_ok(write_text("base.gltf", base_json), &s);
    assert_int_equal(cg_scene_triangle_count(&s), 1);
    cg_scene_free(&s);
}

/* The malformed corpus: files in tests/data/gltf/malformed, listed in its expected.txt with
 * the status each must give and a part of the message (test gltf_validator runs the Khronos
 * glTF-Validator over the same files). Every file must be refused with that status, a message
 * naming the file and that part, and an empty scene; all mismatches are listed before the
 * test fails. */
static void
malformed_corpus(void **state)
{
    (void)state;
    char dir[4096], manifest[4200];
    snprintf(dir, sizeof dir, "%s", cg_test_data_path("gltf/malformed"));
    snprintf(manifest, sizeof manifest, "%s/expected.txt", dir);
    FILE *fp = fopen(manifest, "r");
    assert_non_null(fp);
    char line[1024];
    int count = 0, wrong = 0;
    while (fgets(line, sizeof line, fp)) {
        line[strcspn(line, "\n")] = '\0';
        if (line[0] == '#' || line[0] == '\0')
            continue;
        char name[256], status[64];
        int used = 0;
        assert_int_equal(sscanf(line, "%255s %63s %n", name, status, &used), 2);
        const char *part = line + used;
        char path[4500];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        cg_scene s;
        cg_error err = { 0 };
        count++;
        if (cg_scene_load(path, &s, &err)) {
            printf("# %s loaded; expected %s\n", name, status);
            cg_scene_free(&s);
            wrong++;
            continue;
        }
        if (strcmp(cg_status_name(err.status), status) || !strstr(err.message, name) || !strstr(err.message, part)) {
            printf("# %s: %s (%s); expected %s naming the file and '%s'\n", name, cg_status_name(err.status),
                   err.message, status, part);
            wrong++;
            continue;
        }
        printf("# %s: %s\n", cg_status_name(err.status), strrchr(err.message, '/') + 1);
        assert_int_equal(s.mesh_count, 0);
        assert_null(s.meshes);
    }
    fclose(fp);
    printf("# %d malformed files refused as expected, %d not\n", count - wrong, wrong);
    assert_true(count >= 70);
    assert_int_equal(wrong, 0);
}

/* A URI naming a device is refused before it is read (/dev/zero would never end). Not in the
 * malformed corpus: the validator would read it for ever. tinygltf joins URIs to the file's
 * directory, so the device is reached upwards from there (".." at / stays at /). */
static void
buffer_from_a_device_is_refused(void **state)
{
    (void)state;
    const char *path = write_text("device.gltf", "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":"
                                                 "\"../../../../../../../../../../../../dev/zero\",\"byteLength\":4}]}");
    cg_error err = { 0 };
    cg_scene s;
    assert_cg_status(cg_scene_load(path, &s, &err), &err, CG_ERR_GLTF_BUFFER);
    assert_non_null(strstr(err.message, "device.gltf"));
    assert_non_null(strstr(err.message, "not a regular file"));
}

static void
missing_file(void **state)
{
    (void)state;
    cg_error err = { 0 };
    cg_scene s;
    char missing[4200];
    snprintf(missing, sizeof missing, "%s/nothing_here.gltf", cg_test_tmpdir());
    assert_cg_status(cg_scene_load(missing, &s, &err), &err, CG_ERR_FILE_NOT_FOUND);
    assert_non_null(strstr(err.message, "nothing_here.gltf"));
}

/* ------------------------------------------------------------------ materials (glTF 2.0 and
 * KHR_materials_*, KHR_texture_transform), tangents, a sun's angular diameter
 *
 * tests/data/gltf/materials/materials.gltf: five unit quads in the z = 0 plane facing +z, laid
 * out as an image (u right, v down: uv (0,1) at the origin, (1,0) at (1,1)); "generated" and
 * "from_file" use material "full" (every field read), "mirrored" the same with u mirrored,
 * "plain" material "unsupported" (features conegraph leaves out), "no_material" none; a sun
 * with conegraph_angular_diameter 0.0093. */

static const cg_mesh *
mesh_named(const cg_scene *s, const char *name)
{
    for (int i = 0; i < s->mesh_count; i++)
        if (!strcmp(s->meshes[i].name, name))
            return &s->meshes[i];
    fail_msg("no mesh '%s'", name);
    return NULL;
}

static const cg_material *
material_named(const cg_scene *s, const char *name)
{
    for (int i = 0; i < s->material_count; i++)
        if (!strcmp(s->materials[i].name, name))
            return &s->materials[i];
    fail_msg("no material '%s'", name);
    return NULL;
}

static void
check_uv(const cg_uv_transform *t, const double want[6], double tol)
{
    for (int k = 0; k < 6; k++)
        if (!(fabs(t->m[k] - want[k]) <= tol))
            fail_msg("uv transform m[%d] = %.9g, expected %.9g", k, t->m[k], want[k]);
}

/* glTF's defaults (spec 5.19 and the extensions' schemas): what "defaults" and the loader's
 * material 0 must be. */
static void
check_gltf_defaults(const cg_material *m)
{
    for (int k = 0; k < 4; k++)
        assert_true(m->base_color[k] == 1);
    assert_true(m->metallic == 1 && m->roughness == 1);
    assert_true(m->emissive[0] == 0 && m->emissive_strength == 1);
    assert_int_equal(m->base_color_texture, -1);
    assert_int_equal(m->emissive_texture, -1);
    assert_int_equal(m->metallic_roughness_texture, -1);
    assert_int_equal(m->normal_texture, -1);
    assert_int_equal(m->occlusion_texture, -1);
    assert_int_equal(m->transmission_texture, -1);
    assert_true(m->normal_scale == 1 && m->occlusion_strength == 1);
    assert_int_equal(m->alpha_mode, CG_ALPHA_OPAQUE);
    assert_true(m->alpha_cutoff == 0.5f);
    assert_false(m->double_sided);
    assert_true(m->ior == 1.5f && m->specular == 1);
    for (int k = 0; k < 3; k++)
        assert_true(m->specular_color[k] == 1 && m->attenuation_color[k] == 1);
    assert_true(m->transmission == 0 && m->thickness == 0);
    assert_true(isinf(m->attenuation_distance) && m->attenuation_distance > 0);
    static const double identity[6] = { 1, 0, 0, 1, 0, 0 };
    for (int t = 0; t < CG_TEX_COUNT; t++)
        check_uv(&m->uv[t], identity, 0);
}

static void
check_tangents(const cg_mesh *m, const float want[4])
{
    assert_non_null(m->tangents);
    for (uint32_t v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 4; k++)
            if (!(fabsf(m->tangents[4 * v + k] - want[k]) <= 1e-6f))
                fail_msg("mesh '%s' vertex %u tangent[%d] = %g, expected %g", m->name, v, k, m->tangents[4 * v + k],
                         want[k]);
}

/* Every field of "full" as the file gives it, with its textures' encodings. */
static void
check_full_material(const cg_scene *s)
{
    const cg_material *m = material_named(s, "full");
    const float base[4] = { 0.8f, 0.6f, 0.4f, 0.9f };
    for (int k = 0; k < 4; k++)
        assert_true(m->base_color[k] == base[k]);
    assert_true(m->metallic == 0.25f && m->roughness == 0.125f);
    assert_true(m->normal_scale == 0.5f && m->occlusion_strength == 0.25f);
    assert_int_equal(m->alpha_mode, CG_ALPHA_MASK);
    assert_true(m->alpha_cutoff == 0.3f);
    assert_true(m->double_sided);
    assert_true(m->emissive[1] * m->emissive_strength == 1.0f);
    assert_true(m->ior == 1.33f && m->specular == 0.5f);
    assert_true(m->specular_color[0] == 0.9f && m->specular_color[1] == 0.8f && m->specular_color[2] == 0.7f);
    assert_true(m->transmission == 0.75f && m->thickness == 0.1f && m->attenuation_distance == 2);
    assert_true(m->attenuation_color[0] == 0.5f && m->attenuation_color[1] == 0.6f && m->attenuation_color[2] == 0.7f);
    /* Base colour and emissive are sRGB; metallicRoughness, normal, occlusion and transmission
     * linear. glTF texture 0 serves base colour (sRGB) and metallicRoughness and transmission
     * (linear), texture 1 emissive (sRGB) and normal and occlusion (linear): four cg textures,
     * the two of a pair with the same pixels. */
    assert_int_equal(s->texture_count, 4);
    int srgb[] = { m->base_color_texture, m->emissive_texture };
    int linear[] = { m->metallic_roughness_texture, m->normal_texture, m->occlusion_texture, m->transmission_texture };
    for (int k = 0; k < 2; k++) {
        assert_in_range(srgb[k], 0, s->texture_count - 1);
        assert_true(s->textures[srgb[k]].srgb);
    }
    for (int k = 0; k < 4; k++) {
        assert_in_range(linear[k], 0, s->texture_count - 1);
        assert_false(s->textures[linear[k]].srgb);
    }
    assert_int_not_equal(m->base_color_texture, m->metallic_roughness_texture);
    assert_int_equal(m->metallic_roughness_texture, m->transmission_texture);
    assert_int_equal(m->normal_texture, m->occlusion_texture);
    const cg_texture *a = &s->textures[m->base_color_texture], *b = &s->textures[m->metallic_roughness_texture];
    assert_memory_equal(a->rgba, b->rgba, 16);
    /* glTF's top row (red, green) is the first row of cg_texture; the texel (1, 1) of the image
     * (its bottom right) has alpha 128. */
    assert_int_equal(a->rgba[0], 255);
    assert_int_equal(a->rgba[5], 255);
    assert_int_equal(a->rgba[15], 128);
    /* KHR_texture_transform: T(0.5, 0.25) R(pi/2) S(2, 3), with u' = cos r u + sin r v,
     * v' = -sin r u + cos r v: A = [[0, 3], [-2, 0]] (rows), columns first (0, -2, 3, 0). */
    static const double base_uv[6] = { 0, -2, 3, 0, 0.5, 0.25 };
    static const double mr_uv[6] = { 4, 0, 0, 4, 0, 0 };
    static const double occ_uv[6] = { 1, 0, 0, 1, 0.125, 0 };
    const double c = cos(0.5), sn = sin(0.5);
    const double tr_uv[6] = { c, -sn, sn, c, 0, 0 };
    static const double identity[6] = { 1, 0, 0, 1, 0, 0 };
    check_uv(&m->uv[CG_TEX_BASE_COLOR], base_uv, 1e-6);
    check_uv(&m->uv[CG_TEX_METALLIC_ROUGHNESS], mr_uv, 1e-6);
    check_uv(&m->uv[CG_TEX_OCCLUSION], occ_uv, 1e-6);
    check_uv(&m->uv[CG_TEX_TRANSMISSION], tr_uv, 1e-6);
    check_uv(&m->uv[CG_TEX_NORMAL], identity, 0);
    check_uv(&m->uv[CG_TEX_EMISSIVE], identity, 0);
    /* The extension's own example: offset (0, 1), rotation pi/2, scale 0.5 takes the unit square
     * to the image's lower left quadrant (u in [0, 0.5], v in [0.5, 1]), seen through its corner
     * uv (1, 1) -> (0.5, 0.5). */
    const cg_uv_transform *t = &m->uv[CG_TEX_BASE_COLOR];
    double u = t->m[0] * 1 + t->m[2] * 0 + t->m[4], v = t->m[1] * 1 + t->m[3] * 0 + t->m[5];
    assert_float_equal(u, 0.5, 1e-6);  /* (1, 0): u' = 0 + 0.5 */
    assert_float_equal(v, -1.75, 1e-6); /* v' = -2 + 0.25 */
}

static void
materials_as_gltf_defines_them(void **state)
{
    (void)state;
    cg_scene s;
    load_ok(cg_test_data_path("gltf/materials/materials.gltf"), &s);
    /* The loader's material 0 (for a primitive without one) and a material with nothing given
     * are glTF's default material. */
    check_gltf_defaults(&s.materials[0]);
    check_gltf_defaults(material_named(&s, "defaults"));
    assert_int_equal(mesh_named(&s, "no_material")->material, 0);
    check_full_material(&s);
    const cg_material *u = material_named(&s, "unsupported");
    assert_int_equal(u->alpha_mode, CG_ALPHA_BLEND);
    assert_true(u->ior == 0); /* KHR_materials_ior: 0 is an infinite ior, kept as 0 */
    assert_true(u->transmission == 1 && u->thickness == 0.5f && u->specular == 1);

    /* Tangents: generated for the quad laid out as the image, T = +x and w = +1 (bitangent
     * cross(N, T) = +y, the image's up); u mirrored gives T = -x and w = -1; the file's TANGENT
     * is kept as it is; a material without normal texture gets none. */
    static const float generated[4] = { 1, 0, 0, 1 }, mirrored[4] = { -1, 0, 0, -1 }, file[4] = { 0, 1, 0, -1 };
    check_tangents(mesh_named(&s, "generated"), generated);
    check_tangents(mesh_named(&s, "mirrored"), mirrored);
    check_tangents(mesh_named(&s, "from_file"), file);
    assert_null(mesh_named(&s, "plain")->tangents);
    assert_null(mesh_named(&s, "no_material")->tangents);

    assert_int_equal(s.light_count, 1);
    assert_true(s.lights[0].angular_diameter == 0.0093f);
    cg_scene_free(&s);
}

/* The one notice at load names each feature left out, the material and the fallback. The
 * log goes to stderr: captured here through a file. */
static void
notice_lists_what_is_left_out(void **state)
{
    (void)state;
    char path[4200];
    snprintf(path, sizeof path, "%s/notice.txt", cg_test_tmpdir());
    fflush(stderr);
    int saved = dup(2);
    assert_true(saved >= 0);
    FILE *capture = fopen(path, "w+");
    assert_non_null(capture);
    assert_true(dup2(fileno(capture), 2) >= 0);
    cg_scene s;
    cg_error err = { 0 };
    bool ok = cg_scene_load(cg_test_data_path("gltf/materials/materials.gltf"), &s, &err);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    fclose(capture);
    assert_cg_ok(ok, &err);
    cg_scene_free(&s);
    char *text;
    size_t size;
    assert_cg_ok(cg_read_file(path, &text, &size, &err), &err);
    printf("# %s", text);
    static const char *const parts[] = {
        "material features not rendered",
        "KHR_materials_clearcoat (material 'unsupported'): no clear coat; the base layer alone",
        "KHR_materials_specular specularTexture (material 'unsupported'): specularFactor alone",
        "KHR_materials_volume thicknessTexture (material 'unsupported'): thicknessFactor alone",
    };
    for (size_t i = 0; i < sizeof parts / sizeof *parts; i++)
        if (!strstr(text, parts[i]))
            fail_msg("the notice lacks '%s'", parts[i]);
    /* One notice: the heading once. */
    assert_null(strstr(strstr(text, parts[0]) + 1, parts[0]));
    free(text);
}

/* What loading `path` writes on stderr (captured through a file, as above); the scene is loaded
 * into *s. */
static char *
load_capturing_stderr(const char *path, cg_scene *s)
{
    char capture_path[4200];
    snprintf(capture_path, sizeof capture_path, "%s/load_stderr.txt", cg_test_tmpdir());
    fflush(stderr);
    int saved = dup(2);
    assert_true(saved >= 0);
    FILE *capture = fopen(capture_path, "w+");
    assert_non_null(capture);
    assert_true(dup2(fileno(capture), 2) >= 0);
    cg_error err = { 0 };
    bool ok = cg_scene_load(path, s, &err);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    fclose(capture);
    assert_cg_ok(ok, &err);
    char *text;
    assert_cg_ok(cg_read_file(capture_path, &text, NULL, &err), &err);
    return text;
}

/* Morph targets are read (tests/data/gltf/morph/tent.gltf: one target lifts the third vertex by
 * 1 along +z, its weight animated from 0 to 1 over 1 s) and load without a notice, as a skinned
 * file (skin/bend.gltf) does. */
static void
morph_targets_and_skins_load_silently(void **state)
{
    (void)state;
    cg_scene s;
    char *text = load_capturing_stderr(cg_test_data_path("gltf/morph/tent.gltf"), &s);
    if (text[0])
        fail_msg("tent.gltf loaded with a notice: %s", text);
    free(text);
    assert_int_equal(s.morphed_count, 1);
    assert_int_equal(s.morphed[0].target_count, 1);
    assert_true(cg_scene_is_animated(&s));
    const cg_mesh *m = &s.meshes[s.morphed[0].mesh];
    assert_true(s.instances[s.morphed[0].instance].moving);
    assert_float_equal(m->positions[8], 0, 0); /* t = 0: weight 0 */
    cg_scene_changes ch;
    cg_scene_evaluate(&s, 0.5, &ch);
    assert_int_equal(ch.meshes_deformed, 1);
    assert_int_equal(ch.instances_moved, 1);
    assert_true(m->revision == s.revision);
    assert_float_equal(m->positions[8], 0.5, 1e-6);
    assert_float_equal(m->positions[0], 0, 0); /* the other vertices stay */
    cg_scene_evaluate(&s, 1, &ch);
    assert_float_equal(m->positions[8], 1, 1e-6);
    assert_float_equal(m->bounds_max[2], 1, 1e-6);
    cg_scene_evaluate(&s, 1, &ch);
    assert_int_equal(ch.meshes_deformed, 0);
    /* The bounds hold the lifted vertex whatever the time the scene is posed at. */
    assert_true(s.bounds_max[2] >= 1 - 1e-6);
    cg_scene_free(&s);

    text = load_capturing_stderr(cg_test_data_path("gltf/skin/bend.gltf"), &s);
    if (text[0])
        fail_msg("bend.gltf loaded with a notice: %s", text);
    assert_int_equal(s.skinned_count, 1);
    free(text);
    cg_scene_free(&s);
}

static void
assert_same_material(const cg_material *x, const cg_material *y, double uv_tol)
{
    assert_string_equal(x->name, y->name);
    cg_material a = *x, b = *y;
    for (int t = 0; t < CG_TEX_COUNT; t++) {
        double want[6];
        for (int k = 0; k < 6; k++)
            want[k] = a.uv[t].m[k];
        check_uv(&b.uv[t], want, uv_tol);
        a.uv[t] = b.uv[t];
    }
    /* Every other field exactly (the structs are copies made field by field, padding included
     * through the same initialisation: compare fields, not bytes). */
    assert_memory_equal(a.base_color, b.base_color, sizeof a.base_color);
    assert_memory_equal(a.emissive, b.emissive, sizeof a.emissive);
    assert_true(a.emissive_strength == b.emissive_strength);
    assert_true(a.metallic == b.metallic && a.roughness == b.roughness);
    assert_int_equal(a.base_color_texture, b.base_color_texture);
    assert_int_equal(a.emissive_texture, b.emissive_texture);
    assert_int_equal(a.metallic_roughness_texture, b.metallic_roughness_texture);
    assert_int_equal(a.normal_texture, b.normal_texture);
    assert_int_equal(a.occlusion_texture, b.occlusion_texture);
    assert_int_equal(a.transmission_texture, b.transmission_texture);
    assert_true(a.normal_scale == b.normal_scale && a.occlusion_strength == b.occlusion_strength);
    assert_int_equal(a.alpha_mode, b.alpha_mode);
    assert_true(a.alpha_cutoff == b.alpha_cutoff);
    assert_int_equal(a.double_sided, b.double_sided);
    assert_true(a.ior == b.ior && a.specular == b.specular && a.transmission == b.transmission);
    assert_memory_equal(a.specular_color, b.specular_color, sizeof a.specular_color);
    assert_true(a.thickness == b.thickness && a.attenuation_distance == b.attenuation_distance);
    assert_memory_equal(a.attenuation_color, b.attenuation_color, sizeof a.attenuation_color);
}

/* Export and load back (.gltf and .glb): every material field, the textures' encodings, the
 * tangents and the sun's angular diameter come back. */
static void
materials_round_trip(void **state)
{
    (void)state;
    cg_scene a;
    load_ok(cg_test_data_path("gltf/materials/materials.gltf"), &a);
    const char *outs[2] = { "materials_out.gltf", "materials_out.glb" };
    for (int i = 0; i < 2; i++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", cg_test_tmpdir(), outs[i]);
        cg_error err = { 0 };
        assert_cg_ok(cg_scene_export_gltf(&a, path, &err), &err);
        cg_scene b;
        load_ok(path, &b);
        assert_int_equal(a.material_count, b.material_count);
        for (int m = 0; m < a.material_count; m++)
            assert_same_material(&a.materials[m], &b.materials[m], 1e-6);
        assert_int_equal(a.texture_count, b.texture_count);
        for (int t = 0; t < a.texture_count; t++) {
            assert_int_equal(a.textures[t].srgb, b.textures[t].srgb);
            assert_memory_equal(a.textures[t].rgba, b.textures[t].rgba, 16);
        }
        assert_int_equal(a.mesh_count, b.mesh_count);
        for (int m = 0; m < a.mesh_count; m++) {
            assert_int_equal(a.meshes[m].material, b.meshes[m].material);
            assert_int_equal(a.meshes[m].tangents != NULL, b.meshes[m].tangents != NULL);
            if (a.meshes[m].tangents)
                assert_memory_equal(a.meshes[m].tangents, b.meshes[m].tangents,
                                    16 * (size_t)a.meshes[m].vertex_count);
        }
        assert_true(b.lights[0].angular_diameter == a.lights[0].angular_diameter);
        cg_scene_free(&b);
    }
    cg_scene_free(&a);
}

/* A built-in scene's Lambertian materials (specular 0, metallic 0, double-sided) are not
 * glTF's defaults: exported, they load back the same, material 0 included. */
static void
builtin_materials_round_trip(void **state)
{
    (void)state;
    const char *sources[] = { "builtin:cornell", "builtin:furnace" };
    for (size_t i = 0; i < sizeof sources / sizeof *sources; i++) {
        cg_scene a, b;
        load_ok(sources[i], &a);
        char path[4200];
        snprintf(path, sizeof path, "%s/builtin_materials_%zu.gltf", cg_test_tmpdir(), i);
        cg_error err = { 0 };
        assert_cg_ok(cg_scene_export_gltf(&a, path, &err), &err);
        load_ok(path, &b);
        assert_int_equal(a.material_count, b.material_count);
        for (int m = 0; m < a.material_count; m++) {
            assert_true(a.materials[m].specular == 0);
            assert_same_material(&a.materials[m], &b.materials[m], 0);
        }
        for (int m = 0; m < a.mesh_count; m++)
            assert_int_equal(a.meshes[m].material, b.meshes[m].material);
        cg_scene_free(&a);
        cg_scene_free(&b);
    }
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(triangle_with_and_without_indices),
             cmocka_unit_test(strips_and_fans),
             cmocka_unit_test(points_and_lines_are_skipped),
             cmocka_unit_test(node_hierarchy),
             cmocka_unit_test(lights_and_cameras),
             cmocka_unit_test(materials_and_textures),
             cmocka_unit_test(binary_gltf),
             cmocka_unit_test(heightfield_classification),
             cmocka_unit_test(sparse_accessors),
             cmocka_unit_test(good_base_loads),
             cmocka_unit_test(malformed_corpus),
             cmocka_unit_test(buffer_from_a_device_is_refused),
             cmocka_unit_test(missing_file),
             cmocka_unit_test(materials_as_gltf_defines_them),
             cmocka_unit_test(notice_lists_what_is_left_out),
             cmocka_unit_test(morph_targets_and_skins_load_silently),
             cmocka_unit_test(materials_round_trip),
             cmocka_unit_test(builtin_materials_round_trip))
