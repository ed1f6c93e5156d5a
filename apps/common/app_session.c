/* One graph run on one scene: see app_session.h. */
#include "app_session.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "app_registry.h"
#include "cg/camera.h"
#include "cg/graphfile.h"

/* Fails with err prefixed by where: the one exit of every function below. */
static bool
failed(cg_error *err, const char *what)
{
    app_error_prefix(err, what);
    return false;
}

/* "sun (3 W/m^2 ...)" of the default light, for the notices. */
static void
describe_default_sun(char *out, size_t size)
{
    cg_light sun;
    cg_default_sun(&sun);
    snprintf(out, size, "a sun (%g W/m^2, white, %g degrees above the horizon, %g degrees from +z towards +x: "
             "direction [%.3f %.3f %.3f])", (double)sun.intensity, CG_DEFAULT_SUN_ELEVATION_DEG,
             CG_DEFAULT_SUN_AZIMUTH_DEG, (double)sun.direction[0], (double)sun.direction[1],
             (double)sun.direction[2]);
}

static bool
has_directional_light(const cg_scene *scene)
{
    for (int i = 0; i < scene->light_count; i++)
        if (scene->lights[i].type == CG_LIGHT_DIRECTIONAL)
            return true;
    return false;
}

bool
app_light_scene(const char *tool, cg_scene *scene, const cg_sky *sky, const char *origin, bool no_default_light,
                cg_error *err)
{
    if (!tool)
        tool = "conegraph";
    cg_sky none = { .type = CG_SKY_NONE };
    if (!sky)
        sky = &none;
    char sun[256], text[128];
    describe_default_sun(sun, sizeof sun);
    /* A black sky (none, 0) lights nothing: the default light then replaces it. */
    bool lit = !cg_sky_is_black(sky) || cg_scene_is_lit(scene);
    if (!lit && !no_default_light) {
        cg_sky fallback;
        cg_default_sky(&fallback);
        if (!cg_scene_add_default_sun(scene, err) || !cg_scene_set_sky(scene, &fallback, err))
            return false;
        cg_sky_format(&fallback, text, sizeof text);
        char why[256] = "has no light";
        if (cg_scene_emits(scene))
            snprintf(why, sizeof why, "has no light but emissive surfaces too small or faint to light it (%.3g "
                     "W/(m^2 sr) spread over its surfaces, below %.3g)", cg_scene_emitted_light(scene),
                     CG_EMITTERS_MIN_LIGHT);
        fprintf(stderr, "%s: scene %s %s: added %s and a uniform sky (%s W/(m^2 sr)); "
                "--no-default-light turns this off\n", tool, scene->name, why, sun, text);
        return true;
    }
    if (sky->type == CG_SKY_PREETHAM && !has_directional_light(scene) && !no_default_light) {
        if (!cg_scene_add_default_sun(scene, err))
            return false;
        fprintf(stderr, "%s: scene %s has no directional light for the Preetham sky (%s) to follow: added %s; "
                "--no-default-light turns this off\n", tool, scene->name, origin ? origin : "--sky", sun);
    }
    if (!cg_scene_set_sky(scene, sky, err)) {
        if (origin)
            app_error_prefix(err, origin);
        return false;
    }
    if (!cg_scene_is_lit(scene))
        fprintf(stderr, "%s: warning: scene %s has no light, no sky and no emissive surface that could "
                "light it, and --no-default-light keeps it so: the image will be %s\n", tool, scene->name,
                cg_scene_emits(scene) ? "black but for the emitters" : "black");
    return true;
}

