/* heightmap_raster, mip2d, hsat and the fitting cube alone on a software context:
 *   - the 2D lightmap of a known tilted plane holds its heights and its lit radiance;
 *   - mip2d against a CPU 2x2 box filter;
 *   - hsat min/max (and eq. 13's mean) over random rectangles against brute force at
 *     256^2 and 2048^2, on a terrain 100 km from the origin and 10 km up, for the three
 *     modes: pyramid and pnorm never inside the true range, power_mean (eq. 14 as written)
 *     measurably below the true maximum;
 *   - eq. 10 and 11 (common/fitting_cube.glsl, run on the GPU): cube geometry for
 *     axis-parallel, generic and grazing cones.
 * The measured errors are printed (docs/hybrid.md quotes them). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "cg/shader.h"
#include "hybrid_fixture.h"
#include "test_support.h"

/* ------------------------------------------------------------------ heightmap_raster */

static double
tilted(double x, double z, const void *user)
{
    (void)user;
    return 2.0 + 0.3 * x - 0.2 * z;
}

static const char raster_graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"hm\": { \"type\": \"heightmap_raster\", \"params\": { \"resolution\": 64, \"format\": \"%s\" } },"
    " \"mip\": { \"type\": \"mip2d\", \"inputs\": { \"lightmap\": \"hm.lightmap\" } } },"
    " \"outputs\": [ \"mip.lightmap\" ] }";

static void
check_tilted_plane(cg_context *ctx, const char *format, double height_tolerance)
{
    hf_scene s;
    hf_init(&s);
    hf_material(&s, 1, 0.5f, 0.1f);
    hf_grid(&s, 4, -4.0, -4.0, 8.0, tilted, NULL);
    const double sun[3] = {0.3, -1.0, 0.2};
    hf_sun(&s, sun, 3.0f);
    hf_finish(&s);
    vf_runner r;
    vf_run_format(&r, &s.scene, 32, 32, raster_graph, format);
    int w = 0, h = 0;
    float *map = hf_read_2d(&r, "mip.lightmap", 0, &w, &h);
    assert_int_equal(w, 64);
    assert_int_equal(h, 64);
    /* Lambert: n = (-0.3, 1, 0.2)/|.|, towards the light = -sun/|sun|. */
    double n[3] = {-0.3, 1.0, 0.2}, l[3] = {-0.3, 1.0, -0.2};
    double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), ll = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    double cosine = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / (nn * ll);
    double radiance = 0.1 + 0.5 * 3.0 * cosine / M_PI;
    /* The region block's radiance scale decodes the stored rgb: 1 for RGBA32F, for RGBA16F a
     * bound on the radiance / 32768 (sdk/radiance.h), so that no stored value exceeds 32768. */
    float block[12];
    glGetNamedBufferSubData(fg_graph_texture(r.graph, "hm.region"), 0, sizeof block, block);
    if (!strcmp(format, "rgba32f"))
        assert_float_equal(block[8], 1.0, 0.0);
    else
        assert_true(block[8] > 0.0f && radiance / block[8] <= 32768.0);
    double worst_h = 0, worst_l = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const float *t = &map[4 * (j * w + i)];
            double x = -4.0 + (i + 0.5) * 8.0 / w, z = -4.0 + (j + 0.5) * 8.0 / h;
            worst_h = fmax(worst_h, fabs(t[3] - tilted(x, z, NULL)));
            for (int k = 0; k < 3; k++)
                worst_l = fmax(worst_l, fabs(t[k] * block[8] - radiance) / radiance);
        }
    printf("# heightmap %s: tilted plane, worst height error %.3g m, worst radiance error %.3g (relative)\n",
           format, worst_h, worst_l);
    assert_true(worst_h <= height_tolerance);
    assert_true(worst_l <= 2e-3);

    /* mip2d: every level the 2x2 mean of the one below, all four channels. */
    float *fine = map;
    for (int level = 1, size = w / 2; size >= 1; level++, size /= 2) {
        int cw = 0, ch = 0;
        float *coarse = hf_read_2d(&r, "mip.lightmap", level, &cw, &ch);
        assert_int_equal(cw, size);
        for (int j = 0; j < size; j++)
            for (int i = 0; i < size; i++)
                for (int k = 0; k < 4; k++) {
                    int f = 2 * size;
                    double mean = 0.25 * (fine[4 * ((2 * j) * f + 2 * i) + k] + fine[4 * ((2 * j) * f + 2 * i + 1) + k] +
                                          fine[4 * ((2 * j + 1) * f + 2 * i) + k] +
                                          fine[4 * ((2 * j + 1) * f + 2 * i + 1) + k]);
                    double got = coarse[4 * (j * size + i) + k];
                    if (fabs(got - mean) > 1e-3 * fabs(mean) + 1e-5)
                        fail_msg("mip2d %s level %d texel (%d,%d) channel %d: %g, CPU %g", format, level, i, j, k,
                                 got, mean);
                }
        free(fine);
        fine = coarse;
    }
    free(fine);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
}

