/* apps/demo/demo_view.h: the resource viewer's drawing: one level of any texture resource of a
 * compiled graph (a 2D texture, a layer of a 2D array, a slice of a 3D texture) into an 8-bit
 * texture that the UI shows (shaders/demo/view.frag). Texels are fetched, never filtered, so
 * the picture holds the stored values:
 * - float and normalized colours: x 2^exposure, then sRGB-encoded by the framebuffer, or shown
 *   as stored when they are display values already (8-bit ones such as an ldr output);
 * - depth: grey, lo..hi mapped to black..white (fitted to the values when first shown);
 * - integers (counts, summed-area tables): grey per channel likewise.
 * One channel (R, G, B, A) can be shown as grey instead of RGB.
 *
 * Declares: demo_view_class, demo_view_settings, DEMO_VIEW_MAX_SIZE, demo_view,
 *           demo_view_create, demo_view_destroy, demo_view_class_of, demo_view_defaults,
 *           demo_view_level_size, demo_view_fit, demo_view_draw.
 */
#ifndef CONEGRAPH_DEMO_VIEW_H
#define CONEGRAPH_DEMO_VIEW_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/fg.h"
#include "cg/gl.h"

typedef enum demo_view_class {
    DEMO_VIEW_COLOUR,           /* float, normalized (unorm, snorm) */
    DEMO_VIEW_DEPTH,
    DEMO_VIEW_UINT,
    DEMO_VIEW_INT,
    DEMO_VIEW_CLASS_COUNT
} demo_view_class;

typedef struct demo_view_settings {
    int level;                  /* mip level */
    int layer;                  /* 3D: slice at that level; 2D array: layer */
    int channel;                /* 0: RGB; 1..4: R, G, B or A as grey */
    double exposure;            /* colour: values x 2^exposure */
    bool srgb;                  /* colour: sRGB-encode (linear values); off: as stored */
    double lo, hi;              /* depth, integers: lo is black, hi white */
} demo_view_settings;

/* The longest side of the viewer's picture; larger levels are shown a texel every few. */
#define DEMO_VIEW_MAX_SIZE 1024

typedef struct demo_view {
    GLuint programs[3][DEMO_VIEW_CLASS_COUNT]; /* [2D, 3D, 2D array][class], compiled when first used */
    GLuint vao;                 /* core profile: a draw needs one bound, even with no attributes */
    GLuint fbo, sampler;
    GLuint target;              /* SRGB8_ALPHA8, drawn into */
    GLuint shown;               /* the same texels viewed as RGBA8: what the UI samples, unconverted */
    int width, height;
} demo_view;

/* With the GL context current. */
void demo_view_create(demo_view *view);
void demo_view_destroy(demo_view *view);
/* What kind of values a texture holds (asked of GL, so any sized format is known). */
demo_view_class demo_view_class_of(GLuint texture);
/* Settings that show a fresh resource (its texture, desc and class): level 0, the middle slice
 * of a volume, else layer 0, RGB, exposure 0; sRGB encoding unless it holds 8-bit normalized
 * values; depth 0..1 and integers 0..255 until fitted (demo_view_fit). */
void demo_view_defaults(GLuint texture, const fg_resource_desc *desc, demo_view_class cls,
                        demo_view_settings *out);
/* Texels of `desc` at `level`: width, height and slices (3D: shrinking with the level; 2D
 * array: its layers; 2D: 1). */
void demo_view_level_size(const fg_resource_desc *desc, int level, int *width, int *height, int *slices);
/* Reads the shown level and slice back (the settings clamped to the resource first) and fits
 * the mapping to the values of the shown channels: a colour's exposure so that its largest
 * finite value is white, depth's and integers' lo and hi to their smallest and largest
 * (kept when nothing is finite). False, the settings kept, when the level cannot be read
 * back (out of memory, or more than 2 GiB). */
bool demo_view_fit(GLuint texture, const fg_resource_desc *desc, demo_view_class cls, demo_view_settings *settings,
                   cg_error *err);
/* Draws `texture` (described by `desc`, of class cls) into view->shown, resized to the level
 * (at most DEMO_VIEW_MAX_SIZE on a side); the settings are clamped to the resource first.
 * Leaves the window's framebuffer bound for drawing, no program, vertex array, texture or
 * sampler on unit 0, and the viewport and the enables it touches as it found them. Fails only
 * when its shader does not build. */
bool demo_view_draw(demo_view *view, GLuint texture, const fg_resource_desc *desc, demo_view_class cls,
                    demo_view_settings *settings, cg_error *err);

#endif
