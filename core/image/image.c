/* Float RGBA images: allocation, sRGB transfer functions, and the format and atomicity
 * rules of cg/image.h around the OpenImageIO module (image_oiio.cpp, loaded by cg_oiio). */
#include "cg/image.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "cg/fs.h"
#include "cg/log.h"
#include "image_oiio.h"

bool
cg_image_alloc(cg_image *img, int width, int height, cg_error *err)
{
    img->width = img->height = 0;
    img->rgba = NULL;
    if (width <= 0 || height <= 0)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "image size %dx%d: expected a positive width and height", width,
                       height);
    if ((size_t)width > SIZE_MAX / 4 / sizeof(float) / (size_t)height)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "image size %dx%d is too large", width, height);
    img->rgba = calloc((size_t)width * height * 4, sizeof(float));
    if (!img->rgba)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory for a %dx%d image", width, height);
    img->width = width;
    img->height = height;
    return true;
}

void
cg_image_free(cg_image *img)
{
    if (!img)
        return;
    free(img->rgba);
    img->rgba = NULL;
    img->width = img->height = 0;
}

/* IEC 61966-2-1 (sRGB), the piecewise curve, not the 2.2 approximation. */
float
cg_srgb_encode(float linear)
{
    if (linear <= 0.0031308f)
        return 12.92f * linear;
    return 1.055f * powf(linear, 1.0f / 2.4f) - 0.055f;
}

float
cg_srgb_decode(float encoded)
{
    if (encoded <= 0.04045f)
        return encoded / 12.92f;
    return powf((encoded + 0.055f) / 1.055f, 2.4f);
}

/* Undoes a file's transfer function. BT.709's inverse OETF: V < 0.081 ? V / 4.5 :
 * ((V + 0.099) / 1.099)^(1 / 0.45) (ITU-R BT.709-6, item 1.2). */
static float
decode(cg_oiio_transfer transfer, float gamma, float v)
{
    switch (transfer) {
    case CG_OIIO_SRGB: return cg_srgb_decode(v);
    case CG_OIIO_REC709: return v < 0.081f ? v / 4.5f : powf((v + 0.099f) / 1.099f, 1.0f / 0.45f);
    case CG_OIIO_GAMMA: return powf(v, gamma);
    case CG_OIIO_LINEAR:
    case CG_OIIO_OTHER: break;
    }
    return v;
}

bool
cg_image_read_info(const char *path, cg_image *out, cg_image_file_info *info, cg_error *err)
{
    out->width = out->height = 0;
    out->rgba = NULL;
    memset(info, 0, sizeof *info);
    if (access(path, R_OK) != 0)
        return cg_fail(err, CG_ERR_FILE_NOT_FOUND, "%s: no such readable file", path);
    const cg_oiio_api *oiio = cg_oiio(err);
    if (!oiio)
        return false;
    cg_oiio_transfer transfer = CG_OIIO_LINEAR;
    float gamma = 1.0f;
    if (!oiio->read(path, out, &transfer, &gamma, info->colour_space, sizeof info->colour_space, &info->bits,
                    &info->floating, err))
        return false;
    if (transfer == CG_OIIO_OTHER)
        cg_log_warn("%s: colour space \"%s\" is not converted: pixels are read as stored", path, info->colour_space);
    info->display_encoded = transfer != CG_OIIO_LINEAR && transfer != CG_OIIO_OTHER;
    if (!info->display_encoded)
        return true;
    size_t count = (size_t)out->width * out->height;
    for (size_t i = 0; i < count; i++) {
        float *p = out->rgba + 4 * i;
        for (int c = 0; c < 3; c++) /* alpha is never encoded */
            p[c] = decode(transfer, gamma, p[c]);
    }
    return true;
}

bool
cg_image_read(const char *path, cg_image *out, cg_error *err)
{
    cg_image_file_info info;
    return cg_image_read_info(path, out, &info, err);
}

