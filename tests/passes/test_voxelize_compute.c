/* The voxelizer two ways, the surface model's geometry sums: voxelize's geometry-shader path (the
 * pass as shipped: dominant-axis projection, dilated triangles, an exact triangle/voxel test per
 * fragment) against a compute-shader one (shaders/voxelize/compute.comp: each triangle visits
 * its columns itself, large triangles binned to whole work groups), on one scene.
 *
 * Asserted: every fragment (voxel of a triangle's column) the rasterized path makes, the compute
 * path makes too; the compute path's extra ones are ties at voxel faces (below); where both
 * counted a voxel alike, their albedo, normal and offset sums agree to the rounding of the
 * interpolated attributes.
 * Printed: the median time of each over the runs (glFinish around each; the geometry-shader
 * figure is the voxelize pass with cache=false, its clear and its resolve included).
 *
 * As a test: builtin:openworld at 20 000 triangles and builtin:cornell, 32^3, 1 run. As the benchmark of the
 * dynamic-scenes issue (docs/dynamic.md):
 *     build/tests/test_voxelize_compute SCENE RESOLUTION RUNS */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/scene.h"
#include "cg/shader.h"
#include "sdk/blocks.h"
#include "test_support.h"
#include "vct_fixture.h"

static const char *scene_source = NULL;   /* NULL: the test's two scenes */
static int resolution = 32;
static int runs = 1;

#define SLABS 14
#define SURFACE_HEADROOM 4096.0    /* passes/voxelize/voxelize.c's */

static double
now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static int
compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double
median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_doubles);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static uint32_t *
read_accumulation(GLuint tex, size_t count)
{
    uint32_t *data = malloc(count * sizeof *data);
    assert_non_null(data);
    glGetTextureImage(tex, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, (GLsizei)(count * sizeof *data), data);
    return data;
}

/* The compute voxelizer over every instance of the scene into `accum` (2R x 2R x 4R R32UI, the
 * pass's layout); returns the milliseconds it took (glFinish). */
static double
voxelize_compute(const cg_gpu_scene *gpu, GLuint small, GLuint large, GLuint list, GLuint accum,
                 const float origin_voxel[4], double unit_fixed, double emission_fixed, size_t *large_triangles)
{
    const cg_scene *scene = gpu->scene;
    glFinish();
    double t0 = now_ms();
    const GLuint zero = 0;
    glClearTexImage(accum, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindImageTexture(0, accum, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_MATERIALS, gpu->material_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, list);
    *large_triangles = 0;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        const cg_gpu_mesh *mesh = &gpu->meshes[inst->mesh];
        if (mesh->index_count == 0)
            continue;
        /* The model and normal matrices as cg_gpu_scene_draw sets them. */
        const float *m = inst->world;
        double a[9] = {m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]}, inv[9];
        double det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[3] * (a[1] * a[8] - a[2] * a[7]) +
                     a[6] * (a[1] * a[5] - a[2] * a[4]);
        inv[0] = (a[4] * a[8] - a[5] * a[7]) / det;
        inv[1] = (a[2] * a[7] - a[1] * a[8]) / det;
        inv[2] = (a[1] * a[5] - a[2] * a[4]) / det;
        inv[3] = (a[5] * a[6] - a[3] * a[8]) / det;
        inv[4] = (a[0] * a[8] - a[2] * a[6]) / det;
        inv[5] = (a[2] * a[3] - a[0] * a[5]) / det;
        inv[6] = (a[3] * a[7] - a[4] * a[6]) / det;
        inv[7] = (a[1] * a[6] - a[0] * a[7]) / det;
        inv[8] = (a[0] * a[4] - a[1] * a[3]) / det;
        float normal[9];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                normal[3 * c + r] = (float)inv[3 * r + c];  /* transpose of the inverse */
        int material = scene->meshes[inst->mesh].material;
        if (material < 0 || material >= scene->material_count)
            material = 0;
        GLuint triangles = (GLuint)(mesh->index_count / 3);
        const GLuint reset = 0;
        glNamedBufferSubData(list, 0, sizeof reset, &reset);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, mesh->vertex_buffer);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, mesh->index_buffer);
        const cg_material *mat = scene->material_count > 0 ? &scene->materials[material] : NULL;
        glBindTextureUnit(0, mat && mat->base_color_texture >= 0 ? gpu->textures[mat->base_color_texture]
                                                                  : gpu->white_texture);
        glBindTextureUnit(1, mat && mat->emissive_texture >= 0 ? gpu->textures[mat->emissive_texture]
                                                                : gpu->white_texture);
        for (int pass = 0; pass < 2; pass++) {
            glUseProgram(pass == 0 ? small : large);
            glUniformMatrix4fv(0, 1, GL_FALSE, m);
            glUniformMatrix3fv(1, 1, GL_FALSE, normal);
            glUniform1i(2, material);
            glUniform4fv(8, 1, origin_voxel);
            glUniform1i(9, resolution);
            glUniform1ui(10, triangles);
            glUniform4f(13, (float)unit_fixed, (float)emission_fixed, 0.0f, 0.0f);
            if (pass == 0) {
                glDispatchCompute((triangles + 63) / 64, 1, 1);
                glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            } else {
                GLuint count = 0;
                glGetNamedBufferSubData(list, 0, sizeof count, &count);
                *large_triangles += count;
                if (count > 0)
                    glDispatchCompute(count, 1, 1);
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            }
        }
    }
    glUseProgram(0);
    glFinish();
    return now_ms() - t0;
}