static void
test_heightmap_tilted_plane(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    /* fp32: interpolated heights to a few ulps of 4 m; fp16: 11 bits of heights up to 5.2 m. */
    check_tilted_plane(ctx, "rgba32f", 1e-5);
    check_tilted_plane(ctx, "rgba16f", 4e-3);
}

static double
flat_far(double x, double z, const void *user)
{
    (void)x, (void)z, (void)user;
    return 12345.5;
}

/* A flat height field (no height extent) 12 km up and 100 km out: every texel covered, at
 * its height exactly (the depth range must not collapse onto the near plane). */
static void
test_heightmap_flat_far(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    hf_scene s;
    hf_init(&s);
    hf_material(&s, 1, 0.5f, 0.25f);
    hf_grid(&s, 4, 1.0e5, -1.0e5, 500.0, flat_far, NULL);
    hf_finish(&s);
    vf_runner r;
    vf_run_format(&r, &s.scene, 16, 16, raster_graph, "rgba32f");
    int w = 0, h = 0;
    float *map = hf_read_2d(&r, "mip.lightmap", 0, &w, &h);
    for (int i = 0; i < w * h; i++)
        if (map[4 * i + 3] != 12345.5f || fabsf(map[4 * i] - 0.25f) > 1e-6f)
            fail_msg("texel %d: height %.4f radiance %g; expected 12345.5 and 0.25", i, map[4 * i + 3], map[4 * i]);
    free(map);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
}

static void
test_heightmap_culled_without_terrain(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    hf_scene s;
    hf_init(&s);
    const double c[3] = {0, 0, 0}, e1[3] = {1, 0, 0}, e2[3] = {0, 0, -1};
    hf_quad(&s, c, e1, e2);
    hf_finish(&s);
    vf_runner r;
    static const char json[] =
        "{ \"version\": 1, \"passes\": {"
        " \"hm\": { \"type\": \"heightmap_raster\", \"params\": { \"resolution\": 64 } },"
        " \"mip\": { \"type\": \"mip2d\", \"inputs\": { \"lightmap\": \"hm.lightmap\" } },"
        " \"gbuf\": { \"type\": \"gbuffer\" } },"
        " \"outputs\": [ \"gbuf.albedo\" ] }";
    vf_start(&r, &s.scene, 16, 16, json, NULL);
    assert_true(fg_pass_is_culled(fg_graph_find_pass(r.graph, "hm")));
    assert_true(fg_pass_is_culled(fg_graph_find_pass(r.graph, "mip")));
    vf_frame(&r);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
}

/* ------------------------------------------------------------------ hsat */

#define FAR_X 1.0e5
#define FAR_Z -1.0e5
#define FAR_Y 1.0e4
#define TERRAIN 2000.0

static double
bumpy(double x, double z, const void *user)
{
    (void)user;
    double u = (x - FAR_X) / TERRAIN, v = (z - FAR_Z) / TERRAIN;
    return FAR_Y + 40.0 * sin(9.0 * u) * cos(7.0 * v) + 25.0 * sin(23.0 * u + 5.0 * v) + 60.0 * u * v;
}

