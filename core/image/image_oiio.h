/* image_oiio.h: internal interface of the OpenImageIO module (image_oiio.cpp, built as the
 * shared module libcg-oiio.so), the only C++ behind cg/image.h. image.c does everything else
 * (formats, transfer functions, temporary files) in C; oiio_module.c loads the module on first
 * use (cg_oiio), because OpenImageIO's 260 shared libraries cost every program that links
 * them half a second at start-up.
 *
 * The module holds none of core: what it needs of core (errors, image allocation) it calls
 * through the cg_oiio_host table the loader hands it, so it loads into any program, whether
 * or not that program exports its symbols.
 *
 * Declares: cg_oiio_transfer, cg_oiio_pixel_type, cg_oiio_host, cg_oiio_api,
 *           CG_OIIO_MODULE_ABI, cg_oiio_module (the module's one exported symbol), cg_oiio.
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

/* What the module may call in core. */
typedef struct cg_oiio_host {
    bool (*fail)(cg_error *err, cg_status status, const char *fmt, ...);
    bool (*image_alloc)(cg_image *img, int width, int height, cg_error *err);
    void (*image_free)(cg_image *img);
} cg_oiio_host;

/* The module's functions. */
typedef struct cg_oiio_api {
    /* Reads subimage 0, mip 0 of any file OIIO reads into out (allocated here) as RGBA
     * float, rows top to bottom, channel values as stored (integers normalised to [0,1],
     * no transfer function undone); grey becomes RGB, missing alpha is 1. The file's
     * oiio:ColorSpace attribute goes to colour_space (for messages); bits and floating: its
     * sample type. Alpha is never multiplied into or divided out of the colour channels, on
     * reading or writing. */
    bool (*read)(const char *path, cg_image *out, cg_oiio_transfer *transfer, float *gamma, char *colour_space,
                 size_t colour_space_size, int *bits, bool *floating, cg_error *err);

    /* Writes width x height RGBA pixels to `path` in the format its extension names, stored
     * as `type`; srgb tags the file as sRGB-encoded. Writes `path` itself: atomicity is the
     * caller's. On failure a partly written `path` may remain. */
    bool (*write)(const char *path, int width, int height, cg_oiio_pixel_type type, const void *pixels, bool srgb,
                  cg_error *err);

    /* cg_image_read_samples (cg/image.h), all but the file's existence, which the caller checks. */
    bool (*read_samples)(const char *path, long long max_samples, cg_image_samples *out, cg_error *err);
} cg_oiio_api;

/* Raised whenever cg_oiio_host or cg_oiio_api changes, so that a stale module is refused. */
#define CG_OIIO_MODULE_ABI 1

/* The module's entry point, looked up by this name: its functions, or NULL when it was built
 * for another ABI. `host` must outlive every call. */
#define CG_OIIO_MODULE_ENTRY "cg_oiio_module"
typedef const cg_oiio_api *cg_oiio_module_fn(int abi, const cg_oiio_host *host);
cg_oiio_module_fn cg_oiio_module;

/* The module's functions, loading it on the first call (thread-safe); NULL with *err filled
 * (CG_ERR_IO: which file was looked for, and why it did not load) when it cannot be loaded. */
const cg_oiio_api *cg_oiio(cg_error *err);

#ifdef __cplusplus
}
#endif

#endif
