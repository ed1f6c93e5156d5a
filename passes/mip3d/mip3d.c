/* passes/mip3d: the filtered mip chain of a 3D lightmap, in place (VCT paper 3.1, figure 5).
 *
 * Input and output `volume` (the same resource: level 0 is read, levels 1.. are written).
 * A 2x2x2 box filter by compute, one dispatch per level: on llvmpipe a compute chain
 * beats glGenerateMipmap (22 vs 43 ms at 256^3 RGBA8, docs/PLATFORM), and unlike it,
 * it can filter opacity by the max rule (see shaders/mip3d/downsample.comp).
 */
#include <stdio.h>
#include <stdlib.h>

#include "sdk/pass.h"
#include "cg/fg.h"
#include "cg/shader.h"

static const fg_param_desc mip3d_params[] = {
    { .name = "opacity", .type = FG_PARAM_ENUM, .choices = "max|average",
      .doc = "coarse opacity: max of the 8 children (thin walls stay opaque) or their average (volume fraction)" },
    { .name = "anisotropic", .type = FG_PARAM_BOOL,
      .doc = "also build six directional chains of levels 1.. (outputs px nx py ny pz nz, Crassin et al. 2011)" },
};

/* Outputs of the anisotropic chains: level k holds global level k + 1 as seen by a cone
 * travelling along +x, -x, +y, -y, +z, -z. */
static const char *const direction_names[6] = {"px", "nx", "py", "ny", "pz", "nz"};

typedef struct mip3d_state {
    GLuint program;
    GLuint directional;
    GLenum format;
    bool anisotropic;
    fg_slot volume, directions[6];  /* directions: with anisotropic */
} mip3d_state;

static bool
mip3d_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *in = fg_declare_input(decl, "volume", FG_TEXTURE_3D,
                                                  FG_ACCESS_IMAGE_LOAD | FG_ACCESS_IMAGE_STORE, true);
    if (!in)
        return true;
    if (in->format != GL_RGBA16F && in->format != GL_RGBA8)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'volume' must be RGBA16F or RGBA8", fg_pass_name(pass));
    if (in->width != in->height || in->width != in->depth)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'volume' must be cubic, got %dx%dx%d",
                       fg_pass_name(pass), in->width, in->height, in->depth);
    cgp_declare_in_place_chain(decl, "volume", in, "the volume has a single mip level");
    if (in->levels >= 2 && fg_param_bool(pass, "anisotropic")) {
        fg_resource_desc dir = *in;
        dir.width = dir.height = dir.depth = in->width / 2;
        dir.levels = in->levels - 1;
        dir.persistent = false;
        dir.gi = true;
        for (int d = 0; d < 6; d++)
            fg_declare_output(decl, direction_names[d], &dir, FG_ACCESS_IMAGE_STORE);
    }
    return true;
}

static bool
mip3d_prepare(fg_pass *pass, mip3d_state *s, cg_error *err)
{
    s->volume = fg_pass_slot(pass, "volume");
    const fg_resource_desc *desc = fg_slot_resource(pass, s->volume);
    s->format = desc->format;
    char defines[128];
    snprintf(defines, sizeof defines, "#define FORMAT %s\n#define %s\n",
             s->format == GL_RGBA8 ? "rgba8" : "rgba16f",
             fg_param_enum(pass, "opacity") == 0 ? "OPACITY_MAX" : "OPACITY_AVERAGE");
    s->anisotropic = fg_param_bool(pass, "anisotropic");
    for (int d = 0; d < 6 && s->anisotropic; d++)
        s->directions[d] = fg_pass_slot(pass, direction_names[d]);
    char format_define[64];
    snprintf(format_define, sizeof format_define, "#define FORMAT %s\n", s->format == GL_RGBA8 ? "rgba8" : "rgba16f");
    return cgp_compute_program(s, "mip3d/downsample.comp", defines, &s->program, err) &&
                            (!s->anisotropic ||
                             cgp_compute_program(s, "mip3d/directional.comp", format_define, &s->directional, err));
}

static bool
mip3d_execute(fg_pass *pass, mip3d_state *s, cg_error *err)
{
    (void)err;
    const fg_resource_desc *desc = fg_slot_resource(pass, s->volume);
    GLuint tex = fg_slot_texture(pass, s->volume);
    glUseProgram(s->program);
    for (int level = 1; level < desc->levels; level++) {
        int size = desc->width >> level;
        if (size < 1)
            size = 1;
        glBindImageTexture(0, tex, level - 1, GL_TRUE, 0, GL_READ_ONLY, s->format);
        glBindImageTexture(1, tex, level, GL_TRUE, 0, GL_WRITE_ONLY, s->format);
        GLuint groups = (GLuint)((size + 3) / 4);
        glDispatchCompute(groups, groups, groups);
        /* The next level reads what this one wrote. */
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    if (s->anisotropic) {
        glUseProgram(s->directional);
        for (int d = 0; d < 6; d++) {
            GLuint dir = fg_slot_texture(pass, s->directions[d]);
            glUniform1i(0, d / 2);
            glUniform1i(1, d % 2 == 0 ? 1 : -1);
            for (int k = 0; k < desc->levels - 1; k++) {
                int size = desc->width >> (k + 1);
                /* Directional level 0 comes from the isotropic level 0, the others from
                 * the same direction's level below. */
                if (k == 0)
                    glBindImageTexture(0, tex, 0, GL_TRUE, 0, GL_READ_ONLY, s->format);
                else
                    glBindImageTexture(0, dir, k - 1, GL_TRUE, 0, GL_READ_ONLY, s->format);
                glBindImageTexture(1, dir, k, GL_TRUE, 0, GL_WRITE_ONLY, s->format);
                GLuint groups = (GLuint)((size + 3) / 4);
                glDispatchCompute(groups, groups, groups);
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            }
        }
    }
    cgp_compute_end(2, 0, NULL);
    return true;
}

CGP_PASS(mip3d, CGP_PARAMS(mip3d_params),
         "Filtered mip chain of a 3D lightmap by a 2x2x2 box filter, one compute dispatch per "
         "level, in place (VCT paper 3.1). Opacity by the max or the average of the children.");
