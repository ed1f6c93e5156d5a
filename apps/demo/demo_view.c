/* The resource viewer's drawing: see demo_view.h. */
#include "demo_view.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/shader.h"

enum { VIEW_2D, VIEW_3D, VIEW_ARRAY };

void
demo_view_create(demo_view *view)
{
    memset(view, 0, sizeof *view);
    glCreateVertexArrays(1, &view->vao);
    glCreateFramebuffers(1, &view->fbo);
    /* Texel fetches ignore filtering but not a depth texture's compare mode, which a shadow
     * pass may have set on the texture: this sampler turns it off. */
    glCreateSamplers(1, &view->sampler);
    glSamplerParameteri(view->sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(view->sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(view->sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

static void
release_target(demo_view *view)
{
    if (view->shown)
        glDeleteTextures(1, &view->shown);
    if (view->target)
        glDeleteTextures(1, &view->target);
    view->shown = view->target = 0;
    view->width = view->height = 0;
}

void
demo_view_destroy(demo_view *view)
{
    release_target(view);
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < DEMO_VIEW_CLASS_COUNT; c++)
            if (view->programs[k][c])
                glDeleteProgram(view->programs[k][c]);
    if (view->sampler)
        glDeleteSamplers(1, &view->sampler);
    if (view->fbo)
        glDeleteFramebuffers(1, &view->fbo);
    if (view->vao)
        glDeleteVertexArrays(1, &view->vao);
    memset(view, 0, sizeof *view);
}

demo_view_class
demo_view_class_of(GLuint texture)
{
    GLint depth = GL_NONE, red = GL_NONE;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_DEPTH_TYPE, &depth);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_RED_TYPE, &red);
    if (depth != GL_NONE)
        return DEMO_VIEW_DEPTH;
    if (red == GL_UNSIGNED_INT)
        return DEMO_VIEW_UINT;
    if (red == GL_INT)
        return DEMO_VIEW_INT;
    return DEMO_VIEW_COLOUR;
}

void
demo_view_defaults(GLuint texture, const fg_resource_desc *desc, demo_view_class cls, demo_view_settings *out)
{
    memset(out, 0, sizeof *out);
    /* The middle of a volume: its outer slices are mostly empty. */
    out->layer = desc->kind == FG_TEXTURE_3D ? desc->depth / 2 : 0;
    out->lo = 0;
    out->hi = cls == DEMO_VIEW_DEPTH ? 1 : 255;
    GLint red = GL_NONE, bits = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_RED_TYPE, &red);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_RED_SIZE, &bits);
    /* 8-bit normalized texels are display values already (an ldr output is sRGB-encoded);
     * wider and float ones are linear. */
    out->srgb = !(red == GL_UNSIGNED_NORMALIZED && bits <= 8);
}

void
demo_view_level_size(const fg_resource_desc *desc, int level, int *width, int *height, int *slices)
{
    *width = desc->width >> level > 0 ? desc->width >> level : 1;
    *height = desc->height >> level > 0 ? desc->height >> level : 1;
    if (desc->kind == FG_TEXTURE_3D)
        *slices = desc->depth >> level > 0 ? desc->depth >> level : 1;
    else if (desc->kind == FG_TEXTURE_2D_ARRAY)
        *slices = desc->depth;
    else
        *slices = 1;
}

static bool
program_for(demo_view *view, int kind, demo_view_class cls, GLuint *out, cg_error *err)
{
    GLuint *program = &view->programs[kind][cls];
    if (!*program) {
        static const char *const kinds[] = { "", "#define VIEW_3D\n", "#define VIEW_ARRAY\n" };
        static const char *const classes[] = { "", "#define VIEW_DEPTH\n", "#define VIEW_UINT\n",
                                               "#define VIEW_INT\n" };
        char defines[128];
        strcpy(defines, kinds[kind]);
        strcat(defines, classes[cls]);
        if (!cg_program_graphics("demo/view.vert", NULL, "demo/view.frag", defines, program, err))
            return false;
    }
    *out = *program;
    return true;
}

/* The picture's size for a level: the level's, scaled down to DEMO_VIEW_MAX_SIZE on its
 * longest side. */
static void
target_size(int w, int h, int *tw, int *th)
{
    int longest = w > h ? w : h;
    if (longest <= DEMO_VIEW_MAX_SIZE) {
        *tw = w;
        *th = h;
        return;
    }
    *tw = (int)((long long)w * DEMO_VIEW_MAX_SIZE / longest);
    *th = (int)((long long)h * DEMO_VIEW_MAX_SIZE / longest);
    *tw = *tw > 0 ? *tw : 1;
    *th = *th > 0 ? *th : 1;
}