typedef struct hsat_stats {
    int queries;
    int below_max, above_min;   /* bound inside the true range (not conservative) */
    int off_blocks;             /* pyramid: differs from the brute-force range of its covering blocks */
    int beyond_pnorm;           /* SAT modes: max above the exact p-norm's limit N^(1/p) x max */
    double worst_beyond;        /* by how much at most (metres): the rounding margin's share */
    double worst_under_max;     /* largest (true max - bound) */
    double mean_over_max;       /* mean (bound - true max) */
    double worst_mean;          /* eq. 13's mean against brute force */
} hsat_stats;

static uint32_t
next_random(uint32_t *x)
{
    *x ^= *x << 13;
    *x ^= *x >> 17;
    *x ^= *x << 5;
    return *x;
}

static hsat_stats
run_hsat(cg_context *ctx, int resolution, const char *mode, GLuint query_program)
{
    hf_scene s;
    hf_init(&s);
    hf_material(&s, 1, 0.5f, 0.2f);
    hf_grid(&s, 96, FAR_X, FAR_Z, TERRAIN, bumpy, NULL);
    hf_finish(&s);
    char json[1024];
    snprintf(json, sizeof json,
             "{ \"version\": 1, \"passes\": {"
             " \"hm\": { \"type\": \"heightmap_raster\", \"params\": { \"resolution\": %d } },"
             " \"mip\": { \"type\": \"mip2d\", \"inputs\": { \"lightmap\": \"hm.lightmap\" } },"
             " \"hsat\": { \"type\": \"hsat\", \"params\": { \"mode\": \"%s\", \"p\": 16 },"
             "   \"inputs\": { \"lightmap\": \"mip.lightmap\", \"region\": \"hm.region\" } } },"
             " \"outputs\": [ \"hsat.table\", \"hsat.info\", \"hm.region\", \"mip.lightmap\" ] }",
             resolution, mode);
    vf_runner r;
    vf_start(&r, &s.scene, 16, 16, json, NULL);
    vf_frame(&r);
    bool pyramid = strcmp(mode, "pyramid") == 0;
    int levels = 0;
    for (int n = resolution; n >= 1; n /= 2)
        levels++;
    float **heights = calloc((size_t)levels, sizeof *heights);
    assert_non_null(heights);
    for (int l = 0; l < levels; l++) {
        int w = 0, h = 0;
        heights[l] = hf_read_2d(&r, "mip.lightmap", l, &w, &h);
    }
    const cg_mesh *mesh = &s.meshes[0];
    double x0 = mesh->bounds_min[0], z0 = mesh->bounds_min[2];
    double dx = (double)(mesh->bounds_max[0] - x0) / resolution, dz = (double)(mesh->bounds_max[2] - z0) / resolution;
    enum { QUERIES = 4096 };
    float *queries = calloc(QUERIES * 4, sizeof(float));
    int *query_levels = calloc(QUERIES, sizeof(int));
    int *rects = calloc(QUERIES * 4, sizeof(int));
    assert_true(queries && query_levels && rects);
    uint32_t seed = 12345u + (uint32_t)resolution;
    for (int q = 0; q < QUERIES; q++) {
        int l = pyramid ? 0 : (int)(next_random(&seed) % (uint32_t)(levels - 1));
        int n = resolution >> l;
        /* Widths from 1 texel to the whole map, small ones more often. */
        int max_w = 1 << (next_random(&seed) % (uint32_t)(levels - l));
        int i0 = (int)(next_random(&seed) % (uint32_t)n), j0 = (int)(next_random(&seed) % (uint32_t)n);
        int i1 = i0 + (int)(next_random(&seed) % (uint32_t)max_w), j1 = j0 + (int)(next_random(&seed) % (uint32_t)max_w);
        if (i1 >= n) i1 = n - 1;
        if (j1 >= n) j1 = n - 1;
        double sx = dx * (1 << l), sz = dz * (1 << l);
        /* A quarter texel inside the texel rectangle's edges: no rounding ambiguity. */
        queries[4 * q + 0] = (float)(x0 + (i0 + 0.25) * sx);
        queries[4 * q + 1] = (float)(z0 + (j0 + 0.25) * sz);
        queries[4 * q + 2] = (float)(x0 + (i1 + 0.75) * sx);
        queries[4 * q + 3] = (float)(z0 + (j1 + 0.75) * sz);
        query_levels[q] = l;
        rects[4 * q + 0] = i0, rects[4 * q + 1] = j0, rects[4 * q + 2] = i1, rects[4 * q + 3] = j1;
    }
    GLuint buffers[3];
    glCreateBuffers(3, buffers);
    glNamedBufferStorage(buffers[0], QUERIES * 4 * sizeof(float), queries, 0);
    glNamedBufferStorage(buffers[1], QUERIES * sizeof(int), query_levels, 0);
    glNamedBufferStorage(buffers[2], QUERIES * 4 * sizeof(float), NULL, GL_DYNAMIC_STORAGE_BIT);
    glUseProgram(query_program);
    glUniform1i(0, QUERIES);
    glBindBufferBase(GL_UNIFORM_BUFFER, 4, fg_graph_texture(r.graph, "hm.region"));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, fg_graph_texture(r.graph, "hsat.info"));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, buffers[1]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, buffers[2]);
    glBindTextureUnit(4, fg_graph_texture(r.graph, "hsat.table"));
    /* Integer textures are complete only with nearest filtering. */
    GLuint sampler = 0;
    glCreateSamplers(1, &sampler);
    glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindSampler(4, sampler);
    glDispatchCompute((QUERIES + 63) / 64, 1, 1);
    glBindSampler(4, 0);
    glDeleteSamplers(1, &sampler);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    float *results = calloc(QUERIES * 4, sizeof(float));
    assert_non_null(results);
    glGetNamedBufferSubData(buffers[2], 0, QUERIES * 4 * sizeof(float), results);
    glDeleteBuffers(3, buffers);
    glUseProgram(0);

    hsat_stats st = {.queries = QUERIES};
    for (int q = 0; q < QUERIES; q++) {
        int l = query_levels[q], n = resolution >> l;
        double lo = INFINITY, hi = -INFINITY, sum = 0;
        for (int j = rects[4 * q + 1]; j <= rects[4 * q + 3]; j++)
            for (int i = rects[4 * q + 0]; i <= rects[4 * q + 2]; i++) {
                double v = heights[l][4 * ((size_t)j * n + i) + 3];
                lo = fmin(lo, v);
                hi = fmax(hi, v);
                sum += v;
            }
        double mean = sum / ((rects[4 * q + 2] - rects[4 * q] + 1.0) * (rects[4 * q + 3] - rects[4 * q + 1] + 1.0));
        double got_lo = results[4 * q], got_hi = results[4 * q + 1];
        int i0 = rects[4 * q], j0 = rects[4 * q + 1], i1 = rects[4 * q + 2], j1 = rects[4 * q + 3];
        if (pyramid) {
            /* The pyramid reads the at most 2 x 2 blocks of level L = ceil(log2(span)) that cover
             * the rectangle: its answer is exactly the range over those blocks. */
            int span = (i1 - i0 > j1 - j0 ? i1 - i0 : j1 - j0) + 1, L = 0;
            while ((1 << L) < span && L < levels - 1)
                L++;
            int bi0 = (i0 >> L) << L, bj0 = (j0 >> L) << L;
            int bi1 = (((i1 >> L) + 1) << L) - 1, bj1 = (((j1 >> L) + 1) << L) - 1;
            double block_lo = INFINITY, block_hi = -INFINITY;
            for (int j = bj0; j <= bj1 && j < n; j++)
                for (int i = bi0; i <= bi1 && i < n; i++) {
                    double v = heights[0][4 * ((size_t)j * n + i) + 3];
                    block_lo = fmin(block_lo, v);
                    block_hi = fmax(block_hi, v);
                }
            st.off_blocks += (float)block_lo != (float)got_lo || (float)block_hi != (float)got_hi;
        } else {
            /* The un-normalised p-norm is at most N^(1/p) times the max (normalised heights). */
            const cg_mesh *tm = &s.meshes[0];
            double y0 = tm->bounds_min[1], range = tm->bounds_max[1] - tm->bounds_min[1];
            double count = (i1 - i0 + 1.0) * (j1 - j0 + 1.0);
            double limit = y0 + range * fmin(1.0, (hi - y0) / range * pow(count, 1.0 / 16.0)) + 1e-3;
            st.beyond_pnorm += got_hi > limit;
            st.worst_beyond = fmax(st.worst_beyond, got_hi - limit);
        }
        st.below_max += got_hi < hi;
        st.above_min += got_lo > lo;
        st.worst_under_max = fmax(st.worst_under_max, hi - got_hi);
        st.mean_over_max += (got_hi - hi) / QUERIES;
        if (!pyramid)
            st.worst_mean = fmax(st.worst_mean, fabs(results[4 * q + 2] - mean));
    }
    printf("# hsat %s %d^2 (heights %.0f m +- 100 m, 100 km from the origin): %d queries, max below truth %d times "
           "(worst %.4g m), min above truth %d times, mean max over-estimate %.4g m, eq. 13 mean worst error %.4g m\n",
           mode, resolution, FAR_Y, QUERIES, st.below_max, st.worst_under_max, st.above_min, st.mean_over_max,
           st.worst_mean);
    if (pyramid)
        printf("# hsat pyramid %d^2: %d of %d answers differ from the brute-force range of their covering blocks\n",
               resolution, st.off_blocks, QUERIES);
    else
        printf("# hsat %s %d^2: max above N^(1/p) x the true max (the exact p-norm's limit) %d times, by up to %.4g m "
               "(cancellation of tiny sums in the table; pnorm: and its margin for it)\n", mode, resolution, st.beyond_pnorm, st.worst_beyond);
    for (int l = 0; l < levels; l++)
        free(heights[l]);
    free(heights);
    free(queries);
    free(query_levels);
    free(rects);
    free(results);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
    return st;
}

