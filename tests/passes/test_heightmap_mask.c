/* heightmap_raster and alphaMode MASK (glTF 3.9.4): below alphaCutoff a surface is not there, for
 * the 2D lightmap as for the G-buffer and the voxels. Two height-field quads 2 m above a flat
 * terrain under a sun straight down, no shadow map: one MASK with alpha 0.3 under its cutoff 0.5,
 * one MASK with alpha 0.7 over it. Under the first every texel holds the terrain's height (0) and
 * light (its albedo x E / pi), under the second the quad's (height 2, its own albedo), with
 * cache=true (geometry raster, relight) and cache=false (lit raster) alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cg/gl.h"
#include "hybrid_fixture.h"
#include "test_support.h"

#define RESOLUTION 64

static const char graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"hm\": { \"type\": \"heightmap_raster\", \"params\": { \"resolution\": %d, \"cache\": %s } } },"
    " \"outputs\": [ \"hm.lightmap\" ] }";

static void
make_scene(hf_scene *s)
{
    hf_init(s);
    hf_material(s, 1, 0.2f, 0.0f);
    hf_material(s, 2, 0.8f, 0.0f);
    hf_material(s, 3, 0.8f, 0.0f);
    hf_grid(s, 8, -4.0, -4.0, 8.0, hf_flat, NULL);
    const double masked[3] = {-3, 2, 1}, opaque[3] = {1, 2, 1}, e1[3] = {2, 0, 0}, e2[3] = {0, 0, -2};
    hf_quad(s, masked, e1, e2); /* material 2 */
    hf_quad(s, opaque, e1, e2); /* material 3 */
    for (int m = 1; m <= 2; m++)
        s->meshes[m].kind = CG_MESH_HEIGHTFIELD;
    for (int m = 2; m <= 3; m++) {
        s->materials[m].alpha_mode = CG_ALPHA_MASK;
        s->materials[m].alpha_cutoff = 0.5f;
    }
    s->materials[2].base_color[3] = 0.3f;
    s->materials[3].base_color[3] = 0.7f;
    const double down[3] = {0, -1, 0};
    hf_sun(s, down, 3.0f);
    hf_finish(s);
}

/* Worst |texel - expected| (rgb and height) over the texels whose centre lies inside
 * [x0, x1] x [z0, z1] by more than a texel. */
static double
worst_over(const float *map, double x0, double x1, double z0, double z1, double radiance, double height, int *count)
{
    /* The map spans the height fields' xz bounds, the terrain's [-4, 4]^2. */
    double texel = 8.0 / RESOLUTION, worst = 0.0;
    *count = 0;
    for (int j = 0; j < RESOLUTION; j++)
        for (int i = 0; i < RESOLUTION; i++) {
            double x = -4.0 + (i + 0.5) * texel, z = -4.0 + (j + 0.5) * texel;
            if (x < x0 + texel || x > x1 - texel || z < z0 + texel || z > z1 - texel)
                continue;
            const float *t = &map[4 * (j * RESOLUTION + i)];
            for (int k = 0; k < 3; k++)
                worst = fmax(worst, fabs(t[k] - radiance));
            worst = fmax(worst, fabs(t[3] - height));
            (*count)++;
        }
    return worst;
}

static void
test_mask_leaves_the_map(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    for (int cache = 0; cache <= 1; cache++) {
        hf_scene s;
        make_scene(&s);
        vf_runner r;
        vf_run_format(&r, &s.scene, 16, 16, graph, RESOLUTION, cache ? "true" : "false");
        int w = 0, h = 0;
        float *map = hf_read_2d(&r, "hm.lightmap", 0, &w, &h);
        assert_int_equal(w, RESOLUTION);
        assert_int_equal(h, RESOLUTION);
        double terrain = 0.2 * 3.0 / M_PI, quad = 0.8 * 3.0 / M_PI;
        int n_masked = 0, n_opaque = 0;
        double masked = worst_over(map, -3, -1, -1, 1, terrain, 0.0, &n_masked);
        double opaque = worst_over(map, 1, 3, -1, 1, quad, 2.0, &n_opaque);
        printf("# cache=%s: under the masked quad (alpha 0.3 < 0.5) worst |texel - terrain's| %.2g over %d "
               "texels; under the kept one (0.7) worst |texel - quad's| %.2g over %d\n",
               cache ? "true" : "false", masked, n_masked, opaque, n_opaque);
        assert_true(n_masked > 100 && n_opaque > 100);
        if (masked > 1e-3)
            fail_msg("cache=%d: texels under a MASK quad below its cutoff are %.3g off the terrain's "
                     "(height 0, radiance %.3f): the masked surface was written", cache, masked, terrain);
        if (opaque > 1e-3)
            fail_msg("cache=%d: texels under a MASK quad above its cutoff are %.3g off its own", cache, opaque);
        free(map);
        assert_no_gl_errors(ctx);
        vf_stop(&r);
        hf_free(&s);
    }
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_mask_leaves_the_map))
