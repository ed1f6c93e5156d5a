/* cg/pt_render.h: the CPU path tracer (Embree 3): the reference behind the path_trace pass and bench.
 *
 * Declares: PT_RENDER_VERSION, pt_settings, pt_settings_default, pt_scene, pt_scene_create, pt_scene_destroy,
 *           pt_scene_triangle_count, pt_render, pt_part, pt_part_name, pt_render_parts.
 *
 * Pure C, no GL: it renders a cg_scene seen through a cg_view into linear float RGBA
 * (rows top to bottom, as cg_image stores them), so tests and `conegraph bench` can use
 * it without a context. Physics and units are those of cg/scene.h (docs/architecture.md, "Units and conventions"):
 *   - Lambertian surfaces, albedo = base_color x base colour texture (bilinear, repeat,
 *     sRGB-decoded before filtering as GL does for SRGB8_ALPHA8; no mipmaps);
 *   - emissive radiance = emissive x emissive texture x emissive_strength, seen from
 *     both sides of a surface;
 *   - punctual lights by next-event estimation with hard shadows: directional
 *     E = intensity x color, point E = I/d^2, spot as point times the
 *     KHR_lights_punctual cone falloff; `range` > 0 applies the extension's
 *     recommended smooth window;
 *   - camera rays through pixel centres (or spread over the pixel), built in camera space
 *     in double precision from the eye (perspective) or the near plane (orthographic), so
 *     that they are exact at any distance from the origin;
 *   - hit points from the barycentrics on the world-space vertices; rays leave a surface
 *     from a point pushed along its normal by 2^-19 times the magnitude of the triangle's
 *     coordinates, with no absolute term: the image does not depend on the scene's scale;
 *   - emissive triangles are lights too: one is chosen per vertex by power, a point
 *     uniformly on it, and that sample is combined with the cosine-sampled continuation
 *     by the power heuristic (MIS); both sides of an emitter emit;
 *   - `bounces` n counts as Cycles and pbrt count: the path x1..x(n+1) from the camera,
 *     every vertex lit directly by every source (punctual lights and emitters), plus the
 *     emission the camera sees. n = 0 is the direct light of every source; each bounce adds
 *     a diffuse reflection. A white furnace of albedo a and emission L gives
 *     L x sum_{k=0..n+1} a^k (to noise: the MIS estimate is not constant per sample).
 * Determinism: each sample draws from a counter-based generator keyed by (seed, pixel,
 * sample), and a pixel's samples are summed in a fixed order, so the image is
 * bit-identical whatever the thread count or tile schedule.
 */
#ifndef CG_PT_RENDER_H
#define CG_PT_RENDER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cg/camera.h"
#include "cg/error.h"
#include "cg/scene.h"

/* Bumped whenever a change makes pt_render give other images for the same input, so that
 * images cached by `conegraph bench` are not reused across it. */
#define PT_RENDER_VERSION 3

typedef struct pt_settings {
    int spp;            /* samples per pixel, >= 1 */
    int bounces;        /* diffuse bounces as Cycles counts them (0 = direct light), >= 0 */
    uint32_t seed;
    int threads;        /* render threads; 0 = one per online core */
    bool jitter;        /* false: every sample through the pixel centre, exactly the raster
                         * camera's rays; true: uniform over the pixel (box-filtered edges) */
    bool progress;      /* progress bar on stderr */
} pt_settings;

/* spp 64, bounces 1, seed 1, all cores, pixel centres, no progress bar. */
pt_settings pt_settings_default(void);

typedef struct pt_scene pt_scene;

/* Builds the BVH (one Embree geometry per instance, vertices transformed to world space)
 * and linear copies of the textures. The cg_scene must outlive the pt_scene. */
bool pt_scene_create(const cg_scene *scene, pt_scene **out, cg_error *err);
void pt_scene_destroy(pt_scene *pts);
size_t pt_scene_triangle_count(const pt_scene *pts);

/* Renders view->width x view->height pixels into rgba (width*height*4 floats, rows top
 * to bottom, alpha 1). Fails with CG_ERR_USAGE on bad settings. If rays_traced is not
 * NULL it receives the number of rays cast (camera, bounce and shadow rays). */
bool pt_render(const pt_scene *pts, const cg_view *view, const pt_settings *settings,
               float *rgba, uint64_t *rays_traced, cg_error *err);

/* The parts of the image by where the light comes from and how often it was reflected,
 * counted in the same trace: they add up to pt_render's image (to float rounding; the image
 * itself does not depend on whether parts are asked for). */
typedef enum pt_part {
    PT_PART_EMITTED,         /* emission and sky the camera sees (no reflection) */
    PT_PART_DIRECT_PUNCTUAL, /* light of punctual lights reflected once */
    PT_PART_DIRECT_EMITTERS, /* light of emissive surfaces reflected once */
    PT_PART_DIRECT_SKY,      /* sky light reflected once */
    PT_PART_INDIRECT,        /* light of any source reflected twice or more (the bounces) */
    PT_PART_COUNT
} pt_part;

/* "emitted", "direct_punctual", "direct_emitters", "direct_sky", "indirect". */
const char *pt_part_name(pt_part part);

/* pt_render, and each parts[k] that is not NULL (parts itself may be NULL) receives part k
 * as an image like rgba. */
bool pt_render_parts(const pt_scene *pts, const cg_view *view, const pt_settings *settings,
                     float *rgba, float *const parts[PT_PART_COUNT], uint64_t *rays_traced, cg_error *err);

#endif
