/* image_oiio.h: internal interface of the OpenImageIO adapter (image_oiio.cpp), the only
 * C++ behind cg/image.h. image.c does everything else (formats, transfer functions,
 * temporary files) in C.
 *
 * Declares: cg_oiio_transfer, cg_oiio_pixel_type, cg_oiio_read, cg_oiio_write.
 */
#ifndef CG_IMAGE_OIIO_H
#define CG_IMAGE_OIIO_H

#include <stdbool.h>
#include <stddef.h>

/* The project's C headers carry no extern "C" of their own: give them C linkage here. */
#ifdef __cplusplus
extern "C" {
#endif

#include "cg/error.h"
#include "cg/image.h"

/* The transfer function a file declares for its colour channels. */
typedef enum cg_oiio_transfer {
    CG_OIIO_LINEAR,
    CG_OIIO_SRGB,
    CG_OIIO_REC709, /* BT.709 OETF: what OIIO reports for PNM files */
    CG_OIIO_GAMMA,  /* value^gamma */
    CG_OIIO_OTHER   /* a colour space not converted here: pixels are used as stored */
} cg_oiio_transfer;

typedef enum cg_oiio_pixel_type {
    CG_OIIO_UINT8, /* pixels are unsigned char */
    CG_OIIO_HALF,  /* pixels are float, stored as half */
    CG_OIIO_FLOAT  /* pixels are float */
} cg_oiio_pixel_type;

/* Reads subimage 0, mip 0 of any file OIIO reads into out (allocated here) as RGBA
 * float, rows top to bottom, channel values as stored (integers normalised to [0,1],
 * no transfer function undone); grey becomes RGB, missing alpha is 1. The file's
 * oiio:ColorSpace attribute goes to colour_space (for messages); bits and floating: its
 * sample type. Alpha is never multiplied into or divided out of the colour channels, on
 * reading or writing. */
bool cg_oiio_read(const char *path, cg_image *out, cg_oiio_transfer *transfer, float *gamma,
                  char *colour_space, size_t colour_space_size, int *bits, bool *floating, cg_error *err);

/* Writes width x height RGBA pixels to `path` in the format its extension names, stored
 * as `type`; srgb tags the file as sRGB-encoded. Writes `path` itself: atomicity is the
 * caller's. On failure a partly written `path` may remain. */
bool cg_oiio_write(const char *path, int width, int height, cg_oiio_pixel_type type,
                   const void *pixels, bool srgb, cg_error *err);

#ifdef __cplusplus
}
#endif

#endif
