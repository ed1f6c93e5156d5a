/* passes/hsat: per-level min/max height tables of a mipped 2D lightmap, so that the hybrid
 * cone tracer finds the lowest and highest terrain under any rectangle in constant time
 * (hybrid paper VI.A, "HSAT", eq. 13-14). shaders/common/hsat.glsl reads them.
 *
 * Inputs: lightmap (a heightmap_raster lightmap after mip2d), region (heightmap_raster's block).
 * Outputs
 *   table  mode pyramid: RG32UI (float bits), n x n, one level per lightmap level, level L =
 *          exact (min, max) of the level-0 heights over 2^L x 2^L blocks;
 *          modes pnorm and power_mean: RGBA32UI, 2n x n, level l = summed-area tables of
 *          level l's normalised height x, x^p and (1 - x)^p as doubles (two texels per
 *          entry), each minus its level mean (Hensley 2005). fp32 tables were measured
 *          2.6 m off in the mean height of small rectangles at 2048^2 (docs/hybrid.md).
 *   info   std430 block CG_HSAT_INFO_BLOCK (common/blocks.h): mode, p, levels, and the
 *          per-level means.
 *
 * Why three modes: eq. 14 (power_mean) under-estimates the maximum by up to N^(-1/p) over N
 * texels, so a skip test built on it can skip terrain that is there; x^p also flushes to zero
 * for small x. pnorm drops the 1/N (an upper bound, with a margin for rounding and
 * underflow), and pyramid is exact on aligned blocks, conservative elsewhere and free of
 * precision loss (no sums at all): the default. docs/hybrid.md has the measured errors.
 */
#include <stdio.h>
#include <stdlib.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"
#include "cg/fg.h"
#include "cg/shader.h"

enum { MODE_PYRAMID, MODE_PNORM, MODE_POWER_MEAN };

static const fg_param_desc hsat_params[] = {
    { .name = "mode", .type = FG_PARAM_ENUM, .default_value = MODE_PYRAMID, .choices = "pyramid|pnorm|power_mean",
      .doc = "pyramid: exact min/max mip pyramid (conservative); pnorm: SAT with the un-normalised p-norm "
             "(an upper bound); power_mean: SAT with eq. 14 as the paper writes it (under-estimates)" },
    { .name = "p", .type = FG_PARAM_FLOAT, .default_value = 16, .min = 1, .max = 64,
      .active_when = "mode=pnorm|power_mean",
      .doc = "exponent of eq. 14 (SAT modes)" },
};

typedef struct hsat_state {
    int mode;
    GLenum lightmap_format;
    GLuint first, next;                     /* pyramid */
    GLuint row_sums, mean, rows, columns;   /* SAT stages */
    GLuint row_buffer;
    fg_slot lightmap, region, table, info;
} hsat_state;

static bool
hsat_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *lightmap = fg_declare_input(decl, "lightmap", FG_TEXTURE_2D, FG_ACCESS_IMAGE_LOAD, true);
    const fg_resource_desc *region = fg_declare_input(decl, "region", FG_BUFFER, FG_ACCESS_UNIFORM, true);
    if (!lightmap || !region)
        return true;
    if (lightmap->format != GL_RGBA16F && lightmap->format != GL_RGBA32F)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'lightmap' must be RGBA16F or RGBA32F (a heightmap_raster lightmap)",
                       fg_pass_name(pass));
    if (lightmap->width != lightmap->height || lightmap->levels > CG_HSAT_MAX_LEVELS)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'lightmap' must be square with at most %d levels, got %dx%d, %d levels",
                       fg_pass_name(pass), CG_HSAT_MAX_LEVELS, lightmap->width, lightmap->height, lightmap->levels);
    if (region->buffer_bytes < sizeof(cg_heightmap_block))
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'region' holds %zu bytes; a heightmap_raster 'region' holds %zu",
                       fg_pass_name(pass), region->buffer_bytes, sizeof(cg_heightmap_block));
    bool pyramid = fg_param_enum(pass, "mode") == MODE_PYRAMID;
    fg_resource_desc table = {
        .kind = FG_TEXTURE_2D, .format = pyramid ? GL_RG32UI : GL_RGBA32UI,
        .width = pyramid ? lightmap->width : 2 * lightmap->width, .height = lightmap->height, .depth = 1,
        .levels = lightmap->levels, .gi = true,
    };
    fg_declare_output(decl, "table", &table, FG_ACCESS_IMAGE_STORE | FG_ACCESS_IMAGE_LOAD);
    fg_resource_desc info = cgp_buffer_desc(sizeof(cg_hsat_info_block));
    info.gi = true;
    fg_declare_output(decl, "info", &info, FG_ACCESS_TRANSFER | FG_ACCESS_STORAGE);
    return true;
}

