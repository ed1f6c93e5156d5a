/* sdk/upsample.h (pass SDK): decoupled GI resolution of a cone gather: its diffuse cones traced at
 * one pixel of each D x D block, the full resolution rebuilt by joint bilateral upsampling with
 * the G-buffer's position and normal (shaders/common/upsample.glsl says how, and why no light
 * crosses a depth or normal edge).
 *
 * Declares: CGP_DOWNSAMPLE_PARAM, CGP_TEMPORAL_PARAM, CGP_INTERLEAVE_PARAM, CGP_DOWNSAMPLE_AUTO_ROWS, cgp_gather_downsample,
 *           cgp_gather_blocks, cgp_gather_blocks_define,
 *           cgp_gather_blocks_prepare, cgp_gather_blocks_trace, cgp_gather_blocks_deferred,
 *           cgp_gather_blocks_end.
 *
 * Shared by cone_gather and hybrid_gather (and a plugin gather that wants the same). A gather's
 * shader that takes part includes common/upsample.glsl, whose main() is the entry point with
 * CG_GATHER_LOWRES or CG_GATHER_DEFERRED (it calls the shader's cg_upsample_trace,
 * cg_upsample_untraced and cg_upsample_camera); four programs by define:
 *   CG_GATHER_LOWRES    one invocation per block (cg_gather_pixel over the image of blocks, bound as
 *                       `radiance` at image unit 0): lists the blocks that trace this frame and
 *                       writes the background's;
 *   CG_GATHER_LOWRES and CG_GATHER_DEFERRED  one invocation per listed block, 64 to a group: the
 *                       diffuse cones of its representative pixel (cg_upsample_representative),
 *                       before the material's diffuse share;
 *   neither             the shader's own main: every pixel as before, its diffuse light from
 *                       cg_upsample_diffuse; where that fails the pixel is listed (cg_upsample_defer)
 *                       and its diffuse light left 0; the specular and refracted cones at every pixel;
 *   CG_GATHER_DEFERRED  one invocation per listed pixel, 64 to a group: its own diffuse cones.
 * With downsample = 1 none is compiled in and the shader is the gather it always was. A pass runs
 * them as: cgp_gather_begin, cgp_gather_blocks_trace, cgp_gather_dispatch, cgp_gather_blocks_deferred,
 * cgp_gather_end, cgp_gather_blocks_end.
 *
 * With interleave (CG_GATHER_INTERLEAVE in both programs) a block traces the quarter of the cone set
 * its place in a 2 x 2 of blocks picks (common/upsample.glsl's cg_upsample_interleave), and a pixel
 * sums the four subsets around it over their cone weights (cg_upsample_diffuse).
 *
 * With temporal = N > 1 (CG_GATHER_TEMPORAL in the block program) the blocks of one turn in N trace
 * each frame and each other block takes the light of the last frame's block where its pixel's point
 * was seen (the last camera's projection), where that light was traced at a surface that agrees with
 * the pixel's and is at most N - 1 frames old (cg_upsample_block_kept): the images of blocks and of
 * the surfaces traced are the state's, two of each (this frame's and the last's), kept from frame to
 * frame until the next prepare, whose first frame traces every block.
 */
#ifndef CGP_UPSAMPLE_H
#define CGP_UPSAMPLE_H

#include <stdbool.h>
#include <stddef.h>

#include "cg/error.h"
#include "cg/fg.h"
#include "sdk/cone.h"

/* The parameter, one entry of a gather's table. */
#define CGP_DOWNSAMPLE_PARAM                                                                          \
    { .name = "downsample", .type = FG_PARAM_INT, .default_value = 1, .min = 0, .max = 8,             \
      .allowed = FG_PARAM_VALUES(0, 1, 2, 4, 8), .stage = FG_STAGE_PREPARE,                           \
      .doc = "diffuse cones traced at one pixel of each downsample x downsample block, the full "    \
             "resolution rebuilt by joint bilateral upsampling with the G-buffer's position and "    \
             "normal (a pixel no block agrees with traces its own); 1: every pixel; 0: by the "       \
             "image's height, 4 below 540 rows and 8 from 540 up (blocks as many as 4 gives at "      \
             "640x360 or fewer); the specular and refracted cones always at every pixel "              \
             "(docs/results/gi-resolution.md)" }
/* The block size the parameter `downsample` gives for the frame's image: the parameter, or for 0
 * (auto) 4 below CGP_DOWNSAMPLE_AUTO_ROWS rows and 8 from them up. */
#define CGP_DOWNSAMPLE_AUTO_ROWS 540
int cgp_gather_downsample(const fg_pass *pass);

