/* The command line as a new user meets it, end to end through $CONEGRAPH_EXE: `version` and
 * `--version`, scenes without lights (the default light and its notice), cameras whose aspect
 * ratio is not the image's, --camera auto, --from/--look-at/--fov, --sky on the command line
 * and in graph files, and `compare` refusing an sRGB image beside a linear one. The glTF files
 * are small ones written here, each reproducing a case met in third-party files. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cg/fs.h"
#include "cg/image.h"
#include "test_support.h"

static char out_text[1 << 16], err_text[1 << 16];

/* Runs conegraph with `args`; returns the exit code, stdout and stderr in out_text, err_text. */
static int
run(const char *args)
{
    return cg_test_run_conegraph_split(args, out_text, sizeof out_text, err_text, sizeof err_text);
}

static void
expect_in(const char *text, const char *what, const char *args)
{
    if (!strstr(text, what))
        fail_msg("conegraph %s: expected '%s' in:\n%s", args, what, text);
}

/* ------------------------------------------------------------ scenes as third-party files are */

/* One mesh of the test scene, as it goes into the buffer. */
typedef struct test_mesh {
    float positions[24][3], normals[24][3], texcoords[24][2];
    uint16_t indices[36];
    int vertices, index_count;
} test_mesh;

/* A unit cube about the origin: 4 vertices a face, each face the whole texture. */
static void
make_cube(test_mesh *m)
{
    memset(m, 0, sizeof *m);
    static const float normals[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
    for (int f = 0; f < 6; f++) {
        const float *n = normals[f];
        /* u and v span the face, u x v = n (counter-clockwise seen from outside). */
        float u[3] = { n[1] + n[2] != 0 ? 1.0f : 0.0f, 0, n[0] != 0 ? -n[0] : 0 };
        if (n[2] != 0)
            u[0] = n[2], u[2] = 0;
        if (n[1] != 0)
            u[0] = 1, u[2] = 0;
        float v[3] = { n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0] };
        static const float corners[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
        for (int c = 0; c < 4; c++) {
            int i = m->vertices++;
            for (int k = 0; k < 3; k++) {
                m->positions[i][k] = 0.5f * (n[k] + corners[c][0] * u[k] + corners[c][1] * v[k]);
                m->normals[i][k] = n[k];
            }
            m->texcoords[i][0] = 0.5f * (corners[c][0] + 1);
            m->texcoords[i][1] = 0.5f * (1 - corners[c][1]);
        }
        static const int quad[6] = { 0, 1, 2, 0, 2, 3 };
        for (int k = 0; k < 6; k++)
            m->indices[m->index_count++] = (uint16_t)(4 * f + quad[k]);
    }
}

/* A 4 m square floor at y = -0.5, facing up. */
static void
make_floor(test_mesh *m)
{
    memset(m, 0, sizeof *m);
    static const float corners[4][2] = { { -2, 2 }, { 2, 2 }, { 2, -2 }, { -2, -2 } };
    for (int c = 0; c < 4; c++) {
        m->positions[c][0] = corners[c][0];
        m->positions[c][1] = -0.5f;
        m->positions[c][2] = corners[c][1];
        m->normals[c][1] = 1;
        m->texcoords[c][0] = corners[c][0] > 0;
        m->texcoords[c][1] = corners[c][1] > 0;
    }
    m->vertices = 4;
    static const uint16_t quad[6] = { 0, 1, 2, 0, 2, 3 };
    memcpy(m->indices, quad, sizeof quad);
    m->index_count = 6;
}

/* Writes NAME.gltf (NAME.bin, NAME.png beside it) as Khronos' samples are: no lights, a
 * textured cube and a grey floor (several meshes), and with `camera` a camera of
 * aspectRatio 1 at (0, 1, 4) looking down -z. Returns the .gltf path. */
static const char *
write_scene(const char *name, bool camera)
{
    test_mesh mesh[2];
    make_cube(&mesh[0]);
    make_floor(&mesh[1]);
    static unsigned char bin[8192];
    size_t size = 0, offsets[2][4];
    for (int i = 0; i < 2; i++) {
        const void *parts[4] = { mesh[i].positions, mesh[i].normals, mesh[i].texcoords, mesh[i].indices };
        size_t sizes[4] = { 12u * mesh[i].vertices, 12u * mesh[i].vertices, 8u * mesh[i].vertices,
                            2u * mesh[i].index_count };
        for (int k = 0; k < 4; k++) {
            offsets[i][k] = size;
            memcpy(bin + size, parts[k], sizes[k]);
            size += (sizes[k] + 3) & ~(size_t)3;
        }
    }
    char bin_name[256], png_name[256], gltf_name[256];
    snprintf(bin_name, sizeof bin_name, "%s.bin", name);
    snprintf(png_name, sizeof png_name, "%s.png", name);
    snprintf(gltf_name, sizeof gltf_name, "%s.gltf", name);
    cg_test_write_file(bin_name, bin, size);
    /* A 4x4 texture of two colours in a checker. */
    cg_image tex = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_alloc(&tex, 4, 4, &err), &err);
    for (int i = 0; i < 16; i++) {
        bool odd = ((i % 4) + (i / 4)) % 2;
        float rgb[3] = { odd ? 0.8f : 0.2f, odd ? 0.5f : 0.4f, odd ? 0.1f : 0.7f };
        memcpy(tex.rgba + 4 * i, rgb, sizeof rgb);
        tex.rgba[4 * i + 3] = 1;
    }
    char png_path[4200];
    snprintf(png_path, sizeof png_path, "%s/%s", cg_test_tmpdir(), png_name);
    assert_cg_ok(cg_image_write(png_path, &tex, CG_EXR_HALF, &err), &err);
    cg_image_free(&tex);

    static char json[16384];
    int n = snprintf(json, sizeof json,
        "{ \"asset\": { \"version\": \"2.0\" }, \"scene\": 0,\n"
        "  \"scenes\": [ { \"nodes\": [ 0, 1%s ] } ],\n"
        "  \"nodes\": [ { \"mesh\": 0, \"name\": \"cube\" }, { \"mesh\": 1, \"name\": \"floor\" }%s ],\n"
        "%s"
        "  \"meshes\": [\n"
        "    { \"primitives\": [ { \"attributes\": { \"POSITION\": 0, \"NORMAL\": 1, \"TEXCOORD_0\": 2 }, \"indices\": 3, \"material\": 0 } ] },\n"
        "    { \"primitives\": [ { \"attributes\": { \"POSITION\": 4, \"NORMAL\": 5, \"TEXCOORD_0\": 6 }, \"indices\": 7, \"material\": 1 } ] } ],\n"
        "  \"materials\": [ { \"pbrMetallicRoughness\": { \"baseColorTexture\": { \"index\": 0 }, \"metallicFactor\": 0 } },\n"
        "                   { \"pbrMetallicRoughness\": { \"baseColorFactor\": [ 0.6, 0.6, 0.6, 1 ], \"metallicFactor\": 0 } } ],\n"
        "  \"textures\": [ { \"source\": 0 } ], \"images\": [ { \"uri\": \"%s\" } ],\n"
        "  \"buffers\": [ { \"uri\": \"%s\", \"byteLength\": %zu } ],\n"
        "  \"bufferViews\": [\n",
        camera ? ", 2" : "", camera ? ", { \"camera\": 0, \"name\": \"eye\", \"translation\": [ 0, 1, 4 ] }" : "",
        camera ? "  \"cameras\": [ { \"type\": \"perspective\", \"name\": \"square\", \"perspective\": "
                 "{ \"aspectRatio\": 1.0, \"yfov\": 0.8, \"znear\": 0.1 } } ],\n" : "",
        png_name, bin_name, size);
    static const size_t stride[4] = { 12, 12, 8, 2 };
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 4; k++) {
            size_t length = stride[k] * (size_t)(k == 3 ? mesh[i].index_count : mesh[i].vertices);
            n += snprintf(json + n, sizeof json - (size_t)n, "    { \"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu }%s\n",
                          offsets[i][k], length, i == 1 && k == 3 ? "" : ",");
        }
    n += snprintf(json + n, sizeof json - (size_t)n, "  ],\n  \"accessors\": [\n");
    for (int i = 0; i < 2; i++) {
        float lo[3] = { 1e9f, 1e9f, 1e9f }, hi[3] = { -1e9f, -1e9f, -1e9f };
        for (int v = 0; v < mesh[i].vertices; v++)
            for (int k = 0; k < 3; k++) {
                lo[k] = fminf(lo[k], mesh[i].positions[v][k]);
                hi[k] = fmaxf(hi[k], mesh[i].positions[v][k]);
            }
        n += snprintf(json + n, sizeof json - (size_t)n,
            "    { \"bufferView\": %d, \"componentType\": 5126, \"count\": %d, \"type\": \"VEC3\", \"min\": [ %g, %g, %g ], \"max\": [ %g, %g, %g ] },\n"
            "    { \"bufferView\": %d, \"componentType\": 5126, \"count\": %d, \"type\": \"VEC3\" },\n"
            "    { \"bufferView\": %d, \"componentType\": 5126, \"count\": %d, \"type\": \"VEC2\" },\n"
            "    { \"bufferView\": %d, \"componentType\": 5123, \"count\": %d, \"type\": \"SCALAR\" }%s\n",
            4 * i, mesh[i].vertices, (double)lo[0], (double)lo[1], (double)lo[2], (double)hi[0], (double)hi[1],
            (double)hi[2], 4 * i + 1, mesh[i].vertices, 4 * i + 2, mesh[i].vertices, 4 * i + 3, mesh[i].index_count,
            i == 1 ? "" : ",");
    }
    snprintf(json + n, sizeof json - (size_t)n, "  ] }\n");
    return cg_test_write_file(gltf_name, json, 0);
}