/* The first graph settles the lighting; a later one may not ask for another sky. */
static bool
settle_lighting(app_session *s, cg_error *err)
{
    cg_sky asked;
    bool graph_asks = fg_graph_file_sky(s->graph, &asked);
    char text[2][128];
    if (s->lighting_settled) {
        if (s->sky_given || !graph_asks || cg_sky_equal(&asked, &s->sky_requested))
            return true;
        cg_sky_format(&asked, text[0], sizeof text[0]);
        cg_sky_format(&s->sky_requested, text[1], sizeof text[1]);
        return cg_fail(err, CG_ERR_USAGE,
                       "%s asks for the sky %s, but the scene's sky is %s (%s): a scene is lit once, and every "
                       "graph run on it sees the same light; give --sky to choose one for all",
                       s->graph_path, text[0], text[1], s->sky_origin);
    }
    if (!s->sky_given && graph_asks) {
        s->sky_requested = asked;
        snprintf(s->sky_origin, sizeof s->sky_origin, "\"sky\" of %s", s->graph_path);
    } else if (!s->sky_given) {
        snprintf(s->sky_origin, sizeof s->sky_origin, "no --sky and no \"sky\" in %s", s->graph_path);
    }
    if (!app_light_scene(s->tool, &s->scene, &s->sky_requested, s->sky_origin, s->no_default_light, err))
        return false;
    s->lighting_settled = true;
    return true;
}

bool
app_session_open(app_session *s, const app_session_desc *desc, cg_error *err)
{
    memset(s, 0, sizeof *s);
    s->tool = desc->tool ? desc->tool : "conegraph";
    s->scene_source = desc->scene;
    s->compile = desc->compile;
    s->no_default_light = desc->no_default_light;
    s->sky_given = desc->sky != NULL;
    if (desc->sky) {
        s->sky_requested = *desc->sky;
        snprintf(s->sky_origin, sizeof s->sky_origin, "--sky");
    }
    if (!cg_scene_load(desc->scene, &s->scene, err))
        return failed(err, "scene");
    s->scene_loaded = true;
    if (!cg_camera_select(&s->scene, desc->camera, &s->camera, err)) {
        app_session_close(s);
        return failed(err, "camera");
    }
    s->view_spec = (cg_view_spec){ .camera = s->camera, .from_given = desc->from_given,
                                   .look_at_given = desc->look_at_given, .yfov = desc->yfov };
    memcpy(s->view_spec.from, desc->from, sizeof s->view_spec.from);
    memcpy(s->view_spec.look_at, desc->look_at, sizeof s->view_spec.look_at);
    if (!cg_view_spec_check(&s->scene, &s->view_spec, err)) {
        app_session_close(s);
        return failed(err, "camera");
    }
    char note[1024];
    if (cg_view_aspect_note(&s->scene, &s->view_spec, desc->width, desc->height, note, sizeof note))
        fprintf(stderr, "%s: %s\n", s->tool, note);
    s->registry = app_registry_create(desc->plugins, desc->plugin_count, err);
    if (!s->registry) {
        app_session_close(s);
        return failed(err, "passes");
    }
    s->frame = (fg_frame){ .scene = &s->scene, .width = desc->width, .height = desc->height };
    cg_view_from_spec(&s->scene, &s->view_spec, desc->width, desc->height, &s->frame.view);
    return true;
}

/* The graph output whose output name is `suffix` ("hdr", "ldr"), or NULL. */
static const char *
find_output(const fg_graph *graph, const char *suffix)
{
    for (int i = 0; i < fg_graph_output_count(graph); i++) {
        const char *name = fg_graph_output_at(graph, i);
        const char *dot = strrchr(name, '.');
        if (dot && !strcmp(dot + 1, suffix))
            return name;
    }
    return NULL;
}

static bool
is_output(const fg_graph *graph, const char *source)
{
    for (int i = 0; i < fg_graph_output_count(graph); i++)
        if (!strcmp(fg_graph_output_at(graph, i), source))
            return true;
    return false;
}

