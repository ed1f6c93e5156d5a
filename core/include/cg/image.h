/* cg/image.h: float RGBA images, read and written through OpenImageIO.
 *
 * Declares: cg_image, cg_image_alloc, cg_image_free, cg_image_read, cg_image_file_info,
 *           cg_image_read_info, cg_image_write, cg_image_samples, cg_image_read_samples,
 *           cg_image_samples_free, cg_image_io_check, cg_srgb_encode, cg_srgb_decode.
 *
 * Pixels are linear float RGBA, rows top to bottom (as files store them; GL read-backs
 * are flipped by the caller). .exr is written as linear half or float; .png as 8-bit
 * sRGB-encoded (values clamped to [0,1] after encoding; no tonemap here).
 * Every write goes to a temporary file beside the target, renamed into place, so a
 * failure never leaves a partial or clobbered file.
 *
 * OpenImageIO is loaded on the first read or write, not at program start (it brings some
 * 260 shared libraries, half a second of start-up for every program that links it); a
 * program that never touches an image never loads it. When its module cannot be loaded,
 * reads and writes fail with CG_ERR_IO and say which file was looked for.
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

/* One channel of a data image (an elevation map, say), its samples as stored: integers as
 * the integers (a 16-bit PNG gives 0..65535, not [0, 1]), floating-point samples as they are,
 * no colour conversion of any kind (an sRGB tag or a gAMA chunk is ignored). */
typedef struct cg_image_samples {
    int width, height;      /* samples per row, rows */
    float *value;           /* width x height, row 0 first (the image's top row) */
    char format[32];        /* the file's sample type as OpenImageIO names it (uint16, float, ...) */
} cg_image_samples;

/* Reads channel 0 of subimage 0 of `path` into *out. Fails with CG_ERR_FILE_NOT_FOUND, or
 * CG_ERR_IMAGE_FORMAT for a file that is not an image, a 3D image, or one of more than
 * max_samples samples (checked before any pixel is read). */
bool cg_image_read_samples(const char *path, long long max_samples, cg_image_samples *out, cg_error *err);
void cg_image_samples_free(cg_image_samples *s);

/* Loads OpenImageIO now: for a program that writes its first image only after long work, so
 * that a broken installation fails before that work, not after it (CG_ERR_IO). */
bool cg_image_io_check(cg_error *err);

float cg_srgb_encode(float linear);
float cg_srgb_decode(float encoded);

#endif
