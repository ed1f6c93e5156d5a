/* voxel_light's bounce_spacing (shaders/voxel_light/spacing.glsl): with S > 1 one voxel of each S^3
 * block traces the gathers at the voxels and the others mix its light where their surfaces agree.
 *   - A closed box under a uniform sky, no light: in truth every voxel's outer side has the same
 *     light (its whole sky open) and its inner side none. Mixing must be no farther from that than
 *     tracing at every voxel (whose edges see their own faces, and whose inner cones leak): a weight
 *     that does not sum to 1, or a side taken for the other, fails it. Edges and corners, whose mean
 *     normals lie between two or three faces, mix too: only the representatives trace.
 *   - A shelf over a floor: the plane test keeps the shelf's light off the floor beneath it.
 *   - A small town (terrain, a wall, a roof) under a sun and a sky, two bounces: the light of the
 *     volumes stays within 1% of bounce_spacing 1's (summed), while far fewer voxels trace.
 *   - A terrain folded steeply at 32^3, more occupied voxels than the list holds: every voxel still
 *     gathers (over the whole volume).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hybrid_fixture.h"
#include "test_support.h"
#include "vct_fixture.h"

static const char graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"shadow\": { \"type\": \"shadow_map\", \"params\": { \"resolution\": 256 } },"
    " \"vox\": { \"type\": \"voxelize\", \"params\": { \"model\": \"surface\", \"resolution\": %d } },"
    " \"light\": { \"type\": \"voxel_light\","
    "   \"params\": { \"bounces\": %d, \"bounce_cones\": 6, \"bounce_spacing\": %d },"
    "   \"inputs\": { \"albedo\": \"vox.albedo\", \"coverage\": \"vox.coverage\", \"normal\": \"vox.normal\","
    "     \"emission\": \"vox.emission\", \"region\": \"vox.region\","
    "     \"shadow\": \"shadow.depth\", \"shadow_matrix\": \"shadow.matrix\" } } },"
    " \"outputs\": [ \"light.radiance\", \"light.sides\", \"light.normals\" ] }";

/* A uniform sky of radiance (r, g, b) over the scene. */
static void
set_sky(cg_scene *scene, float r, float g, float b)
{
    cg_error err = {0};
    cg_sky sky = {.type = CG_SKY_UNIFORM, .radiance = {r, g, b}};
    assert_cg_ok(cg_scene_set_sky(scene, &sky, &err), &err);
}

/* The number in voxel_light's report "N gather(s) of M voxels": M, the voxels that traced. */
static unsigned
traced_voxels(const vf_runner *r)
{
    const char *at = strstr(vf_rebuilt(r, "light"), " of ");
    if (!at)
        fail_msg("voxel_light reported \"%s\", without the voxels it gathered at", vf_rebuilt(r, "light"));
    return (unsigned)strtoul(at + 4, NULL, 10);
}

/* The lit side's radiance (rgb / w) of level 0, and the other side's (beta times it), of the two
 * runners compared voxel by voxel: the largest difference relative to the voxel's radiance, and the
 * summed absolute difference over the summed radiance. */
typedef struct light_difference {
    double worst, total;
    int occupied;
} light_difference;

static light_difference
compare_light(const vf_runner *a, const vf_runner *b)
{
    int na = 0, nb = 0;
    float *ra = vf_read_volume(a, "light.radiance", 0, &na), *rb = vf_read_volume(b, "light.radiance", 0, &nb);
    float *sa = vf_read_volume(a, "light.sides", 0, &na), *sb = vf_read_volume(b, "light.sides", 0, &nb);
    assert_int_equal(na, nb);
    light_difference d = {0};
    double sum = 0.0, diff = 0.0;
    for (size_t i = 0; i < (size_t)na * na * na; i++) {
        float wa = ra[4 * i + 3], wb = rb[4 * i + 3];
        assert_true(wa == wb);  /* the same geometry */
        if (wa <= 0.0f)
            continue;
        d.occupied++;
        for (int c = 0; c < 3; c++) {
            /* Each side's radiance: lit = rgb / w, other = beta lit; the sides may swap which is lit,
             * so the two are compared as the brighter and the dimmer. */
            double la = ra[4 * i + c] / wa, lb = rb[4 * i + c] / wb;
            double oa = la * sa[4 * i] / wa, ob = lb * sb[4 * i] / wb;
            double pairs[2][2] = {{la, lb}, {oa, ob}};
            for (int p = 0; p < 2; p++) {
                double e = fabs(pairs[p][0] - pairs[p][1]);
                sum += pairs[p][0];
                diff += e;
                if (pairs[p][0] > 0.0)
                    d.worst = fmax(d.worst, e / pairs[p][0]);
            }
        }
    }
    d.total = diff / sum;
    free(ra);
    free(rb);
    free(sa);
    free(sb);
    return d;
}

