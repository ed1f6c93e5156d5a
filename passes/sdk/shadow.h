/* sdk/shadow.h (pass SDK): a pass that reads a shadow map (shaders/common/shadow.glsl).
 *
 * Declares: cgp_declare_shadow_inputs, cgp_no_shadow, cgp_no_shadow_create, cgp_bind_shadow.
 *
 * The shadow map is an optional pair of inputs, `shadow` (a shadow_map pass's `depth`) and
 * `shadow_matrix` (its `matrix`, the block CG_SHADOW_BLOCK of common/blocks.h). Without them one
 * shader still serves: cgp_bind_shadow() binds a block whose light index is -1 (no light is
 * shadowed) and a depth map at the far plane, objects the pass creates in prepare() and its state
 * owns (cgp_state_new, sdk/pass.h).
 */
#ifndef CGP_SHADOW_H
#define CGP_SHADOW_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/fg.h"

/* Declares the optional inputs `shadow` and `shadow_matrix`; fails when only one is connected
 * (CG_ERR_GRAPH_MISSING_INPUT), when `shadow` is not GL_DEPTH_COMPONENT32F or `shadow_matrix`
 * smaller than a CG_SHADOW_BLOCK (CG_ERR_GRAPH_INCOMPATIBLE). */
bool cgp_declare_shadow_inputs(fg_pass *pass, fg_declare *decl, cg_error *err);

/* The shadow inputs' slots and the "no shadow map" fallback of one pass. */
typedef struct cgp_no_shadow {
    fg_slot shadow, matrix; /* the inputs `shadow` and `shadow_matrix` */
    GLuint block;   /* CG_SHADOW_BLOCK with light index -1 */
    GLuint map;     /* 1x1 GL_DEPTH_COMPONENT32F at the far plane */
} cgp_no_shadow;

/* In prepare(): the slots of a pass that called cgp_declare_shadow_inputs, and the fallback. */
void cgp_no_shadow_create(void *state, const fg_pass *pass, cgp_no_shadow *out);

/* Binds the pass's inputs `shadow` at `texture_unit` and `shadow_matrix` at CG_BINDING_SHADOW,
 * or the fallback where they are absent. */
void cgp_bind_shadow(const fg_pass *pass, const cgp_no_shadow *fallback, GLuint texture_unit);

#endif
