/* sdk/sky.h (pass SDK): the scene's sky baked into a small prefiltered environment texture that
 * the cone tracers and composite read (shaders/common/sky.glsl).
 *
 * Declares: CGP_SKY_WIDTH, CGP_SKY_HEIGHT, CGP_SKY_LAYERS, CGP_SKY_BYTES, cgp_sky_direction,
 *           cgp_sky_layer_half_angle, cgp_sky_bake, cgp_sky, cgp_sky_prepare, cgp_sky_update,
 *           cgp_sky_bind, cgp_sky_unbind.
 *
 * The sky is evaluated by one implementation, cg_sky_model_radiance (core/scene/sky.c), here on
 * the CPU, once per change of the sky (its value, and for a Preetham sky the lights' stamp, since
 * it follows the sun); the passes of a process that read the same sky share one bake (the last
 * one is kept, keyed by its cg_sky_model) and each upload it. The texture is a 3D texture of CGP_SKY_LAYERS lat-long layers of
 * CGP_SKY_WIDTH x CGP_SKY_HEIGHT texels, RGBA32F (radiance of any brightness):
 *   layer 0      the sky's radiance at each texel centre (the background; the narrowest cones),
 *   layer k > 0  the cosine-weighted mean of the sky over a cone of half angle
 *                theta_k = (pi / CGP_SKY_HEIGHT) 2^(k-1) around the texel's direction
 *                (2.8125 degrees at layer 1, 90 degrees at layer 6: a whole hemisphere),
 * so that a cone of half angle theta reads it at the layer of theta, filtered linearly between
 * layers and texels, in one texture fetch. Cosine-weighted about the cone's axis: for the
 * one-cone set (the hemisphere around the normal) that is the exact irradiance / pi of the
 * unoccluded sky; for narrower cones it approaches the plain mean. A uniform sky is L in every
 * texel of every layer, exactly (no sum is formed), so that a cone gathers exactly L.
 *
 * Lat-long: texel (i, j) is centred on phi = 2 pi (i + 0.5) / W - pi (atan2(x, z)), theta =
 * pi (j + 0.5) / H from +y (the zenith): dir = (sin theta sin phi, cos theta, sin theta cos phi).
 */
#ifndef CGP_SKY_H
#define CGP_SKY_H

#include <stdbool.h>
#include <stdint.h>

#include "cg/error.h"
#include "cg/scene.h"
#include "sdk/blocks.h"

#define CGP_SKY_WIDTH 128
#define CGP_SKY_HEIGHT 64
#define CGP_SKY_LAYERS 7
/* RGBA32F texels of the whole texture: 917,504 bytes. */
#define CGP_SKY_BYTES ((size_t)CGP_SKY_WIDTH * CGP_SKY_HEIGHT * CGP_SKY_LAYERS * 4 * sizeof(float))

/* The unit direction at the centre of texel (i, j). */
void cgp_sky_direction(int i, int j, double dir[3]);
/* theta_k of layer k (0 for layer 0), radians. */
double cgp_sky_layer_half_angle(int layer);

/* Bakes the scene's sky into `texels` (CGP_SKY_BYTES, layer-major, then rows, then RGBA).
 * Fails as cg_sky_model_init does (a Preetham sky without a directional light). */
bool cgp_sky_bake(const cg_scene *scene, float *texels, cg_error *err);

/* A pass's baked sky: made in prepare(), updated and bound in execute(). */
typedef struct cgp_sky {
    GLuint texture;         /* 0 until a sky that is not none is baked */
    GLuint sampler;         /* linear, repeat in phi, clamped in theta and between layers */
    GLuint block;           /* CG_SKY_BLOCK */
    bool present;           /* the last update found a sky (not CG_SKY_NONE) */
    bool baked;             /* `sky` and `lights_revision` hold what was baked */
    cg_sky sky;
    uint64_t lights_revision;
    uint64_t bakes;         /* uploads of a new bake so far (a frame with the same sky makes none) */
} cgp_sky;

/* In prepare(): the sampler and the block, owned by `state` (cgp_state_new). */
void cgp_sky_prepare(void *state, cgp_sky *sky);
/* In execute(): bakes the frame's scene's sky when it changed since the last bake (none: no
 * texture is made and nothing is baked), and uploads the block. `scene` may be NULL (none). */
bool cgp_sky_update(void *state, cgp_sky *sky, const cg_scene *scene, cg_error *err);
/* Binds the texture at CG_UNIT_SKY and the block at CG_BINDING_SKY (with no sky the block says
 * so and the shader reads nothing); cgp_sky_unbind undoes the sampler binding. */
void cgp_sky_bind(const cgp_sky *sky);
void cgp_sky_unbind(void);

#endif