static GLuint
test_program(const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "shaders/%s", name);
    GLuint program = 0;
    cg_error err = {0};
    assert_cg_ok(cg_program_compute(cg_test_data_path(path), NULL, &program, &err), &err);
    return program;
}

static void
test_hsat_against_brute_force(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = test_program("hsat_query.comp");
    const int sizes[2] = {256, 2048};
    for (int i = 0; i < 2; i++) {
        /* The exact pyramid: never inside the true range (no tolerance: it copies texels). */
        hsat_stats p = run_hsat(ctx, sizes[i], "pyramid", program);
        assert_int_equal(p.below_max, 0);
        assert_int_equal(p.above_min, 0);
        assert_int_equal(p.off_blocks, 0);
        /* The p-norm bound: never inside either, and eq. 13's mean to 1 mm on a 10 km high
         * terrain 100 km out (double tables; fp32 ones were 2.6 m off at 2048^2). */
        hsat_stats n = run_hsat(ctx, sizes[i], "pnorm", program);
        assert_int_equal(n.below_max, 0);
        assert_int_equal(n.above_min, 0);
        assert_true(n.worst_mean < 1e-3);
        /* Eq. 14 as written: below the true maximum, by metres. */
        hsat_stats m = run_hsat(ctx, sizes[i], "power_mean", program);
        assert_true(m.below_max > m.queries / 10);
        assert_true(m.worst_under_max > 1.0);
    }
    glDeleteProgram(program);
}

