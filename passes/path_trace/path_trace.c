/* path_trace: the CPU path-traced reference (Embree 3) as a frame-graph pass.
 *
 * Renders the frame's scene through the frame's view with pt_render.c and uploads the
 * result as the RGBA32F output `radiance` (linear, direct + `bounces` diffuse bounces +
 * emission: what `composite` takes as its `direct` input in graphs/reference.json).
 * With `parts`, the same trace also gives its parts as outputs `emitted`,
 * `direct_punctual`, `direct_emitters`, `direct_sky` and `indirect` (pt_part), which add up
 * to `radiance`.
 * The image is kept while scene, view and parameters stay the same, so running the graph
 * for several frames traces once and re-uploads.
 */
#include <stdlib.h>
#include <string.h>

#include "sdk/pass.h"
#include "cg/fg.h"
#include "cg/log.h"
#include "cg/pt_render.h"

static const fg_param_desc path_trace_params[] = {
    { .name = "spp", .type = FG_PARAM_INT, .default_value = 64, .min = 1, .max = 65536,
      .step_doubles = true,
      .doc = "samples per pixel" },
    { .name = "bounces", .type = FG_PARAM_INT, .default_value = 1, .min = 0, .max = 16,
      .doc = "diffuse bounces, counted as Cycles counts them: 0 = direct light of every source (punctual "
             "lights, emissive surfaces, the sky) and what the camera sees; each bounce adds a diffuse "
             "reflection" },
    { .name = "glossy_bounces", .type = FG_PARAM_INT, .default_value = 1, .min = 0, .max = 16,
      .doc = "glossy bounces, counted as Cycles counts them: reflections off a GGX lobe (metal, polished "
             "dielectric, and the reflection off glass); a path past the limit shows only the emission it "
             "meets next" },
    { .name = "transmission_bounces", .type = FG_PARAM_INT, .default_value = 4, .min = 0, .max = 16,
      .doc = "transmission bounces, counted as Cycles counts them: refractions into or out of a solid and "
             "crossings of a thin (thickness 0) transmissive sheet" },
    { .name = "caustics", .type = FG_PARAM_BOOL,
      .doc = "false: glossy and transmission lobes only on paths from the camera before their first diffuse "
             "reflection (Cycles' caustics_reflective and caustics_refractive off); glass casts a full "
             "shadow either way (light sampling does not pass glass)" },
    { .name = "seed", .type = FG_PARAM_INT, .default_value = 1, .min = 0, .max = 2147483647.0,
      .doc = "random seed; the image is a function of the seed alone, whatever the thread count" },
    { .name = "threads", .type = FG_PARAM_INT, .min = 0, .max = 256,
      .doc = "render threads (0 = one per core)" },
    { .name = "jitter", .type = FG_PARAM_BOOL,
      .doc = "spread samples over the pixel (antialiased edges) instead of the pixel centre the raster "
             "passes sample" },
    { .name = "progress", .type = FG_PARAM_BOOL, .default_value = 1, .doc = "progress bar on stderr" },
    { .name = "parts", .type = FG_PARAM_BOOL,
      .doc = "also output the parts of `radiance` from the same trace: emitted (seen by the camera), "
             "direct_punctual, direct_emitters, direct_sky (reflected once), indirect (twice or more)" },
};

typedef struct path_trace_state {
    const cg_scene *scene;      /* the scene pts was built from */
    uint64_t revision;          /* its cg_scene.revision then: moved instances or lights rebuild it */
    pt_scene *pts;
    /* The last image, and what it was rendered from. */
    float *rgba;                /* rows bottom to top, ready for GL */
    float *parts[PT_PART_COUNT]; /* the same, when `parts` is on */
    cg_view view;
    pt_settings settings;
    bool with_parts;
    bool valid;
    fg_slot radiance, part_slots[PT_PART_COUNT]; /* part_slots: declared with `parts` */
} path_trace_state;

static bool
path_trace_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    fg_resource_desc out = cgp_image_like(pass, NULL, GL_RGBA32F);
    out.persistent = true; /* holds the cached trace between frames */
    fg_declare_output(decl, "radiance", &out, FG_ACCESS_TRANSFER);
    if (fg_param_bool(pass, "parts"))
        for (int p = 0; p < PT_PART_COUNT; p++)
            fg_declare_output(decl, pt_part_name((pt_part)p), &out, FG_ACCESS_TRANSFER);
    return true;
}

/* What the state holds: the Embree scene and the last images (no GL objects). */
static void
path_trace_cleanup(void *state)
{
    path_trace_state *st = state;
    pt_scene_destroy(st->pts);
    free(st->rgba);
    for (int p = 0; p < PT_PART_COUNT; p++)
        free(st->parts[p]);
}

static bool
path_trace_prepare(fg_pass *pass, path_trace_state *st, cg_error *err)
{
    (void)err;
    st->radiance = fg_pass_slot(pass, "radiance");
    for (int p = 0; p < PT_PART_COUNT && fg_param_bool(pass, "parts"); p++)
        st->part_slots[p] = fg_pass_slot(pass, pt_part_name((pt_part)p));
    cgp_state_on_destroy(st, path_trace_cleanup);
    return true;
}