static void
compare_on(cg_context *ctx, const char *scene_source)
{
    cg_scene scene;
    cg_error err = {0};
    assert_cg_ok(cg_scene_load(scene_source, &scene, &err), &err);
    char json[512];
    snprintf(json, sizeof json,
             "{ \"version\": 1, \"passes\": { \"vox\": { \"type\": \"voxelize\", \"params\": {"
             " \"model\": \"surface\", \"resolution\": %d, \"cache\": false } } }, \"outputs\": [ \"vox.albedo\" ] }",
             resolution);
    vf_runner r;
    vf_start(&r, &scene, 64, 36, json, NULL);
    double *gs = calloc((size_t)runs, sizeof *gs), *cs = calloc((size_t)runs, sizeof *cs);
    assert_non_null(gs);
    assert_non_null(cs);
    vf_frame(&r);   /* warm-up: programs linked, memory touched */
    for (int k = 0; k < runs; k++) {
        glFinish();
        double t0 = now_ms();
        vf_frame(&r);
        glFinish();
        gs[k] = now_ms() - t0;
    }
    size_t count = (size_t)16 * resolution * resolution * resolution;
    uint32_t *raster = read_accumulation(fg_graph_texture(r.graph, "vox.accumulation"), count);
    cg_volume_block block;
    glGetNamedBufferSubData(fg_graph_texture(r.graph, "vox.region"), 0, sizeof block, &block);

    double emission = 0.0;
    for (int m = 0; m < scene.material_count; m++)
        for (int k = 0; k < 3; k++)
            emission = fmax(emission, (double)scene.materials[m].emissive[k] * scene.materials[m].emissive_strength);
    double unit_fixed = 2147483647.0 / SURFACE_HEADROOM;
    double emission_fixed = emission > 0.0 ? 4294967295.0 / (emission * SURFACE_HEADROOM) : 1.0;

    GLuint small = 0, large = 0;
    assert_cg_ok(cg_program_compute("voxelize/compute.comp", NULL, &small, &err), &err);
    assert_cg_ok(cg_program_compute("voxelize/compute.comp", "#define LARGE\n", &large, &err), &err);
    GLuint accum = 0, list = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &accum);
    glTextureStorage3D(accum, 1, GL_R32UI, 2 * resolution, 2 * resolution, 4 * resolution);
    size_t max_triangles = 0;
    for (int m = 0; m < scene.mesh_count; m++)
        if ((size_t)r.gpu.meshes[m].index_count / 3 > max_triangles)
            max_triangles = (size_t)r.gpu.meshes[m].index_count / 3;
    glCreateBuffers(1, &list);
    glNamedBufferStorage(list, (GLsizeiptr)((max_triangles + 1) * sizeof(GLuint)), NULL, GL_DYNAMIC_STORAGE_BIT);
    size_t large_triangles = 0;
    voxelize_compute(&r.gpu, small, large, list, accum, block.origin_voxel, unit_fixed, emission_fixed,
                     &large_triangles);
    for (int k = 0; k < runs; k++)
        cs[k] = voxelize_compute(&r.gpu, small, large, list, accum, block.origin_voxel, unit_fixed,
                                 emission_fixed, &large_triangles);
    uint32_t *compute = read_accumulation(accum, count);

    /* Slab k of the 14 lies at (k & 1, (k >> 1) & 1, k >> 2) x resolution (voxelize.frag). */
    size_t voxels = 0, count_diff = 0, share_diff = 0, fragments = 0, extra_compute = 0, extra_raster = 0;
    double worst_sum = 0.0;
    int n = resolution, w = 2 * n, h = 2 * n;
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                uint32_t c_r = 0, c_c = 0;
                for (int s = 0; s < SLABS; s++) {
                    size_t at = ((size_t)(z + (s >> 2) * n) * h + (size_t)(y + ((s >> 1) & 1) * n)) * w +
                                (size_t)(x + (s & 1) * n);
                    uint32_t a = raster[at], b = compute[at];
                    if (s == 0) {
                        c_r = a;
                        c_c = b;
                        voxels += a > 0;
                        fragments += a;
                        count_diff += a != b;
                        extra_compute += b > a ? b - a : 0;
                        extra_raster += a > b ? a - b : 0;
                    } else if (s >= 11) {
                        share_diff += a != b;
                    } else if (c_r == c_c && c_r > 0) {
                        /* Signed sums (normals, offsets) wrap as two's complement. */
                        double d = fabs((double)(int32_t)(a - b)) / (unit_fixed * c_r);
                        if (s >= 4 && s <= 6)
                            d = fabs((double)a - (double)b) / (emission_fixed * c_r);
                        worst_sum = fmax(worst_sum, d);
                    }
                }
            }
    printf("# %s, %d^3: %zu voxels, %zu fragments; compute against rasterized: %zu counts differ, %zu "
           "coverage shares differ, worst mean attribute difference %.3g (of 1); %zu large triangles binned\n",
           scene_source, resolution, voxels, fragments, count_diff, share_diff, worst_sum, large_triangles);
    printf("# fragments only in compute %zu, only rasterized %zu\n", extra_compute, extra_raster);
    printf("# %s, %d^3, median of %d: voxelize pass (geometry shader, cache=false, with clear and resolve) "
           "%.1f ms, compute voxelizer (clear and voxelization) %.1f ms, ratio %.2f\n",
           scene_source, resolution, runs, median(gs, runs), median(cs, runs), median(cs, runs) / median(gs, runs));
    assert_true(voxels > 0);
    /* Every fragment the rasterizer made, the compute path made too: it is at least as
     * conservative. It makes more where a triangle touches a voxel's face or edge within the
     * overlap test's tolerance (1e-4 voxel), which voxelize.frag means to count (a triangle on a
     * face belongs to both sides) but which the rasterizer reaches only where the dilated
     * triangle covers the pixel's centre: a tie that its fixed-point edge functions break one
     * way or the other. Measured: 2.6% more fragments here, 16% on openworld at 128^3 (its
     * terrain meets voxel faces along whole rows), 0.5% at 2M triangles. */
    assert_int_equal(extra_raster, 0);
    assert_true(extra_compute < fragments / 4);
    /* The attributes are interpolated at the column centre by the rasterizer on one side and by
     * the shader's barycentrics on the other: float rounding, far below the 8-bit volumes. */
    assert_true(worst_sum < 1e-3);

    free(raster);
    free(compute);
    free(gs);
    free(cs);
    glDeleteTextures(1, &accum);
    glDeleteBuffers(1, &list);
    glDeleteProgram(small);
    glDeleteProgram(large);
    vf_stop(&r);
    assert_no_gl_errors(ctx);
    cg_scene_free(&scene);
}

/* The default: an open world's small terrain triangles (one invocation each) and Cornell's
 * walls, each wider than CG_VOXELIZE_SMALL columns (binned to work groups). */
static void
test_compute_against_rasterized(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    if (scene_source) {
        compare_on(ctx, scene_source);
        return;
    }
    compare_on(ctx, "builtin:openworld?triangles=20000");
    compare_on(ctx, "builtin:cornell");
}

int
main(int argc, char **argv)
{
    if (argc > 1)
        scene_source = argv[1];
    if (argc > 2)
        resolution = atoi(argv[2]);
    if (argc > 3)
        runs = atoi(argv[3]);
    if (resolution < 16 || resolution > 512 || (resolution & (resolution - 1)) || runs < 1) {
        fprintf(stderr, "usage: test_voxelize_compute [SCENE [RESOLUTION (16..512, a power of two) [RUNS]]]\n");
        return 2;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_compute_against_rasterized),
    };
    return cmocka_run_group_tests(tests, cg_test_gl_setup, cg_test_gl_teardown);
}