static bool
hsat_prepare(fg_pass *pass, hsat_state *s, cg_error *err)
{
    s->mode = fg_param_enum(pass, "mode");
    CGP_SLOTS(pass, s, lightmap, region, table, info);
    s->lightmap_format = fg_slot_resource(pass, s->lightmap)->format;
    const char *format = s->lightmap_format == GL_RGBA16F ? "rgba16f" : "rgba32f";
    char defines[128];
    bool ok = true;
    if (s->mode == MODE_PYRAMID) {
        snprintf(defines, sizeof defines, "#define LIGHTMAP_FORMAT %s\n#define FIRST\n", format);
        ok = cgp_compute_program(s, "hsat/pyramid.comp", defines, &s->first, err) &&
             cgp_compute_program(s, "hsat/pyramid.comp", "#define LIGHTMAP_FORMAT rgba32f\n", &s->next, err);
    } else {
        static const char *const stages[4] = {"ROW_SUMS", "MEAN", "ROWS", "COLUMNS"};
        GLuint *programs[4] = {&s->row_sums, &s->mean, &s->rows, &s->columns};
        for (int i = 0; i < 4 && ok; i++) {
            snprintf(defines, sizeof defines, "#define LIGHTMAP_FORMAT %s\n#define %s\n", format, stages[i]);
            ok = cgp_compute_program(s, "hsat/sat.comp", defines, programs[i], err);
        }
        if (ok) {
            int size = fg_slot_resource(pass, s->lightmap)->width;
            s->row_buffer = cgp_buffer(s, (size_t)size * 4 * sizeof(double), NULL, 0);
        }
    }
    return ok;
}

static bool
hsat_execute(fg_pass *pass, hsat_state *s, cg_error *err)
{
    (void)err;
    const fg_resource_desc *lightmap_desc = fg_slot_resource(pass, s->lightmap);
    GLuint lightmap = fg_slot_texture(pass, s->lightmap);
    GLuint table = fg_slot_texture(pass, s->table);
    GLuint info = fg_slot_buffer(pass, s->info);
    int levels = lightmap_desc->levels;
    float p = fg_param_float(pass, "p");
    /* The means are zero until the SAT stages write them (the pyramid has none). */
    const cg_hsat_info_block block = {.params = {(float)s->mode, p, (float)levels, 0.0f}};
    glNamedBufferSubData(info, 0, sizeof block, &block);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);

    if (s->mode == MODE_PYRAMID) {
        for (int level = 0; level < levels; level++) {
            int size = lightmap_desc->width >> level;
            glUseProgram(level == 0 ? s->first : s->next);
            if (level == 0)
                glBindImageTexture(0, lightmap, 0, GL_FALSE, 0, GL_READ_ONLY, s->lightmap_format);
            else
                glBindImageTexture(0, table, level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RG32UI);
            glBindImageTexture(1, table, level, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32UI);
            GLuint groups = (GLuint)((size + 7) / 8);
            glDispatchCompute(groups, groups, 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        }
        cgp_compute_end(2, 0, NULL);
        return true;
    }

    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_HEIGHTMAP, fg_slot_buffer(pass, s->region));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_HSAT, info);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_HSAT_ROWS, s->row_buffer);
    const GLuint stages[4] = {s->row_sums, s->mean, s->rows, s->columns};
    const GLbitfield after[4] = {GL_SHADER_STORAGE_BARRIER_BIT, GL_SHADER_STORAGE_BARRIER_BIT,
                                 GL_SHADER_IMAGE_ACCESS_BARRIER_BIT, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT};
    for (int level = 0; level < levels; level++) {
        int size = lightmap_desc->width >> level;
        glBindImageTexture(0, lightmap, level, GL_FALSE, 0, GL_READ_ONLY, s->lightmap_format);
        glBindImageTexture(1, table, level, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32UI);
        for (int i = 0; i < 4; i++) {
            glUseProgram(stages[i]);
            glUniform1i(0, size);
            glUniform1i(1, level);
            glUniform1f(2, p);
            glDispatchCompute(i == 1 ? 1u : (GLuint)((size + 63) / 64), 1, 1);
            glMemoryBarrier(after[i]);
        }
    }
    cgp_compute_end(2, 2, (const GLuint[]){ CG_BINDING_HSAT, CG_BINDING_HSAT_ROWS });
    return true;
}

CGP_PASS(hsat, CGP_PARAMS(hsat_params),
         "Per-level min/max height tables of a mipped 2D lightmap (hybrid paper VI.A, HSAT, "
         "eq. 13-14): the lowest and highest terrain under any rectangle in constant time. "
         "Default: an exact min/max pyramid (conservative); or summed-area tables of x^p read "
         "as the un-normalised p-norm (an upper bound) or as eq. 14's power mean (the paper's, "
         "which under-estimates). SAT entries are stored minus the level mean (Hensley 2005).");
