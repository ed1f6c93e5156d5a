/* passes/mip2d: the mip chain of a 2D lightmap, in place (hybrid paper V.B).
 *
 * Input and output `lightmap` (the same resource: level 0 is read, levels 1.. written).
 * A 2x2 box filter of radiance and height by compute, one dispatch per level, as mip3d
 * does for the 3D lightmap. Height keeps the average in alpha, as the paper does; the
 * min and max heights per level come from the hsat pass.
 */
#include <stdio.h>
#include <stdlib.h>

#include "sdk/pass.h"
#include "cg/fg.h"
#include "cg/shader.h"

typedef struct mip2d_state {
    GLuint program;
    GLenum format;
    fg_slot lightmap;
} mip2d_state;

static bool
mip2d_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *in = fg_declare_input(decl, "lightmap", FG_TEXTURE_2D,
                                                  FG_ACCESS_IMAGE_LOAD | FG_ACCESS_IMAGE_STORE, true);
    if (!in)
        return true;
    if (in->format != GL_RGBA16F && in->format != GL_RGBA32F)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'lightmap' must be RGBA16F or RGBA32F", fg_pass_name(pass));
    if (in->width != in->height || (in->width & (in->width - 1)) != 0)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'lightmap' must be square with a power-of-two side, got %dx%d",
                       fg_pass_name(pass), in->width, in->height);
    cgp_declare_in_place_chain(decl, "lightmap", in, "the lightmap has a single mip level");
    return true;
}

static bool
mip2d_prepare(fg_pass *pass, mip2d_state *s, cg_error *err)
{
    s->lightmap = fg_pass_slot(pass, "lightmap");
    s->format = fg_slot_resource(pass, s->lightmap)->format;
    char defines[64];
    snprintf(defines, sizeof defines, "#define FORMAT %s\n", s->format == GL_RGBA16F ? "rgba16f" : "rgba32f");
    return cgp_compute_program(s, "mip2d/downsample.comp", defines, &s->program, err);
}

static bool
mip2d_execute(fg_pass *pass, mip2d_state *s, cg_error *err)
{
    (void)err;
    const fg_resource_desc *desc = fg_slot_resource(pass, s->lightmap);
    GLuint tex = fg_slot_texture(pass, s->lightmap);
    glUseProgram(s->program);
    for (int level = 1; level < desc->levels; level++) {
        int size = desc->width >> level;
        glBindImageTexture(0, tex, level - 1, GL_FALSE, 0, GL_READ_ONLY, s->format);
        glBindImageTexture(1, tex, level, GL_FALSE, 0, GL_WRITE_ONLY, s->format);
        GLuint groups = (GLuint)((size + 7) / 8);
        glDispatchCompute(groups, groups, 1);
        /* The next level reads what this one wrote. */
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    cgp_compute_end(2, 0, NULL);
    return true;
}

CGP_PASS(mip2d, CGP_NO_PARAMS,
         "Mip chain of a 2D lightmap (hybrid paper V.B) by a 2x2 box filter, one compute dispatch "
         "per level, in place: mean radiance in rgb, mean height in alpha (the paper's filtered "
         "geometry; per-level height extremes come from hsat).");
