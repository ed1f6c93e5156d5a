#include "sweep_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/scene.h"
#include "test_support.h"
#include "vct_fixture.h"

cg_image
sf_render(const char *source, const char *graph, const char *const *overrides, int width, int height)
{
    return sf_render_placed(source, 1.0, 0.0, graph, overrides, width, height);
}

/* Moves the whole scene by d along each axis. */
static void
move_scene(cg_scene *s, double d)
{
    for (int i = 0; i < s->instance_count; i++)
        for (int r = 0; r < 3; r++)
            s->instances[i].world[12 + r] = (float)(s->instances[i].world[12 + r] + d);
    for (int i = 0; i < s->light_count; i++)
        for (int r = 0; r < 3; r++)
            s->lights[i].position[r] = (float)(s->lights[i].position[r] + d);
    for (int i = 0; i < s->camera_count; i++)
        for (int r = 0; r < 3; r++)
            s->cameras[i].world[12 + r] = (float)(s->cameras[i].world[12 + r] + d);
    cg_scene_compute_bounds(s);
}

static bool
scene_emits(const cg_scene *s)
{
    for (int i = 0; i < s->material_count; i++)
        if (s->materials[i].emissive_strength > 0.0f &&
            (s->materials[i].emissive[0] > 0.0f || s->materials[i].emissive[1] > 0.0f || s->materials[i].emissive[2] > 0.0f))
            return true;
    return false;
}

cg_image
sf_render_placed(const char *source, double scale, double offset, const char *graph, const char *const *overrides,
                 int width, int height)
{
    cg_scene scene;
    cg_error err = {0};
    assert_cg_ok(cg_scene_load(source, &scene, &err), &err);
    if (scale != 1.0)
        cg_test_scale_scene(&scene, scale);
    if (offset != 0.0)
        move_scene(&scene, offset);
    char file[300];
    snprintf(file, sizeof file, "%s.json", graph);
    /* vct.json's and hybrid.json's voxel_light count bounces as path_trace does, so where the
     * scene emits (the furnace) their one bounce is a gather at every occupied voxel (40 s at 128^3
     * and 16 cones; hybrid.json's box at 128 is as fine): one cone per such gather keeps that path,
     * scaled like the rest, at a sixteenth of the cost. */
    /* And their volumes at 64^3, not 128^3: what these sweeps check (the same image at every
     * scale, placement and radiance range) does not depend on the voxels' count, and at 64^3 a
     * frame of voxel_light costs an eighth (scale_sweep 61 -> 20 s, radiance_range 55 -> 18 s). */
    const char *with_bounce[18];
    if (!strcmp(graph, "vct") || !strcmp(graph, "hybrid")) {
        int n = 0;
        for (; n < 15 && overrides && overrides[n]; n++)
            with_bounce[n] = overrides[n];
        with_bounce[n++] = "vox.resolution=64";
        if (scene_emits(&scene))
            with_bounce[n++] = "light.bounce_cones=1";
        with_bounce[n] = NULL;
        overrides = with_bounce;
    }
    vf_runner r;
    vf_start_file(&r, &scene, width, height, file, overrides);
    vf_frame(&r);
    GLuint hdr = fg_graph_texture(r.graph, "final.hdr");
    assert_true(hdr != 0);
    cg_image img = {0};
    img.rgba = cg_test_read_texture(hdr, 0, &img.width, &img.height, NULL);
    vf_stop(&r);
    cg_scene_free(&scene);
    return img;
}

size_t
sf_nonfinite(const cg_image *img)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)img->width * (size_t)img->height; i++)
        for (int c = 0; c < 3; c++)
            n += !isfinite(img->rgba[4 * i + c]);
    return n;
}

cg_metrics
sf_compare(const cg_image *test, const cg_image *ref, double divide)
{
    cg_image scaled = {0};
    cg_error err = {0};
    assert_cg_ok(cg_image_alloc(&scaled, test->width, test->height, &err), &err);
    for (size_t i = 0; i < (size_t)test->width * (size_t)test->height * 4; i++)
        scaled.rgba[i] = (float)(test->rgba[i] / divide);
    cg_metrics m;
    assert_cg_ok(cg_metrics_compute(&scaled, ref, &m, &err), &err);
    cg_image_free(&scaled);
    return m;
}

bool
sf_level_runs(int i, int count, int unit)
{
    const char *sweep = getenv("CONEGRAPH_SWEEP");
    bool extremes = sweep && !strcmp(sweep, "extremes");
    if (sweep && *sweep && !extremes && strcmp(sweep, "all"))
        fail_msg("CONEGRAPH_SWEEP is '%s'; expected 'all' or 'extremes'", sweep);
    return !extremes || i == 0 || i == count - 1 || i == unit;
}