/* ------------------------------------------------------------------ fitting cube */

typedef struct cone_case {
    double v[3], half_angle, dis;
    bool eq11;
} cone_case;

static void
run_cubes(GLuint program, const cone_case *cases, int count, const double apex[3], float *out)
{
    float *in = calloc((size_t)count * 8, sizeof(float));
    assert_non_null(in);
    for (int i = 0; i < count; i++) {
        const cone_case *c = &cases[i];
        double len = sqrt(c->v[0] * c->v[0] + c->v[1] * c->v[1] + c->v[2] * c->v[2]);
        for (int k = 0; k < 3; k++)
            in[8 * i + k] = (float)(c->v[k] / len);
        in[8 * i + 3] = (float)c->half_angle;
        in[8 * i + 4] = (float)c->dis;
        in[8 * i + 5] = (float)(2.0 * c->dis * tan(c->half_angle));
        in[8 * i + 6] = c->eq11 ? 1.0f : 0.0f;
    }
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    glNamedBufferStorage(buffers[0], (GLsizeiptr)count * 8 * sizeof(float), in, 0);
    glNamedBufferStorage(buffers[1], (GLsizeiptr)count * 8 * sizeof(float), NULL, 0);
    glUseProgram(program);
    glUniform1i(0, count);
    glUniform3f(1, (float)apex[0], (float)apex[1], (float)apex[2]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, buffers[1]);
    glDispatchCompute((GLuint)(count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buffers[1], 0, (GLsizeiptr)count * 8 * sizeof(float), out);
    glDeleteBuffers(2, buffers);
    glUseProgram(0);
    free(in);
}

/* Distance of p along the unit axis v from the apex and from the axis. */
static void
axis_coordinates(const double apex[3], const double v[3], const double p[3], double *along, double *off)
{
    double d[3] = {p[0] - apex[0], p[1] - apex[1], p[2] - apex[2]};
    *along = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
    double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - *along * *along;
    *off = sqrt(fmax(r2, 0.0));
}

static void
test_fitting_cube(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = test_program("fitting_cube.comp");
    const double apex[3] = {3.0, -2.0, 7.0};
    enum { FIXED = 6, RANDOM = 2000 };
    cone_case *cases = calloc(FIXED + RANDOM, sizeof *cases);
    assert_non_null(cases);
    cases[0] = (cone_case){{1, 0, 0}, 0.3, 2.0, true};          /* axis-parallel: eq. 10 */
    cases[1] = (cone_case){{0, -1, 0}, 0.5, 1.0, true};         /* axis-parallel: eq. 10 */
    cases[2] = (cone_case){{0.6, 0.7, 0.39}, 0.05, 2.0, true};  /* generic (theta1 = 0.23): eq. 11 */
    cases[3] = (cone_case){{1, 1, 1}, 0.3, 2.0, true};          /* on a body diagonal: theta1 = 0 */
    cases[4] = (cone_case){{1, 0.9, 0.8}, 0.6, 2.0, true};      /* theta1 < theta/2: diagonal inside the cone */
    cases[5] = (cone_case){{0.6, 0.7, 0.39}, 0.3, 2.0, false};  /* eq. 10 forced */
    uint32_t seed = 99u;
    for (int i = FIXED; i < FIXED + RANDOM; i++) {
        cone_case *c = &cases[i];
        for (int k = 0; k < 3; k++)
            c->v[k] = (int)(next_random(&seed) % 2001u) / 1000.0 - 1.0;
        if (fabs(c->v[0]) + fabs(c->v[1]) + fabs(c->v[2]) < 1e-3)
            c->v[1] = 1.0;
        c->half_angle = 0.01 + 0.75 * (next_random(&seed) % 1000u) / 1000.0;   /* up to 44 degrees */
        c->dis = pow(10.0, -3.0 + 7.0 * (next_random(&seed) % 1000u) / 1000.0); /* 1 mm to 10 km */
        c->eq11 = true;
    }
    int count = FIXED + RANDOM;
    float *out = calloc((size_t)count * 8, sizeof(float));
    assert_non_null(out);
    run_cubes(program, cases, count, apex, out);
    int eq11_count = 0, fallback = 0;
    double worst_surface = 0;
    for (int i = 0; i < count; i++) {
        const cone_case *c = &cases[i];
        double v[3], len = sqrt(c->v[0] * c->v[0] + c->v[1] * c->v[1] + c->v[2] * c->v[2]);
        for (int k = 0; k < 3; k++)
            v[k] = c->v[k] / len;
        double d = 2.0 * c->dis * tan(c->half_angle);
        const float *o = &out[8 * i];
        int equation = (int)o[4];
        double side = o[3];
        for (int k = 0; k < 4; k++)
            if (!isfinite(o[k]))
                fail_msg("cone %d: non-finite cube", i);
        assert_true(side > 0.0);
        double centre[3] = {o[0], o[1], o[2]};
        double scale = c->dis + d + fabs(apex[0]) + fabs(apex[1]) + fabs(apex[2]);
        if (equation == 10) {
            /* Eq. 10: S = d / sqrt(2), T on the axis at dis + S/2. */
            assert_true(fabs(side - d / sqrt(2.0)) <= 1e-5 * d + 1e-7);
            for (int k = 0; k < 3; k++)
                assert_true(fabs(centre[k] - (apex[k] + v[k] * (c->dis + 0.5 * side))) <= 1e-5 * scale);
            fallback += c->eq11;
            continue;
        }
        assert_int_equal(equation, 11);
        eq11_count++;
        assert_true(c->eq11);
        assert_true(side <= 4.0 * d * (1 + 1e-5));
        /* Eq. 11: the body diagonal along f1 = sign(v)/sqrt(3) starts on the cross-section
         * circle at dis (radius d/2) and ends on the cone's surface. */
        double start[3], end[3];
        for (int k = 0; k < 3; k++) {
            double sgn = v[k] < 0 ? -1.0 : 1.0;
            start[k] = centre[k] - 0.5 * side * sgn;
            end[k] = centre[k] + 0.5 * side * sgn;
        }
        double along, off;
        axis_coordinates(apex, v, start, &along, &off);
        /* fp32 on the GPU: acos and the law of sines amplify rounding by 1/sin(theta1 - theta/2). */
        double tol = 5e-4 * (scale + side);
        if (fabs(along - c->dis) > tol || fabs(off - 0.5 * d) > tol)
            fail_msg("cone %d: eq. 11 diagonal starts at %g along, %g off; expected %g, %g", i, along, off, c->dis, 0.5 * d);
        axis_coordinates(apex, v, end, &along, &off);
        double surface = fabs(off - along * tan(c->half_angle));
        worst_surface = fmax(worst_surface, surface / scale);
        if (surface > tol)
            fail_msg("cone %d: eq. 11 diagonal ends %g off the cone's surface (v %g %g %g, half angle %g, dis %g, side %g, d %g, along %g off %g)", i, surface, v[0], v[1], v[2], c->half_angle, c->dis, side, d, along, off);
    }
    printf("# fitting cube: %d cones, %d by eq. 11, %d fell back to eq. 10 (axis-parallel, theta1 <= theta/2 "
           "or S > 4 d), worst surface miss %.3g of the scale\n", count, eq11_count, fallback, worst_surface);
    assert_int_equal((int)out[4], 10);
    assert_int_equal((int)out[8 + 4], 10);
    assert_int_equal((int)out[16 + 4], 11);
    assert_int_equal((int)out[24 + 4], 10);
    assert_int_equal((int)out[32 + 4], 10);
    assert_int_equal((int)out[40 + 4], 10);
    assert_true(eq11_count > RANDOM / 4);
    free(out);
    free(cases);
    glDeleteProgram(program);
    assert_no_gl_errors(ctx);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_heightmap_tilted_plane),
             cmocka_unit_test(test_heightmap_flat_far),
             cmocka_unit_test(test_heightmap_culled_without_terrain),
             cmocka_unit_test(test_hsat_against_brute_force),
             cmocka_unit_test(test_fitting_cube))