typedef enum image_format { FORMAT_UNKNOWN, FORMAT_EXR, FORMAT_PNG } image_format;

static image_format
format_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    if (!dot)
        return FORMAT_UNKNOWN;
    if (!strcasecmp(dot, ".exr"))
        return FORMAT_EXR;
    if (!strcasecmp(dot, ".png"))
        return FORMAT_PNG;
    return FORMAT_UNKNOWN;
}

/* 8-bit sRGB: encode, clamp to [0,1] (cg/image.h), round to nearest. NaN has no
 * 8-bit value, so it is refused rather than written as some arbitrary byte. */
static bool
encode_png(const char *path, const cg_image *img, unsigned char **out, cg_error *err)
{
    size_t count = (size_t)img->width * img->height * 4;
    unsigned char *bytes = malloc(count);
    if (!bytes)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory encoding the image", path);
    for (size_t i = 0; i < count; i++) {
        float v = img->rgba[i];
        if (isnan(v)) {
            free(bytes);
            size_t px = i / 4;
            return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: pixel (%zu, %zu) channel %zu is NaN: PNG cannot store it",
                           path, px % (size_t)img->width, px / (size_t)img->width, i % 4);
        }
        float e = (i % 4 == 3) ? v : cg_srgb_encode(v);
        e = e < 0.0f ? 0.0f : e > 1.0f ? 1.0f : e;
        bytes[i] = (unsigned char)lrintf(e * 255.0f);
    }
    *out = bytes;
    return true;
}

bool
cg_image_write(const char *path, const cg_image *img, cg_image_exr_type exr_type, cg_error *err)
{
    image_format format = format_of(path);
    if (format == FORMAT_UNKNOWN)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: unsupported image extension: expected .exr or .png", path);
    if (!img || !img->rgba || img->width <= 0 || img->height <= 0)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: empty image (%dx%d)", path, img ? img->width : 0,
                       img ? img->height : 0);
    if (exr_type != CG_EXR_HALF && exr_type != CG_EXR_FLOAT)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: unknown EXR pixel type %d", path, (int)exr_type);

    const cg_oiio_api *oiio = cg_oiio(err);
    if (!oiio)
        return false;
    unsigned char *bytes = NULL;
    if (format == FORMAT_PNG && !encode_png(path, img, &bytes, err))
        return false;

    /* The temporary keeps the extension (cg_temp_path_for), so OIIO picks the same format. */
    char temp[4096];
    if (!cg_temp_path_for(path, temp, sizeof temp)) {
        free(bytes);
        return cg_fail(err, CG_ERR_IO, "%s: path too long", path);
    }
    bool ok;
    if (format == FORMAT_PNG)
        ok = oiio->write(temp, img->width, img->height, CG_OIIO_UINT8, bytes, true, err);
    else
        ok = oiio->write(temp, img->width, img->height, exr_type == CG_EXR_HALF ? CG_OIIO_HALF : CG_OIIO_FLOAT,
                         img->rgba, false, err);
    free(bytes);
    if (ok && rename(temp, path) != 0) {
        ok = cg_fail(err, CG_ERR_IO, "%s: cannot rename %s into place: %s", path, temp, strerror(errno));
    }
    if (!ok)
        unlink(temp); /* the target was never touched */
    return ok;
}

bool
cg_image_io_check(cg_error *err)
{
    return cg_oiio(err) != NULL;
}

bool
cg_image_read_samples(const char *path, long long max_samples, cg_image_samples *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (access(path, R_OK) != 0)
        return cg_fail(err, CG_ERR_FILE_NOT_FOUND, "%s: no such readable file", path);
    const cg_oiio_api *oiio = cg_oiio(err);
    return oiio && oiio->read_samples(path, max_samples, out, err);
}

void
cg_image_samples_free(cg_image_samples *s)
{
    if (!s)
        return;
    free(s->value);
    memset(s, 0, sizeof *s);
}