/* Mean of the RGB channels over the image, and the top-left pixel's red channel. */
static double
mean_of(const char *path, float *corner)
{
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_read(path, &img, &err), &err);
    double sum = 0;
    for (int i = 0; i < img.width * img.height; i++)
        sum += img.rgba[4 * i] + img.rgba[4 * i + 1] + img.rgba[4 * i + 2];
    if (corner)
        *corner = img.rgba[0];
    double mean = sum / (3.0 * img.width * img.height);
    cg_image_free(&img);
    return mean;
}

/* A scene with no light renders lit, with one notice saying so and how to turn it off, in
 * render, graph and info; --no-default-light leaves it black, with a warning; exit 0 both. */
static void
scene_without_light_gets_the_default_light(void **state)
{
    (void)state;
    const char *scene = write_scene("nolight", false);
    const char *out = cg_test_tmp_path("nolight.exr");
    char args[9000];
    const char *graphs[] = { "direct.json", "vct.json" };
    for (int g = 0; g < 2; g++) {
        snprintf(args, sizeof args, "render '%s' --graph %s --size 48x27 -o '%s'", scene, graphs[g], out);
        assert_int_equal(run(args), 0);
        expect_in(err_text, "conegraph render: scene ", args);
        expect_in(err_text, "nolight.gltf has no light: added a sun (3 W/m^2, white, 55 degrees above the horizon", args);
        expect_in(err_text, "and a uniform sky (0.2 W/(m^2 sr)); --no-default-light turns this off", args);
        assert_null(strstr(strstr(err_text, "has no light") + 1, "has no light")); /* once */
        assert_true(mean_of(out, NULL) > 0.02);
    }
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 48x27 --no-default-light -o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    assert_null(strstr(err_text, "added a sun"));
    expect_in(err_text, "--no-default-light keeps it so: the image will be black", args);
    assert_true(mean_of(out, NULL) == 0.0);

    /* graph compiles the scene as render lights it: the shadow pass runs for the sun. */
    snprintf(args, sizeof args, "graph direct.json '%s' --size 48x27", scene);
    assert_int_equal(run(args), 0);
    expect_in(out_text, "4 of 4 passes run", args);
    expect_in(err_text, "conegraph graph: scene ", args);
    snprintf(args, sizeof args, "graph direct.json '%s' --size 48x27 --no-default-light", scene);
    assert_int_equal(run(args), 0);
    expect_in(out_text, "3 of 4 passes run", args);
    /* info says it too, and marks the light it added. */
    snprintf(args, sizeof args, "info '%s'", scene);
    assert_int_equal(run(args), 0);
    expect_in(err_text, "conegraph info: scene ", args);
    expect_in(out_text, "'default_sun' directional (added: the default light)", args);
    expect_in(out_text, "sky 0.2 (uniform", args);
    expect_in(out_text, "meshes 2", args);
    snprintf(args, sizeof args, "info '%s' --no-default-light", scene);
    assert_int_equal(run(args), 0);
    expect_in(out_text, "lights 0", args);
    /* A scene with lights of its own is left as it is. */
    assert_int_equal(run("info builtin:cornell"), 0);
    assert_null(strstr(err_text, "added"));
    assert_null(strstr(out_text, "default_sun"));
}