/* A closed box under a uniform sky of radiance L, no light, one bounce: every voxel's outer side
 * sees the whole open sky (G = L) and its inner side nothing (G = 0), so its light is rho L outside
 * and 0 inside, the same at every voxel. How far a run is from that: the outer side's largest
 * deviation from the median voxel's (relative), and the inner side's mean over the outer side's
 * (the cones' leak through the walls). */
typedef struct box_error {
    double outer, inner;
} box_error;

static int
compare_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static box_error
box_light_error(const vf_runner *r)
{
    int n = 0;
    float *radiance = vf_read_volume(r, "light.radiance", 0, &n), *sides = vf_read_volume(r, "light.sides", 0, &n);
    size_t voxels = (size_t)n * n * n, occupied = 0;
    float *outer = malloc(sizeof(float) * voxels);
    assert_non_null(outer);
    double inner = 0.0, outer_sum = 0.0;
    for (size_t i = 0; i < voxels; i++) {
        float w = radiance[4 * i + 3];
        if (w <= 0.0f)
            continue;
        outer[occupied++] = radiance[4 * i] / w;
        outer_sum += radiance[4 * i] / w;
        inner += radiance[4 * i] / w * sides[4 * i] / w;
    }
    qsort(outer, occupied, sizeof *outer, compare_float);
    double median = outer[occupied / 2];
    box_error e = {fmax(median - outer[0], outer[occupied - 1] - median) / median, inner / outer_sum};
    free(outer);
    free(radiance);
    free(sides);
    return e;
}

static void
add_quad(vf_scene *s, const double o[3], const double e1[3], const double e2[3])
{
    double b[3], c[3], d[3];
    for (int k = 0; k < 3; k++) {
        b[k] = o[k] + e1[k];
        c[k] = o[k] + e1[k] + e2[k];
        d[k] = o[k] + e2[k];
    }
    vf_add_triangle(s, o, b, c);
    vf_add_triangle(s, o, c, d);
}

static void
test_closed_box_under_sky(void **state)
{
    (void)state;
    vf_scene box;
    vf_scene_init(&box, 0.7f, 0.0f);
    const double x[3] = {1.4, 0, 0}, y[3] = {0, 1.4, 0}, z[3] = {0, 0, 1.4};
    const double o[3] = {-0.7, -0.7, -0.7}, ox[3] = {0.7, -0.7, -0.7}, oy[3] = {-0.7, 0.7, -0.7},
                 oz[3] = {-0.7, -0.7, 0.7};
    add_quad(&box, o, y, x);
    add_quad(&box, oz, x, y);
    add_quad(&box, o, x, z);
    add_quad(&box, oy, z, x);
    add_quad(&box, o, z, y);
    add_quad(&box, ox, y, z);
    vf_finish(&box);
    set_sky(&box.scene, 0.5f, 0.5f, 0.5f);
    vf_runner every, spaced;
    vf_run_format(&every, &box.scene, 16, 16, graph, 32, 1, 1);
    vf_run_format(&spaced, &box.scene, 16, 16, graph, 32, 1, 4);
    unsigned all = traced_voxels(&every), few = traced_voxels(&spaced);
    box_error e_every = box_light_error(&every), e_spaced = box_light_error(&spaced);
    printf("# closed box under a sky, 32^3: bounce_spacing 4 traces %u of %u voxels; outer side within %.2e of "
           "the median voxel (spacing 1: %.2e), inner side %.2e of the outer (spacing 1: %.2e; both are 0 in truth)\n",
           few, all, e_spaced.outer, e_every.outer, e_spaced.inner, e_every.inner);
    /* 8^3 blocks; a face's two layers of voxels share its blocks: about 6 * 8^2 representatives. */
    assert_true(few * 8 < all);
    /* The texture reads count the voxels that traced, one gather each, and fall with them; a second,
     * still frame relights nothing and reads nothing. */
    double traced_every, traced_spaced;
    double reads_every = vf_reads(&every, "light", "voxel", &traced_every), reads_spaced = vf_reads(&spaced, "light", "voxel", &traced_spaced);
    printf("# texture reads: %.0f for %.0f voxels at spacing 1, %.0f for %.0f at 4\n", reads_every, traced_every,
           reads_spaced, traced_spaced);
    assert_true(traced_every == all && traced_spaced == few);
    assert_true(reads_spaced * 4 < reads_every && reads_spaced > traced_spaced);
    vf_next_frame(&spaced);
    assert_true(vf_reads(&spaced, "light", "voxel", &traced_spaced) == 0.0 && traced_spaced == 0.0);
    /* Mixing the faces' light is no farther from the truth than tracing at every voxel. */
    assert_true(e_spaced.outer <= fmax(e_every.outer, 2e-3));
    assert_true(e_spaced.inner <= e_every.inner);
    vf_stop(&every);
    vf_stop(&spaced);
}

