/* cg/pt_render.h: the CPU path tracer (Embree 3): the reference behind the path_trace pass and bench.
 *
 * Declares: PT_RENDER_VERSION, pt_settings, pt_settings_default, pt_scene, pt_scene_create, pt_scene_destroy,
 *           pt_scene_triangle_count, pt_render, pt_part, pt_part_name, pt_render_parts.
 *
 * Pure C, no GL: it renders a cg_scene seen through a cg_view into linear float RGBA
 * (rows top to bottom, as cg_image stores them), so tests and `conegraph bench` can use
 * it without a context. Physics and units are those of cg/scene.h (docs/architecture.md, "Units and conventions"):
 *   - glTF 2.0's BSDF (cg/bsdf.h: Lambertian diffuse, GGX reflection, GGX transmission) from
 *     base colour (factor x texture; bilinear, repeat, sRGB-decoded before filtering as GL does
 *     for SRGB8_ALPHA8; no mipmaps), metallic-roughness (B, G) and transmission (R) textures,
 *     normal map (with cg_mesh.tangents), each through its KHR_texture_transform; occlusion is
 *     ignored (a raster approximation of what the tracer computes). A material with specular 0
 *     and no metal or transmission is the pure Lambertian of before, computed as before;
 *   - solid transmissive materials (thickness > 0) refract by Snell at each face (entering or
 *     leaving by the geometric normal's side) with Beer-Lambert exp(-sigma t) over the length t
 *     a ray travels inside (a ray that hits a solid's back face travelled inside it);
 *     thickness 0 is a thin sheet the ray crosses unrefracted (blurred by the roughness);
 *   - alphaMode MASK: where alpha < cutoff the surface is not there for any ray; BLEND: any
 *     ray (camera, bounce and shadow rays alike) passes with probability 1 - alpha, decided by
 *     a hash of the ray's random key and the triangle (stochastic, deterministic). Passing is
 *     no scattering: it counts in no bounce limit. doubleSided false: camera rays do not see
 *     back faces; every other ray sees both sides (Embree filter functions);
 *   - emissive radiance = emissive x emissive texture x emissive_strength, seen from
 *     both sides of a surface;
 *   - punctual lights by next-event estimation (the full BSDF evaluated, reflection lobes),
 *     shadows hard except a directional light's with angular_diameter > 0, whose direction is
 *     drawn uniformly (in solid angle) in the cone of half that angle, E unchanged; directional
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
 *     uniformly on it, and that sample is combined with the BSDF-sampled continuation
 *     by the power heuristic (MIS, with cg_bsdf_pdf); both sides of an emitter emit; the sky
 *     the same way. Light sampling covers the reflection side only: what arrives through a
 *     transmission lobe (and through a smooth lobe) is found by BSDF sampling alone (MIS weight 1);
 *     a shadow ray is stopped by any surface that is there (glass included: a point light
 *     through refracting glass cannot be sampled; light through glass is a caustic);
 *   - bounce limits per kind, each as `bounces` always counted (as Cycles and pbrt count): a
 *     path's scatterings are labelled diffuse, glossy (any reflection off a microfacet lobe,
 *     glass included) or transmission (refraction, or crossing a thin sheet); a vertex reached
 *     after k_d diffuse, k_g glossy and k_t transmission scatterings is shaded (lit directly
 *     and scattered on) while k_d <= bounces, k_g <= glossy_bounces and k_t <= transmission_bounces;
 *     the first vertex beyond a limit adds only the emission it shows (its MIS half) and ends
 *     the path. So bounces n = 0 is the direct light of every source; each bounce adds a
 *     diffuse reflection. A white furnace of Lambertian albedo a and emission L gives
 *     L x sum_{k=0..n+1} a^k (to noise: the MIS estimate is not constant per sample);
 *   - caustics false: after a diffuse scattering the glossy and transmission lobes are removed
 *     (neither sampled nor evaluated), as Cycles' caustics_reflective and caustics_refractive
 *     off; a glass is then black to such paths, and it casts a full shadow either way.
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
#define PT_RENDER_VERSION 4

typedef struct pt_settings {
    int spp;            /* samples per pixel, >= 1 */
    int bounces;        /* diffuse bounces as Cycles counts them (0 = direct light), >= 0 */
    uint32_t seed;
    int threads;        /* render threads; 0 = one per online core */
    bool jitter;        /* false: every sample through the pixel centre, exactly the raster
                         * camera's rays; true: uniform over the pixel (box-filtered edges) */
    bool progress;      /* progress with the time left on stderr (cg/progress.h) */
    int glossy_bounces; /* glossy reflections as Cycles counts them, >= 0 */
    int transmission_bounces; /* refractions and thin-sheet crossings, >= 0 */
    bool caustics;      /* false: glossy and transmission lobes only before the first diffuse
                         * scattering of a path (Cycles' caustics_reflective/_refractive off) */
} pt_settings;

/* spp 64, bounces 1, glossy_bounces 1, transmission_bounces 4, caustics false, seed 1, all
 * cores, pixel centres, no progress lines. */
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

/* The parts of the image by where the light comes from and how often it was scattered,
 * counted in the same trace: they add up to pt_render's image (to float rounding; the image
 * itself does not depend on whether parts are asked for). Every scattering counts, whatever
 * its kind (diffuse, glossy, transmission); passing through a BLEND layer or a MASK hole does
 * not. So "direct" is light scattered once, at the surface the camera ray lands on: its
 * diffuse light and its glossy highlights of the sources, what a raster direct pass computes
 * (shadow-mapped lights with GGX highlights, emission). A mirror's or a glass's view of a lit
 * wall is scattered twice or more: "indirect", with the cone tracers' specular and refracted
 * cones, so that `compare --direct ... --ref-direct` (GI = image - direct) holds every cone's
 * light, diffuse and specular, on both sides. The emitters and sky seen in a mirror or
 * through a glass (one scattering) are direct_emitters and direct_sky. */
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