/* The path tracer shows the sky where no surface is: --sky, a graph file's "sky", and --sky
 * over the file's. The top-left pixel of the framed view (--camera auto) sees no surface. */
static void
sky_is_seen_and_command_line_wins(void **state)
{
    (void)state;
    const char *scene = write_scene("skyscene", true);
    const char *out = cg_test_tmp_path("sky.exr");
    char args[9000];
    float corner;
    snprintf(args, sizeof args, "render '%s' --graph reference.json --set trace.spp=2 --camera auto --size 32x18 "
             "--sky 0.5,0.25,0.125 -o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    assert_null(strstr(err_text, "added a sun")); /* the sky lights the scene */
    mean_of(out, &corner);
    assert_true(corner == 0.5f);
    /* A graph file asking for a sky. */
    char *reference;
    cg_error err = { 0 };
    assert_cg_ok(cg_read_file(cg_test_graph_path("reference.json"), &reference, NULL, &err), &err);
    const char *version = strstr(reference, "\"version\": 1,");
    assert_non_null(version);
    static char with_sky[16384];
    snprintf(with_sky, sizeof with_sky, "%.*s\"version\": 1, \"sky\": \"0.25\",%s", (int)(version - reference),
             reference, version + strlen("\"version\": 1,"));
    free(reference);
    const char *graph = cg_test_write_file("sky-graph.json", with_sky, 0);
    snprintf(args, sizeof args, "render '%s' --graph '%s' --set trace.spp=2 --camera auto --size 32x18 -o '%s'",
             scene, graph, out);
    assert_int_equal(run(args), 0);
    assert_null(strstr(err_text, "added a sun"));
    mean_of(out, &corner);
    assert_true(corner == 0.25f);
    snprintf(args, sizeof args, "render '%s' --graph '%s' --set trace.spp=2 --camera auto --size 32x18 --sky 2 -o '%s'",
             scene, graph, out);
    assert_int_equal(run(args), 0);
    mean_of(out, &corner);
    assert_true(corner == 2.0f);
    /* A Preetham sky on a scene with no sun gets the default sun to follow, with a notice. */
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 32x18 --sky preetham:3,0.05 -o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    expect_in(err_text, "no directional light for the Preetham sky (--sky) to follow: added a sun", args);
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 32x18 --sky preetham --no-default-light -o '%s'",
             scene, out);
    assert_int_equal(run(args), 2);
    expect_in(err_text, "a Preetham sky takes its sun from the first directional light", args);
    /* Bad skies exit 2 before anything is written. */
    const char *bad[] = { "--sky -1", "--sky 1,2", "--sky preetham:11", "--sky blue" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(args, sizeof args, "render '%s' --size 32x18 %s -o '%s'", scene, bad[i], cg_test_tmp_path("never.exr"));
        assert_int_equal(run(args), 2);
        assert_int_not_equal(access(cg_test_tmp_path("never.exr"), F_OK), 0);
    }
}