static void
test_town_close_to_every_voxel(void **state)
{
    (void)state;
    hf_scene town;
    hf_town(&town, 8, 0.0f);
    const double sun[3] = {0.4, -1.0, 0.3};
    hf_sun(&town, sun, 3.0f);
    hf_finish(&town);
    set_sky(&town.scene, 0.3f, 0.35f, 0.4f);
    vf_runner every;
    vf_run_format(&every, &town.scene, 16, 16, graph, 64, 2, 1);
    unsigned all = traced_voxels(&every);
    static const int spacings[2] = {2, 4};
    for (int i = 0; i < 2; i++) {
        vf_runner spaced;
        vf_run_format(&spaced, &town.scene, 16, 16, graph, 64, 2, spacings[i]);
        unsigned few = traced_voxels(&spaced);
        light_difference d = compare_light(&every, &spaced);
        printf("# town, sun and sky, 2 bounces, 64^3: bounce_spacing %d traces %u of %u voxels; light of %d voxels "
               "%.4f (total) from spacing 1's, worst voxel %.3f\n", spacings[i], few, all, d.occupied, d.total,
               d.worst);
        assert_true(few * (unsigned)spacings[i] < all);
        assert_true(d.total < 0.02);
        vf_stop(&spaced);
    }
    vf_stop(&every);
    hf_free(&town);
}

/* A shelf three voxels above a floor, both facing up, under a sky: the floor beneath it sees the
 * shelf's underside, not the sky, and must not take the light of the shelf's top, which is a block
 * away at bounce_spacing 4 and faces the same way: the plane test tells them apart (with a tolerance
 * of 4 voxels the floor came out 1.08 times as bright). The upper side of the floor's voxels under
 * the middle metre of the shelf is compared with bounce_spacing 1's. */
static void
test_shelf_over_floor(void **state)
{
    (void)state;
    hf_scene s;
    hf_init(&s);
    hf_material(&s, 1, 0.5f, 0.0f);
    hf_material(&s, 2, 0.5f, 0.0f);
    hf_grid(&s, 4, -4.0, -4.0, 8.0, hf_flat, NULL);
    /* 32 voxels over 8 m: 0.25 m each; the shelf 0.75 m up, 4 m square, facing up (e2 x e1). */
    const double shelf[3] = {-2.0, 0.75, -2.0}, e1[3] = {4.0, 0.0, 0.0}, e2[3] = {0.0, 0.0, 4.0};
    hf_quad(&s, shelf, e2, e1);
    hf_finish(&s);
    set_sky(&s.scene, 0.5f, 0.5f, 0.5f);
    vf_runner every, spaced;
    vf_run_format(&every, &s.scene, 16, 16, graph, 32, 1, 1);
    vf_run_format(&spaced, &s.scene, 16, 16, graph, 32, 1, 4);
    int n = 0;
    float *ra = vf_read_volume(&every, "light.radiance", 0, &n), *rb = vf_read_volume(&spaced, "light.radiance", 0, &n);
    float *sa = vf_read_volume(&every, "light.sides", 0, &n), *sb = vf_read_volume(&spaced, "light.sides", 0, &n);
    float *na = vf_read_volume(&every, "light.normals", 0, &n), *nb = vf_read_volume(&spaced, "light.normals", 0, &n);
    /* The upper side's light of the horizontal voxels under the shelf's middle metre: the floor's (the
     * lower layers: the volume's cube is centred on the scene, the floor at y = 14, the shelf at 17). */
    double sum_a = 0.0, sum_b = 0.0, top_a = 0.0;
    int floor = 0, top = 0;
    for (int z = 14; z < 18; z++)
        for (int y = 0; y < n; y++)
            for (int x = 14; x < 18; x++) {
                size_t i = (size_t)x + (size_t)n * ((size_t)y + (size_t)n * (size_t)z);
                float w = ra[4 * i + 3];
                if (w <= 0.0f || fabsf(na[4 * i + 1]) < 0.9f * w)
                    continue;   /* empty, or not a horizontal surface */
                /* The lit side is the one `normals` points to; the other has beta times its light. */
                double up_a = ra[4 * i] / w * (na[4 * i + 1] > 0.0f ? 1.0 : sa[4 * i] / w);
                double up_b = rb[4 * i] / w * (nb[4 * i + 1] > 0.0f ? 1.0 : sb[4 * i] / w);
                if (y < n / 2 - 1) {
                    sum_a += up_a;
                    sum_b += up_b;
                    floor++;
                } else {
                    top_a += up_a;
                    top++;
                }
            }
    assert_true(floor > 0 && top > 0);
    printf("# shelf over a floor under a sky, 32^3: the floor's %d voxels under the shelf at %.4f of spacing 1's "
           "(the shelf's %d voxels: %.1f times the floor's light)\n", floor, sum_b / sum_a, top,
           (top_a / top) / (sum_a / floor));
    assert_true(fabs(sum_b / sum_a - 1.0) < 0.05);
    free(ra);
    free(rb);
    free(sa);
    free(sb);
    free(na);
    free(nb);
    vf_stop(&every);
    vf_stop(&spaced);
    hf_free(&s);
}

