/* Decoupled GI resolution of a cone gather (sdk/upsample.h). */
#include "sdk/upsample.h"

#include <stdio.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"

const char *
cgp_gather_blocks_define(const fg_pass *pass, char *out, size_t size)
{
    int d = fg_param_int(pass, "downsample");
    if (d > 1)
        snprintf(out, size, "#define CG_GATHER_DOWNSAMPLE %d\n", d);
    else if (size > 0)
        out[0] = '\0';
    return out;
}

bool
cgp_gather_blocks_prepare(void *state, const fg_pass *pass, const cgp_gather *g, cgp_gather_blocks *b,
                          const char *shader, const char *defines, cg_error *err)
{
    *b = (cgp_gather_blocks){.downsample = fg_param_int(pass, "downsample")};
    const fg_resource_desc *out = fg_slot_resource(pass, g->slots.radiance);
    if (b->downsample <= 1 || !out)
        return true;
    char all[1024];
    snprintf(all, sizeof all, "%s%s%s#define CG_GATHER_LOWRES\n", defines ? defines : "",
             cgp_gather_volume_define(g->model), g->material ? "#define CG_GATHER_MATERIAL\n" : "");
    if (!cgp_compute_program(state, shader, all, &b->program, err))
        return false;
    b->width = (out->width + b->downsample - 1) / b->downsample;
    b->height = (out->height + b->downsample - 1) / b->downsample;
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, b->width, b->height);
    /* Read by texelFetch only; a single level, complete under any filter. */
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    b->texture = cgp_own(state, CGP_GL_TEXTURE, tex);
    return true;
}

void
cgp_gather_blocks_trace(const fg_pass *pass, const cgp_gather *g, const cgp_gather_blocks *b)
{
    if (b->downsample <= 1 || !b->program)
        return;
    glUseProgram(b->program);
    glBindImageTexture(0, b->texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    cgp_dispatch_2d(b->width, b->height);
    /* The full-resolution dispatch reads the blocks by texelFetch, and a pass's cost image written
     * at the representatives by the blocks' dispatch is written by it at the other pixels. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindTextureUnit(CG_UNIT_GATHER_BLOCKS, b->texture);
    glBindSampler(CG_UNIT_GATHER_BLOCKS, 0);
    glUseProgram(g->program);
    glBindImageTexture(0, fg_slot_texture(pass, g->slots.radiance), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
}

void
cgp_gather_blocks_end(const cgp_gather_blocks *b)
{
    if (b->downsample > 1)
        glBindTextureUnit(CG_UNIT_GATHER_BLOCKS, 0);
}