/* The second parameter, the entry after CGP_DOWNSAMPLE_PARAM. */
#define CGP_TEMPORAL_PARAM                                                                            \
    { .name = "temporal", .type = FG_PARAM_INT, .default_value = 1, .min = 1, .max = 4,               \
      .allowed = FG_PARAM_VALUES(1, 2, 4), .stage = FG_STAGE_PREPARE, .interactive = "4",             \
      .active_when = "downsample=0|2|4|8",                                                            \
      .doc = "blocks traced a frame: 1 in `temporal` (2: a checkerboard, 4: one of each 2 x 2), the "  \
             "others taking the light of the last frame's block where the last camera saw their pixel's " \
             "point (reprojection), where it was traced at the pixel's surface (normal and plane as the " \
             "upsampling compares them, and within a block's reach); a block whose surface changed "     \
             "traces again. A block's light is at most temporal - 1 frames old; the first frame after "  \
             "prepare traces every block, so a single frame is downsample's own, and a still camera's "  \
             "frames are too; 1: every block every frame (docs/results/gi-resolution.md)" }
/* The third, the entry after CGP_TEMPORAL_PARAM. */
#define CGP_INTERLEAVE_PARAM                                                                          \
    { .name = "interleave", .type = FG_PARAM_BOOL, .stage = FG_STAGE_PREPARE,                         \
      .active_when = "downsample=0|2|4|8",                                                            \
      .doc = "each block traces a quarter of the diffuse cones, the subset of its place in a 2 x 2 of " \
             "blocks (cones k with k mod 4 = its subset), and a pixel sums the four subsets of the 2 x 2 " \
             "blocks around it (each block as far as it agrees with the pixel, over the cone weights " \
             "of the subsets that agree): a quarter of the blocks' cones, the GI's detail of blocks twice " \
             "as wide (docs/results/gi-resolution.md); false: every block traces the whole set" }
typedef struct cgp_gather_blocks {
    int downsample;         /* the parameter; 1: nothing here is made or used */
    GLuint program;         /* the gather's shader with CG_GATHER_LOWRES */
    GLuint texture[2];      /* RGBA32F, one texel a block: what the programs write ([1]: temporal > 1) */
    int width, height;      /* blocks across and down: the image's size / downsample, rounded up */
    int temporal;           /* the parameter; 1: every block every frame */
    GLuint history[2][2];   /* temporal > 1: the surface each block's light was traced at, position
                             * (w: 1 for a surface) and normal (w: the light's age in frames), RGBA32F */
    int current;            /* temporal > 1: this frame's texture and history; the other is the last's */
    float previous_view_proj[16]; /* temporal > 1: the last frame's camera, for the reprojection */
    bool traced;            /* temporal > 1: the blocks hold a frame's light (not before the first) */
    GLuint deferred_program; /* the gather's shader with CG_GATHER_DEFERRED */
    GLuint listed_program;  /* with CG_GATHER_LOWRES and CG_GATHER_DEFERRED: the listed blocks' traces */
    GLuint deferred;        /* the pixels no block agrees with (CG_GATHER_DEFERRED_BLOCK, a pixel of the
                             * image each at most): 4 bytes a pixel, the state's */
} cgp_gather_blocks;

/* The defines the gather's full-resolution program needs ("#define CG_GATHER_DOWNSAMPLE D\n", and
 * "#define CG_GATHER_INTERLEAVE\n" with interleave), written to `out` (at most `size` bytes); "" for
 * downsample 1. */
const char *cgp_gather_blocks_define(const fg_pass *pass, char *out, size_t size);
/* In prepare(), after cgp_gather_prepare: for downsample > 1, the program of `shader` with `defines`
 * (the full-resolution program's, its CG_GATHER_DOWNSAMPLE included), the model's and the
 * material's defines as cgp_gather_prepare adds them, and CG_GATHER_LOWRES; the image of blocks
 * for the pass's output `radiance`. Owned by `state`. */
bool cgp_gather_blocks_prepare(void *state, const fg_pass *pass, const cgp_gather *g, cgp_gather_blocks *b,
                               const char *shader, const char *defines, cg_error *err);
/* In execute(), after cgp_gather_begin and the pass's own bindings, before cgp_gather_dispatch: runs
 * the block program over the blocks (everything cgp_gather_begin bound is its too), then binds
 * the blocks at CG_UNIT_GATHER_BLOCKS, the emptied list of deferred pixels, and the full-resolution
 * program and `radiance` again. Nothing for downsample 1. */
void cgp_gather_blocks_trace(const fg_pass *pass, const cgp_gather *g, cgp_gather_blocks *b);
/* After cgp_gather_dispatch: the deferred pixels' own cones (CG_GATHER_DEFERRED), over the list the
 * full-resolution dispatch made. Nothing for downsample 1. */
void cgp_gather_blocks_deferred(const fg_pass *pass, const cgp_gather *g, const cgp_gather_blocks *b);
/* After cgp_gather_end: unbinds the blocks. */
void cgp_gather_blocks_end(const cgp_gather_blocks *b);

#endif