bool
app_session_load_graph(app_session *s, const app_graph_desc *desc, cg_error *err)
{
    if (s->graph)
        fg_graph_destroy(s->graph);
    s->image_source = NULL;
    s->reads = desc->reads;
    s->read_count = desc->read_count;
    if (!app_resolve_graph(desc->graph, s->graph_path, sizeof s->graph_path, err))
        return false; /* the message names the graph file: no prefix */
    s->graph = fg_graph_create(s->registry);
    if (!s->graph) {
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory", s->graph_path);
        return failed(err, "graph");
    }
    if (!fg_graph_load_file(s->graph, s->graph_path, err))
        return failed(err, "graph");
    if (!settle_lighting(s, err))
        return failed(err, "sky");
    for (int i = 0; i < desc->set_count; i++)
        if (!fg_graph_apply_override(s->graph, desc->sets[i], err))
            return failed(err, "graph");
    s->interactive[0] = '\0';
    if (desc->interactive && !fg_graph_apply_interactive(s->graph, s->interactive, sizeof s->interactive, err))
        return failed(err, "graph");
    bool added;
    for (int i = 0; i < desc->read_count; i++)
        if (!app_session_mark_output(s, desc->reads[i], &added, err))
            return failed(err, "graph");
    if (desc->image) {
        s->image_source = find_output(s->graph, desc->image);
        if (!s->image_source) {
            cg_fail(err, CG_ERR_GRAPH_NO_OUTPUT, "%s: the graph marks no output named *.%s", s->graph_path,
                    desc->image);
            return failed(err, "graph");
        }
    }
    return true;
}

/* Everything to be read back must be a texture that this scene produces (a pass with nothing
 * to do leaves its outputs absent): known after a compile, before anything runs. */
static bool
check_reads(const app_session *s, cg_error *err)
{
    for (int i = s->image_source ? -1 : 0; i < s->read_count; i++) {
        const char *source = i < 0 ? s->image_source : s->reads[i];
        const fg_resource_info *info = fg_graph_find_resource(s->graph, source);
        char pass_name[256];
        snprintf(pass_name, sizeof pass_name, "%.*s", (int)strcspn(source, "."), source);
        const fg_pass *pass = fg_graph_find_pass(s->graph, pass_name);
        if ((!info || info->absent) && pass && fg_pass_is_culled(pass))
            return cg_fail(err, CG_ERR_USAGE, "%s: absent for scene '%s' (pass '%s': %s), so it cannot be read "
                           "back", source, s->scene_source, pass_name, fg_pass_cull_reason(pass));
        if (!info || info->absent)
            return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%s: no such resource", source);
        if (info->desc.kind == FG_BUFFER)
            return cg_fail(err, CG_ERR_USAGE, "%s: a buffer; only textures can be read back as images", source);
    }
    return true;
}

bool
app_session_check(app_session *s, cg_error *err)
{
    fg_frame frame = s->frame;
    frame.gpu_scene = NULL;
    if (!fg_graph_compile(s->graph, &frame, &s->compile, err) || !check_reads(s, err))
        return failed(err, "graph");
    return true;
}

bool
app_session_start_gl(app_session *s, const cg_context_desc *context, cg_error *err)
{
    if (!cg_context_create(context, &s->ctx, err))
        return failed(err, context->backend == CG_CONTEXT_GLFW ? "window" : "GL context");
    if (!cg_gpu_scene_upload(&s->scene, &s->gpu, err))
        return failed(err, "scene upload");
    s->uploaded = true;
    s->frame.gpu_scene = &s->gpu;
    return true;
}

bool
app_session_compile(app_session *s, cg_error *err)
{
    if (!fg_graph_compile(s->graph, &s->frame, &s->compile, err) || !check_reads(s, err))
        return failed(err, "graph");
    if (!fg_graph_prepare(s->graph, err))
        return failed(err, "prepare");
    return true;
}

bool
app_session_set_time(app_session *s, double t, cg_scene_changes *changes, cg_error *err)
{
    cg_scene_changes local;
    cg_scene_evaluate(&s->scene, t, &local);
    if (changes)
        *changes = local;
    if (local.lights && s->uploaded && !cg_gpu_scene_update_lights(&s->gpu, err))
        return failed(err, "frame");
    /* A skin posed its meshes on the CPU (core/scene/animation.c says why): their vertices go
     * to the GPU again, under a new upload generation that the caching passes see. */
    if (local.meshes_deformed && s->uploaded && !cg_gpu_scene_update_meshes(&s->gpu, NULL, err))
        return failed(err, "frame");
    /* Through the spec: --from, --look-at and --fov hold for a moving camera too. */
    if (local.cameras && s->camera >= 0)
        cg_view_from_spec(&s->scene, &s->view_spec, s->frame.width, s->frame.height, &s->frame.view);
    return true;
}

