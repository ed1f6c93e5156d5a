/* path_trace: the CPU path-traced reference (Embree 3) as a frame-graph pass.
 *
 * Renders the frame's scene through the frame's view with pt_render.c and uploads the
 * result as the RGBA32F output `radiance` (linear, direct + `bounces` diffuse bounces +
 * emission: what `composite` takes as its `direct` input in graphs/reference.json).
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
    { "spp", FG_PARAM_INT, 64, 1, 65536, NULL, "samples per pixel" },
    { "bounces", FG_PARAM_INT, 1, 0, 16, NULL,
      "diffuse bounces after the first hit: 0 = direct light and visible emission, 1 = the GI "
      "graphs' direct + one bounce" },
    { "seed", FG_PARAM_INT, 1, 0, 2147483647.0, NULL,
      "random seed; the image is a function of the seed alone, whatever the thread count" },
    { "threads", FG_PARAM_INT, 0, 0, 256, NULL, "render threads (0 = one per core)" },
    { "jitter", FG_PARAM_BOOL, 0, 0, 1, NULL,
      "spread samples over the pixel (antialiased edges) instead of the pixel centre the raster "
      "passes sample" },
    { "progress", FG_PARAM_BOOL, 1, 0, 1, NULL, "progress bar on stderr" },
};

typedef struct path_trace_state {
    const cg_scene *scene;      /* the scene pts was built from */
    pt_scene *pts;
    /* The last image, and what it was rendered from. */
    float *rgba;                /* rows bottom to top, ready for GL */
    cg_view view;
    pt_settings settings;
    bool valid;
} path_trace_state;

static bool
path_trace_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    fg_resource_desc out = cgp_image_like(pass, NULL, GL_RGBA32F);
    out.persistent = true; /* holds the cached trace between frames */
    fg_declare_output(decl, "radiance", &out, FG_ACCESS_TRANSFER);
    return true;
}

/* What the state holds: the Embree scene and the last image (no GL objects). */
static void
path_trace_cleanup(void *state)
{
    path_trace_state *st = state;
    pt_scene_destroy(st->pts);
    free(st->rgba);
}

static bool
path_trace_prepare(fg_pass *pass, path_trace_state *st, cg_error *err)
{
    (void)err;
    (void)pass;
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
    return s;
}

static bool
same_image(const path_trace_state *st, const cg_view *view, const pt_settings *s)
{
    /* threads and progress do not change the image. */
    return st->valid && !memcmp(&st->view, view, sizeof *view) && st->settings.spp == s->spp &&
           st->settings.bounces == s->bounces && st->settings.seed == s->seed &&
           st->settings.jitter == s->jitter;
}

static bool
path_trace_execute(fg_pass *pass, path_trace_state *st, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    pt_settings settings = settings_of(pass);
    if (st->scene != frame->scene) {
        pt_scene_destroy(st->pts);
        st->pts = NULL;
        st->valid = false;
        if (!pt_scene_create(frame->scene, &st->pts, err))
            return false;
        st->scene = frame->scene;
    }
    int w = frame->view.width, h = frame->view.height;
    const fg_resource_desc *out = fg_resource(pass, "radiance");
    if (!out || out->width != w || out->height != h)
        return cg_fail(err, CG_ERR_PASS, "pass '%s': output is %dx%d, the view %dx%d", fg_pass_name(pass),
                       out ? out->width : 0, out ? out->height : 0, w, h);
    if (!same_image(st, &frame->view, &settings)) {
        size_t row = (size_t)w * 4;
        float *top_down = malloc(sizeof(float) * row * (size_t)h);
        float *rgba = realloc(st->rgba, sizeof(float) * row * (size_t)h);
        if (!top_down || !rgba) {
            free(top_down);
            if (rgba)
                st->rgba = rgba;
            st->valid = false;
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: %dx%d image", w, h);
        }
        st->rgba = rgba;
        uint64_t rays = 0;
        if (!pt_render(st->pts, &frame->view, &settings, top_down, &rays, err)) {
            free(top_down);
            st->valid = false;
            return false;
        }
        /* cg_image rows run top to bottom, GL's bottom to top. */
        for (int y = 0; y < h; y++)
            memcpy(&st->rgba[(size_t)(h - 1 - y) * row], &top_down[(size_t)y * row], sizeof(float) * row);
        free(top_down);
        st->view = frame->view;
        st->settings = settings;
        st->valid = true;
        cg_log_info("path_trace: %dx%d, %d spp, %d bounces, %llu rays", w, h, settings.spp,
                    settings.bounces, (unsigned long long)rays);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTextureSubImage2D(fg_texture(pass, "radiance"), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, st->rgba);
    return true;
}

CGP_PASS(path_trace, CGP_PARAMS(path_trace_params),
         "CPU path-traced reference on Embree 3: Lambertian materials with base colour "
         "textures, emissive surfaces, directional/point/spot lights by next-event estimation "
         "with hard shadows, cosine-sampled diffuse bounces; camera rays through the pixel "
         "centres of the raster passes' view. Output `radiance`: linear RGBA32F. Bit-identical "
         "for a seed whatever the thread count (counter-based random numbers per pixel and sample).");