/* A camera of aspectRatio 1 in a 16:9 image: a notice of the widened field of view, nothing
 * stretched; --camera auto frames the bounds instead; --from, --look-at, --fov. */
static void
cameras_as_users_ask_for_them(void **state)
{
    (void)state;
    const char *scene = write_scene("camscene", true);
    const char *out = cg_test_tmp_path("cam.exr");
    char args[9000];
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 64x36 -o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    expect_in(err_text, "camera 'square' has aspect ratio 1 and the 64x36 image 1.78: the horizontal field of view "
              "is widened from 45.8 to 73.9 degrees (the vertical one, 45.8 degrees, kept), nothing is stretched", args);
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 36x64 -o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    expect_in(err_text, "the vertical field of view is widened from 45.8 to 73.9 degrees", args);
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 64x64 -o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    assert_null(strstr(err_text, "aspect ratio"));
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 64x36 --camera auto -o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    assert_null(strstr(err_text, "aspect ratio"));
    snprintf(args, sizeof args, "render '%s' --graph direct.json --size 64x36 --from 3,2,3 --look-at 0,0,0 --fov 30 "
             "-o '%s'", scene, out);
    assert_int_equal(run(args), 0);
    assert_true(mean_of(out, NULL) > 0.02);
    const char *bad[] = { "--fov 0", "--fov 180", "--fov wide", "--from 1,2", "--look-at 1,2,3,4",
                          "--from 0,1,4 --look-at 0,1,4", "--camera nobody", "--camera 3" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(args, sizeof args, "render '%s' --graph direct.json --size 32x18 %s -o '%s'", scene, bad[i],
                 cg_test_tmp_path("never.exr"));
        if (run(args) != 2)
            fail_msg("%s did not exit 2: %s", bad[i], err_text);
        assert_int_not_equal(access(cg_test_tmp_path("never.exr"), F_OK), 0);
    }
}

static void
version_names_every_library(void **state)
{
    (void)state;
    const char *forms[] = { "version", "--version" };
    for (int i = 0; i < 2; i++) {
        assert_int_equal(run(forms[i]), 0);
        const char *names[] = { "conegraph    0.", "OpenGL       4.5 (Core Profile)", "Embree       3.",
                                "OpenImageIO  2.", "tinygltf     2.", "jansson      2.", "cglm         0.",
                                "GLFW         3." };
        for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
            expect_in(out_text, names[k], forms[i]);
    }
    assert_int_equal(run("version --no-gl"), 0);
    expect_in(out_text, "OpenGL       not queried (--no-gl)", "version --no-gl");
    assert_int_equal(run("version --context osmesa"), 0);
    expect_in(out_text, "(osmesa context)", "version --context osmesa");
    assert_int_equal(run("version --bogus"), 2);
    assert_int_equal(run("version --context vulkan"), 2);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(version_names_every_library),
             cmocka_unit_test(scene_without_light_gets_the_default_light),
             cmocka_unit_test(sky_is_seen_and_command_line_wins),
             cmocka_unit_test(cameras_as_users_ask_for_them))
