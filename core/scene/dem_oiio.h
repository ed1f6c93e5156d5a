/* dem_oiio.h: the OpenImageIO adapter of the DEM loader (dem_oiio.cpp): one channel of an
 * elevation image, its sample values as stored.
 *
 * Declares: cg_dem_samples, cg_dem_read, cg_dem_samples_free.
 */
#ifndef CG_DEM_OIIO_H
#define CG_DEM_OIIO_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "cg/error.h"

typedef struct cg_dem_samples {
    int width, height;      /* samples per row, rows */
    float *value;           /* width x height, row 0 first (the image's top row) */
    char format[32];        /* the file's sample type as OIIO names it (uint16, float, ...) */
} cg_dem_samples;

/* Reads channel 0 of subimage 0 of `path` (a 16-bit PNG, a TIFF, or any single- or
 * multi-channel image OIIO reads): integer samples as the integers stored (not normalised
 * to [0, 1]: a 16-bit PNG gives 0..65535), floating-point samples as stored; no colour
 * conversion of any kind. Fails with CG_ERR_FILE_NOT_FOUND or CG_ERR_IMAGE_FORMAT. */
bool cg_dem_read(const char *path, cg_dem_samples *out, cg_error *err);
void cg_dem_samples_free(cg_dem_samples *s);

#ifdef __cplusplus
}
#endif

#endif