static void
ensure_target(demo_view *view, int w, int h)
{
    if (view->target && view->width == w && view->height == h)
        return;
    release_target(view);
    glCreateTextures(GL_TEXTURE_2D, 1, &view->target);
    glTextureStorage2D(view->target, 1, GL_SRGB8_ALPHA8, w, h);
    /* The UI samples the stored bytes as RGBA8: the framebuffer's sRGB encoding is then
     * what reaches the window (whose blit and UI write bytes as they are). A view's name must
     * be fresh from glGenTextures. */
    glGenTextures(1, &view->shown);
    glTextureView(view->shown, GL_TEXTURE_2D, view->target, GL_RGBA8, 0, 1, 0, 1);
    glTextureParameteri(view->shown, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(view->shown, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(view->shown, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(view->shown, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glNamedFramebufferTexture(view->fbo, GL_COLOR_ATTACHMENT0, view->target, 0);
    view->width = w;
    view->height = h;
}

static int
clamp_int(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* The settings within the resource: a level it has, a slice that level has. */
static void
clamp_settings(const fg_resource_desc *desc, demo_view_settings *s, int *w, int *h)
{
    int slices;
    s->level = clamp_int(s->level, 0, desc->levels - 1);
    demo_view_level_size(desc, s->level, w, h, &slices);
    s->layer = clamp_int(s->layer, 0, slices - 1);
    s->channel = clamp_int(s->channel, 0, 4);
}

bool
demo_view_fit(GLuint texture, const fg_resource_desc *desc, demo_view_class cls, demo_view_settings *s,
              cg_error *err)
{
    int w, h;
    clamp_settings(desc, s, &w, &h);
    int components = cls == DEMO_VIEW_DEPTH ? 1 : 4;
    size_t count = (size_t)w * (size_t)h * (size_t)components;
    /* Floats, uints and ints are all 4 bytes: one buffer for any class. GL takes its size as
     * a GLsizei. */
    if (count > INT_MAX / 4)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "a %dx%d level is too large to read back at once", w, h);
    void *texels = malloc(count * 4);
    if (!texels)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory for %dx%d texels", w, h);
    GLenum format = cls == DEMO_VIEW_DEPTH ? GL_DEPTH_COMPONENT
                  : cls == DEMO_VIEW_COLOUR ? GL_RGBA : GL_RGBA_INTEGER;
    GLenum type = cls == DEMO_VIEW_UINT ? GL_UNSIGNED_INT : cls == DEMO_VIEW_INT ? GL_INT : GL_FLOAT;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureSubImage(texture, s->level, 0, 0, desc->kind == FG_TEXTURE_2D ? 0 : s->layer, w, h, 1, format, type,
                         (GLsizei)(count * 4), texels);
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < count; i++) {
        int c = (int)(i % (size_t)components);
        /* The shown channels only: RGB (not alpha), or the one chosen. */
        if (components == 4 && (s->channel == 0 ? c == 3 : c != s->channel - 1))
            continue;
        double v = cls == DEMO_VIEW_UINT ? ((const GLuint *)texels)[i]
                 : cls == DEMO_VIEW_INT ? ((const GLint *)texels)[i] : ((const float *)texels)[i];
        if (isfinite(v)) {
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
    }
    free(texels);
    if (lo > hi)
        return true; /* nothing finite: keep the mapping */
    if (cls == DEMO_VIEW_COLOUR) {
        if (hi > 0)
            s->exposure = -log2(hi);
    } else {
        s->lo = lo;
        s->hi = hi > lo ? hi : lo + 1;
    }
    return true;
}

bool
demo_view_draw(demo_view *view, GLuint texture, const fg_resource_desc *desc, demo_view_class cls,
               demo_view_settings *s, cg_error *err)
{
    int kind = desc->kind == FG_TEXTURE_3D ? VIEW_3D : desc->kind == FG_TEXTURE_2D_ARRAY ? VIEW_ARRAY : VIEW_2D;
    GLuint program;
    if (!program_for(view, kind, cls, &program, err))
        return false;
    int w, h;
    clamp_settings(desc, s, &w, &h);
    int tw, th;
    target_size(w, h, &tw, &th);
    ensure_target(view, tw, th);

    double offset = 0, scale = 1;
    if (cls == DEMO_VIEW_COLOUR) {
        scale = pow(2.0, s->exposure);
    } else {
        offset = s->lo;
        scale = s->hi != s->lo ? 1.0 / (s->hi - s->lo) : 1.0;
    }
    glProgramUniform2i(program, 0, w, h);
    glProgramUniform2i(program, 1, tw, th);
    glProgramUniform1i(program, 2, s->level);
    glProgramUniform1i(program, 3, s->layer);
    glProgramUniform1i(program, 4, s->channel);
    glProgramUniform1f(program, 5, (float)offset);
    glProgramUniform1f(program, 6, (float)scale);

    static const GLenum enables[] = { GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST,
                                      GL_STENCIL_TEST, GL_FRAMEBUFFER_SRGB };
    GLboolean was[sizeof enables / sizeof enables[0]];
    for (size_t i = 0; i < sizeof enables / sizeof enables[0]; i++) {
        was[i] = glIsEnabled(enables[i]);
        glDisable(enables[i]);
    }
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);

    /* Whatever wrote the resource (image stores included) is visible to the fetches. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    bool encode = cls == DEMO_VIEW_COLOUR && s->srgb;
    if (encode)
        glEnable(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, view->fbo);
    glViewport(0, 0, tw, th);
    glUseProgram(program);
    glBindVertexArray(view->vao);
    glBindTextureUnit(0, texture);
    glBindSampler(0, view->sampler);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindSampler(0, 0);
    glBindTextureUnit(0, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);

    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    for (size_t i = 0; i < sizeof enables / sizeof enables[0]; i++) {
        if (was[i])
            glEnable(enables[i]);
        else
            glDisable(enables[i]);
    }
    return true;
}