static pt_settings
settings_of(const fg_pass *pass)
{
    pt_settings s = pt_settings_default();
    s.spp = fg_param_int(pass, "spp");
    s.bounces = fg_param_int(pass, "bounces");
    s.seed = (uint32_t)fg_param_int(pass, "seed");
    s.threads = fg_param_int(pass, "threads");
    s.jitter = fg_param_bool(pass, "jitter");
    s.progress = fg_param_bool(pass, "progress");
    s.glossy_bounces = fg_param_int(pass, "glossy_bounces");
    s.transmission_bounces = fg_param_int(pass, "transmission_bounces");
    s.caustics = fg_param_bool(pass, "caustics");
    return s;
}

static bool
same_image(const path_trace_state *st, const cg_view *view, const pt_settings *s, bool with_parts)
{
    /* threads and progress do not change the image. */
    return st->valid && !memcmp(&st->view, view, sizeof *view) && st->settings.spp == s->spp &&
           st->settings.bounces == s->bounces && st->settings.seed == s->seed &&
           st->settings.jitter == s->jitter && st->settings.glossy_bounces == s->glossy_bounces &&
           st->settings.transmission_bounces == s->transmission_bounces &&
           st->settings.caustics == s->caustics && (st->with_parts || !with_parts);
}

/* cg_image rows run top to bottom, GL's bottom to top. */
static void
flip_rows(float *dst, const float *src, int w, int h)
{
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h; y++)
        memcpy(&dst[(size_t)(h - 1 - y) * row], &src[(size_t)y * row], sizeof(float) * row);
}

static void
upload(fg_pass *pass, fg_slot output, const float *rgba, int w, int h)
{
    glTextureSubImage2D(fg_slot_texture(pass, output), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, rgba);
}

static bool
path_trace_execute(fg_pass *pass, path_trace_state *st, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    pt_settings settings = settings_of(pass);
    if (st->scene != frame->scene || st->revision != frame->scene->revision) {
        pt_scene_destroy(st->pts);
        st->pts = NULL;
        st->valid = false;
        if (!pt_scene_create(frame->scene, &st->pts, err))
            return false;
        st->scene = frame->scene;
        st->revision = frame->scene->revision;
    }
    int w = frame->view.width, h = frame->view.height;
    const fg_resource_desc *out = fg_slot_resource(pass, st->radiance);
    if (!out || out->width != w || out->height != h)
        return cg_fail(err, CG_ERR_PASS, "pass '%s': output is %dx%d, the view %dx%d", fg_pass_name(pass),
                       out ? out->width : 0, out ? out->height : 0, w, h);
    bool with_parts = fg_param_bool(pass, "parts");
    if (!same_image(st, &frame->view, &settings, with_parts)) {
        size_t pixels = (size_t)w * (size_t)h * 4;
        int count = with_parts ? 1 + PT_PART_COUNT : 1;
        /* The trace's images (top to bottom), then the cached ones (bottom to top). */
        float *top_down[1 + PT_PART_COUNT] = { 0 };
        bool ok = true;
        for (int k = 0; k < count && ok; k++)
            ok = (top_down[k] = malloc(sizeof(float) * pixels)) != NULL;
        float **cached[1 + PT_PART_COUNT] = { &st->rgba };
        for (int p = 0; p < PT_PART_COUNT; p++)
            cached[1 + p] = &st->parts[p];
        for (int k = 0; k < count && ok; k++) {
            float *bigger = realloc(*cached[k], sizeof(float) * pixels);
            if (bigger)
                *cached[k] = bigger;
            ok = bigger != NULL;
        }
        st->valid = false;
        if (!ok) {
            for (int k = 0; k < count; k++)
                free(top_down[k]);
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: %dx%d image", w, h);
        }
        uint64_t rays = 0;
        if (!pt_render_parts(st->pts, &frame->view, &settings, top_down[0], with_parts ? &top_down[1] : NULL, &rays,
                             err)) {
            for (int k = 0; k < count; k++)
                free(top_down[k]);
            return false;
        }
        for (int k = 0; k < count; k++) {
            flip_rows(*cached[k], top_down[k], w, h);
            free(top_down[k]);
        }
        st->view = frame->view;
        st->settings = settings;
        st->with_parts = with_parts;
        st->valid = true;
        cg_log_info("path_trace: %dx%d, %d spp, %d bounces, %llu rays", w, h, settings.spp,
                    settings.bounces, (unsigned long long)rays);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    upload(pass, st->radiance, st->rgba, w, h);
    for (int p = 0; with_parts && p < PT_PART_COUNT; p++)
        upload(pass, st->part_slots[p], st->parts[p], w, h);
    return true;
}

CGP_PASS(path_trace, CGP_PARAMS(path_trace_params),
         "CPU path-traced reference on Embree 3: glTF 2.0 materials (Lambertian diffuse, GGX "
         "reflection, GGX transmission with Beer-Lambert volumes, alpha MASK and BLEND, normal maps), "
         "emissive surfaces, directional (with an angular diameter)/point/spot lights, emitters and "
         "the sky by next-event estimation with multiple importance sampling; diffuse, glossy and "
         "transmission bounces counted as Cycles counts them; camera rays through the pixel "
         "centres of the raster passes' view. Output `radiance`: linear RGBA32F. Bit-identical "
         "for a seed whatever the thread count (counter-based random numbers per pixel and sample).");