bool
app_session_mark_output(app_session *s, const char *source, bool *added, cg_error *err)
{
    *added = !is_output(s->graph, source);
    return !*added || fg_graph_mark_output(s->graph, source, NULL, err);
}

void
app_frame_stats_free(app_frame_stats *stats)
{
    free(stats->frame_ms);
    free(stats->pass_ms);
    free(stats->pass_sum_ms);
    memset(stats, 0, sizeof *stats);
}

double
app_frame_stats_pass_median(const app_frame_stats *stats, int pass)
{
    double *copy = malloc(sizeof *copy * (size_t)(stats->frames > 0 ? stats->frames : 1));
    if (!copy)
        return NAN;
    int n = 0;
    for (int f = 0; f < stats->frames; f++) {
        double ms = stats->pass_ms[(size_t)pass * (size_t)stats->frames + (size_t)f];
        if (ms >= 0.0)
            copy[n++] = ms;
    }
    double median = app_median(copy, n);
    free(copy);
    return median;
}

bool
app_session_run(app_session *s, const app_run_desc *run, app_frame_stats *stats, cg_error *err)
{
    memset(stats, 0, sizeof *stats);
    int passes = fg_graph_pass_count(s->graph);
    stats->frames = run->frames;
    stats->pass_count = passes;
    stats->frame_ms = calloc((size_t)run->frames, sizeof *stats->frame_ms);
    stats->pass_sum_ms = calloc((size_t)run->frames, sizeof *stats->pass_sum_ms);
    stats->pass_ms = calloc((size_t)run->frames * (size_t)(passes > 0 ? passes : 1), sizeof *stats->pass_ms);
    if (!stats->frame_ms || !stats->pass_sum_ms || !stats->pass_ms) {
        app_frame_stats_free(stats);
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%d frames of timings", run->frames);
        return failed(err, "frame");
    }
    for (int f = 0; f < run->warmup + run->frames; f++) {
        s->frame.index = (uint64_t)f;
        double t0 = app_now_ms();
        if (run->animate) {
            int k = f < run->warmup ? 0 : f - run->warmup;
            if (!app_session_set_time(s, run->time + k / run->fps, NULL, err)) {
                app_frame_stats_free(stats);
                return false;
            }
        }
        if (!fg_graph_execute(s->graph, &s->frame, run->timing, err)) {
            app_frame_stats_free(stats);
            return failed(err, "frame");
        }
        glFinish();
        double ms = app_now_ms() - t0;
        if (f < run->warmup)
            continue;
        int t = f - run->warmup;
        stats->frame_ms[t] = ms;
        for (int p = 0; p < passes; p++) {
            double pass_ms = fg_pass_milliseconds(fg_graph_pass_at(s->graph, p));
            stats->pass_ms[(size_t)p * (size_t)run->frames + (size_t)t] = pass_ms;
            if (pass_ms > 0.0)
                stats->pass_sum_ms[t] += pass_ms;
        }
        if (run->on_frame && !run->on_frame(run->user, t, run->frames, ms, err)) {
            app_frame_stats_free(stats);
            return false;
        }
    }
    if (!app_session_check_gl(s, err)) {
        app_frame_stats_free(stats);
        return false;
    }
    /* Medians of sorted copies: the per-frame arrays stay in frame order. */
    double *sorted = malloc(sizeof *sorted * (size_t)run->frames);
    if (!sorted) {
        app_frame_stats_free(stats);
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%d frames of timings", run->frames);
        return failed(err, "frame");
    }
    memcpy(sorted, stats->frame_ms, sizeof *sorted * (size_t)run->frames);
    stats->median_frame_ms = app_median(sorted, run->frames);
    memcpy(sorted, stats->pass_sum_ms, sizeof *sorted * (size_t)run->frames);
    stats->median_pass_sum_ms = app_median(sorted, run->frames);
    free(sorted);
    return true;
}

