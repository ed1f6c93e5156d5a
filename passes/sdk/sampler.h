/* sdk/sampler.h (pass SDK): the sampler objects through which passes read the lightmaps.
 *
 * Declares: cgp_sampler_volume, cgp_sampler_volume_one_level, cgp_sampler_lightmap2d, cgp_sampler_table.
 *
 * Each returns a new GL sampler object owned by a pass state (cgp_state_new, sdk/pass.h).
 */
#ifndef CGP_SAMPLER_H
#define CGP_SAMPLER_H

#include <glad/gl.h>

/* A 3D lightmap: trilinear within and between mip levels; outside the volume reads as empty
 * space (clamped to a border of zero radiance and zero opacity). */
GLuint cgp_sampler_volume(void *state);

/* The same within the nearest mip level only: a read at a whole level touches its 2x2x2 texels
 * alone, where cgp_sampler_volume's reads two levels (the surface march's emptiness test,
 * shaders/common/cone_trace.glsl). */
GLuint cgp_sampler_volume_one_level(void *state);

/* A 2D lightmap: trilinear, edges clamped (the terrain's border continues outward in a
 * filtered sample; texel fetches read only texels inside). */
GLuint cgp_sampler_lightmap2d(void *state);

/* An integer table (the HSAT pyramid or SATs): nearest texel of the nearest level, the only
 * filtering under which an integer texture is complete. */
GLuint cgp_sampler_table(void *state);

#endif