/* A terrain folded steeply across a 32^3 volume: 13 524 occupied voxels, more than the list of
 * occupied voxels holds at 32^3 (12 288, the volume's boundary two voxels thick). The gathers then run
 * over the whole volume; over the list alone, a voxel past its end kept no gathered light. Under a sky
 * and no light, the columns' top voxels: black at 21.5% of them with every voxel gathering (the cones
 * close over a fold's crest; the same share, 21.8%, where the folds are lower and the list holds every
 * voxel), at 31.6% when the gathers ran over the list alone. */
static double
folds(double x, double z, const void *user)
{
    (void)z;
    (void)user;
    return 3.5 * sin(6.0 * x);
}

static void
test_list_overflow(void **state)
{
    (void)state;
    hf_scene s;
    hf_init(&s);
    hf_material(&s, 1, 0.5f, 0.0f);
    hf_grid(&s, 96, -3.9, -3.9, 7.8, folds, NULL);
    hf_finish(&s);
    set_sky(&s.scene, 0.5f, 0.5f, 0.5f);
    for (int spacing = 1; spacing <= 4; spacing *= 4) {
        vf_runner r;
        vf_run_format(&r, &s.scene, 16, 16, graph, 32, 1, spacing);
        unsigned listed = traced_voxels(&r);
        int n = 0;
        float *radiance = vf_read_volume(&r, "light.radiance", 0, &n);
        float *normals = vf_read_volume(&r, "light.normals", 0, &n);
        /* Each column's highest occupied voxel with a side to gather on (y up). */
        int tops = 0, black = 0;
        for (int z = 0; z < n; z++)
            for (int x = 0; x < n; x++)
                for (int y = n - 1; y >= 0; y--) {
                    size_t i = (size_t)x + (size_t)n * ((size_t)y + (size_t)n * (size_t)z);
                    float w = radiance[4 * i + 3];
                    float nl = sqrtf(normals[4 * i] * normals[4 * i] + normals[4 * i + 1] * normals[4 * i + 1] +
                                     normals[4 * i + 2] * normals[4 * i + 2]);
                    if (w <= 0.0f || nl < 0.1f * w)
                        continue;
                    tops++;
                    black += radiance[4 * i] == 0.0f;
                    break;
                }
        printf("# folded terrain, sky only, 32^3, bounce_spacing %d: %u voxels gathered at (more than the list's "
               "12288), %d of the %d columns' top voxels left black\n", spacing, listed, black, tops);
        assert_true(listed > 12288);
        assert_true(tops > 0);
        assert_true(black < tops / 4);
        free(radiance);
        free(normals);
        vf_stop(&r);
    }
    hf_free(&s);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_closed_box_under_sky),
             cmocka_unit_test(test_shelf_over_floor),
             cmocka_unit_test(test_list_overflow),
             cmocka_unit_test(test_town_close_to_every_voxel))