bool
app_session_check_gl(const app_session *s, cg_error *err)
{
    int errors = s->ctx ? cg_context_gl_error_count(s->ctx) : 0;
    if (errors > 0)
        return cg_fail(err, CG_ERR_GL, "%s: %d GL error(s) while running (logged above)", s->graph_path, errors);
    return true;
}

bool
app_session_read_image(const app_session *s, const char *source, bool srgb_encoded, cg_image *out, cg_error *err)
{
    const fg_resource_info *info = fg_graph_find_resource(s->graph, source);
    GLuint texture = fg_graph_texture(s->graph, source);
    if (!info || info->absent || !texture)
        return cg_fail(err, CG_ERR_PASS, "%s: resource absent (its pass was culled or had nothing to do)", source);
    if (info->desc.kind == FG_BUFFER)
        return cg_fail(err, CG_ERR_USAGE, "%s: a buffer, not a texture; only textures can be written as images", source);
    int w = info->desc.width, h = info->desc.height;
    int layers = info->desc.kind == FG_TEXTURE_2D ? 1 : info->desc.depth;
    size_t texels = (size_t)w * (size_t)h * (size_t)layers;
    bool depth = info->desc.format == GL_DEPTH_COMPONENT32F || info->desc.format == GL_DEPTH_COMPONENT24 ||
                 info->desc.format == GL_DEPTH_COMPONENT16 || info->desc.format == GL_DEPTH_COMPONENT32;
    float *data = malloc(texels * 4 * sizeof(float));
    if (!data)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: %zu texels", source, texels);
    /* The last writer may have used image stores. */
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (depth) {
        float *d = malloc(texels * sizeof(float));
        if (!d) {
            free(data);
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: %zu texels", source, texels);
        }
        glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(texels * sizeof(float)), d);
        for (size_t i = 0; i < texels; i++) {
            data[4 * i + 0] = data[4 * i + 1] = data[4 * i + 2] = d[i];
            data[4 * i + 3] = 1.0f;
        }
        free(d);
    } else {
        glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)(texels * 4 * sizeof(float)), data);
    }
    if (!cg_image_alloc(out, w, h * layers, err)) {
        free(data);
        return false;
    }
    /* GL rows go bottom to top; image files top to bottom. */
    for (int layer = 0; layer < layers; layer++)
        for (int y = 0; y < h; y++) {
            const float *src = data + ((size_t)layer * (size_t)h + (size_t)y) * (size_t)w * 4;
            float *dst = out->rgba + ((size_t)layer * (size_t)h + (size_t)(h - 1 - y)) * (size_t)w * 4;
            memcpy(dst, src, (size_t)w * 4 * sizeof(float));
        }
    free(data);
    if (srgb_encoded) {
        /* The ldr texture holds sRGB-encoded values; cg_image is linear and the PNG writer encodes. */
        for (size_t i = 0; i < texels; i++)
            for (int c = 0; c < 3; c++)
                out->rgba[4 * i + c] = cg_srgb_decode(out->rgba[4 * i + c]);
    }
    return true;
}

bool
app_session_write_image(const app_session *s, const char *source, bool srgb_encoded, const char *path,
                        cg_image_exr_type exr_type, cg_error *err)
{
    cg_image image = { 0 };
    bool ok = app_session_read_image(s, source, srgb_encoded, &image, err) &&
              cg_image_write(path, &image, exr_type, err);
    cg_image_free(&image);
    return ok;
}

void
app_session_stop_gl(app_session *s)
{
    /* The graph holds GL objects once prepared: it goes before the context. */
    if (s->graph)
        fg_graph_destroy(s->graph);
    s->graph = NULL;
    s->image_source = NULL;
    if (s->uploaded)
        cg_gpu_scene_destroy(&s->gpu);
    s->uploaded = false;
    s->frame.gpu_scene = NULL;
    if (s->ctx)
        cg_context_destroy(s->ctx);
    s->ctx = NULL;
}

void
app_session_close(app_session *s)
{
    app_session_stop_gl(s);
    if (s->registry)
        fg_registry_destroy(s->registry);
    s->registry = NULL;
    if (s->scene_loaded)
        cg_scene_free(&s->scene);
    s->scene_loaded = false;
}
