/* cg/image.h: float RGBA images, read and written through OpenImageIO.
 *
 * Declares: cg_image, cg_image_alloc, cg_image_free, cg_image_read, cg_image_file_info,
 *           cg_image_read_info, cg_image_write, cg_srgb_encode, cg_srgb_decode.
 *
 * Pixels are linear float RGBA, rows top to bottom (as files store them; GL read-backs
 * are flipped by the caller). .exr is written as linear half or float; .png as 8-bit
 * sRGB-encoded (values clamped to [0,1] after encoding; no tonemap here).
 * Every write goes to a temporary file beside the target, renamed into place, so a
 * failure never leaves a partial or clobbered file.
 */
#ifndef CG_IMAGE_H
#define CG_IMAGE_H

#include <stdbool.h>

#include "cg/error.h"

typedef struct cg_image {
    int width, height;
    float *rgba;            /* width x height x 4 */
} cg_image;

typedef enum cg_image_exr_type {
    CG_EXR_HALF,
    CG_EXR_FLOAT
} cg_image_exr_type;

bool cg_image_alloc(cg_image *img, int width, int height, cg_error *err);
void cg_image_free(cg_image *img);

/* Reads any format OIIO reads into linear RGBA: 8-bit formats are sRGB-decoded when
 * the file says sRGB (PNG, JPEG by default); grey becomes RGB, missing alpha is 1. */
bool cg_image_read(const char *path, cg_image *out, cg_error *err);

/* What a file held before cg_image_read made it linear float RGBA. */
typedef struct cg_image_file_info {
    bool display_encoded;   /* through a transfer function (sRGB, Rec. 709, a gamma) that reading
                             * undid: an image made for display, not linear radiance */
    bool floating;          /* floating-point samples (half, float), not integers */
    int bits;               /* bits per sample as stored */
    char colour_space[64];  /* the file's oiio:ColorSpace, "" when it names none */
} cg_image_file_info;

/* cg_image_read, and what the file held in *info. */
bool cg_image_read_info(const char *path, cg_image *out, cg_image_file_info *info, cg_error *err);

/* Chooses the format from the extension: .exr (exr_type) or .png. */
bool cg_image_write(const char *path, const cg_image *img, cg_image_exr_type exr_type, cg_error *err);

float cg_srgb_encode(float linear);
float cg_srgb_decode(float encoded);

#endif
