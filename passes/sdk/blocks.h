/* sdk/blocks.h (pass SDK): the bindings, texture units and block layouts that C shares with
 * GLSL, for C. They are defined once, in shaders/common/blocks.h, which GLSL includes too.
 *
 * Declares: what shaders/common/blocks.h provides in C (CG_BINDING_*, CG_UNIT_*, the block
 *           structs cg_*_block); cgp_uniform_buffer, cgp_uniform_upload.
 *
 * cg/gpu_scene.h comes first: core defines CG_BINDING_MATERIALS and CG_BINDING_LIGHTS for itself
 * (core cannot see shaders/), and a differing definition here would be a compile error.
 */
#ifndef CGP_BLOCKS_H
#define CGP_BLOCKS_H

#include <stddef.h>
#include <stdint.h>

#include "cg/gpu_scene.h"
#include "common/blocks.h"

/* A uniform buffer of `bytes` for a pass's own block, updated every execute, owned by the pass
 * state (cgp_state_new, sdk/pass.h). */
GLuint cgp_uniform_buffer(void *state, size_t bytes);
/* Writes a block into `buffer` and binds it at `binding` (a CG_BINDING_* uniform binding). */
void cgp_uniform_upload(GLuint buffer, GLuint binding, const void *block, size_t bytes);

#endif
