// OpenImageIO adapter behind cg/image.h (see image_oiio.h): the only C++ in image I/O.
#include "image_oiio.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace {

cg_oiio_transfer
transfer_of(const OIIO::ImageSpec &spec, float *gamma)
{
    std::string cs = spec.get_string_attribute("oiio:ColorSpace");
    *gamma = 1.0f;
    if (cs.empty() || OIIO::Strutil::iequals(cs, "Linear") || OIIO::Strutil::iequals(cs, "scene_linear"))
        return CG_OIIO_LINEAR;
    if (OIIO::Strutil::iequals(cs, "sRGB"))
        return CG_OIIO_SRGB;
    if (OIIO::Strutil::iequals(cs, "Rec709"))
        return CG_OIIO_REC709;
    // PNG with a gAMA chunk: "GammaCorrected2.2" (OIIO 2.4) or "Gamma2.2".
    for (const char *prefix : { "GammaCorrected", "Gamma" }) {
        if (OIIO::Strutil::istarts_with(cs, prefix)) {
            float g = std::strtof(cs.c_str() + std::strlen(prefix), nullptr);
            if (g > 0.0f) {
                *gamma = g;
                return CG_OIIO_GAMMA;
            }
        }
    }
    return CG_OIIO_OTHER;
}

bool
read_pixels(const char *path, cg_image *out, cg_oiio_transfer *transfer, float *gamma, char *colour_space,
            size_t colour_space_size, int *bits, bool *floating, cg_error *err)
{
    // Colour channels as stored: PNG's alpha is unassociated and OIIO would otherwise
    // premultiply it in (lossy at 8 bits, and in encoded space).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        std::string why = OIIO::geterror();
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: not an image OpenImageIO can read: %s", path,
                       why.empty() ? "unknown format" : why.c_str());
    }
    const OIIO::ImageSpec &spec = in->spec();
    int w = spec.width, h = spec.height, n = spec.nchannels;
    if (w <= 0 || h <= 0 || n <= 0 || spec.depth > 1)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: %dx%dx%d image with %d channels: expected a 2D image",
                       path, w, h, spec.depth, n);
    *transfer = transfer_of(spec, gamma);
    *bits = (int)spec.format.size() * 8;
    *floating = spec.format.is_floating_point();
    std::snprintf(colour_space, colour_space_size, "%s", spec.get_string_attribute("oiio:ColorSpace").c_str());

    std::vector<float> src((size_t)w * h * n);
    if (!in->read_image(0, 0, 0, n, OIIO::TypeDesc::FLOAT, src.data())) {
        std::string why = in->geterror();
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: cannot read pixels: %s", path, why.c_str());
    }
    in->close();

    if (!cg_image_alloc(out, w, h, err))
        return false;
    int alpha = spec.alpha_channel >= 0 && spec.alpha_channel < n ? spec.alpha_channel : -1;
    int colour = n - (alpha >= 0 ? 1 : 0); // channels before/around alpha that hold colour
    bool grey = colour == 1;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        const float *s = &src[i * n];
        float *d = &out->rgba[i * 4];
        int c = 0;
        for (int k = 0; k < n && c < 3; k++) {
            if (k != alpha)
                d[c++] = s[k];
        }
        if (grey)
            d[1] = d[2] = d[0];
        else
            for (; c < 3; c++)
                d[c] = 0.0f;
        d[3] = alpha >= 0 ? s[alpha] : 1.0f;
    }
    return true;
}

bool
write_pixels(const char *path, int width, int height, cg_oiio_pixel_type type, const void *pixels, bool srgb,
             cg_error *err)
{
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        std::string why = OIIO::geterror();
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: OpenImageIO cannot write this format: %s", path,
                       why.c_str());
    }
    OIIO::TypeDesc stored = type == CG_OIIO_UINT8  ? OIIO::TypeDesc::UINT8
                            : type == CG_OIIO_HALF ? OIIO::TypeDesc::HALF
                                                   : OIIO::TypeDesc::FLOAT;
    OIIO::TypeDesc given = type == CG_OIIO_UINT8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(width, height, 4, stored);
    spec.attribute("oiio:ColorSpace", srgb ? "sRGB" : "Linear");
    // Pixels are written as given: without this OIIO divides PNG colour by alpha.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (std::strcmp(out->format_name(), "openexr") == 0)
        spec.attribute("compression", "zip"); // lossless, so float files round-trip bit-exactly
    if (!out->open(path, spec)) {
        std::string why = out->geterror();
        return cg_fail(err, CG_ERR_IO, "%s: cannot create: %s", path, why.c_str());
    }
    bool ok = out->write_image(given, pixels);
    std::string why = ok ? std::string() : out->geterror();
    if (!out->close() && ok) {
        ok = false;
        why = out->geterror();
    }
    if (!ok)
        return cg_fail(err, CG_ERR_IO, "%s: write failed: %s", path, why.c_str());
    return true;
}

} // namespace

// C entry points: no exception may cross into C.
extern "C" bool
cg_oiio_read(const char *path, cg_image *out, cg_oiio_transfer *transfer, float *gamma, char *colour_space,
             size_t colour_space_size, int *bits, bool *floating, cg_error *err)
{
    try {
        return read_pixels(path, out, transfer, gamma, colour_space, colour_space_size, bits, floating, err);
    } catch (const std::bad_alloc &) {
        cg_image_free(out);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory reading the image", path);
    } catch (const std::exception &e) {
        cg_image_free(out);
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: %s", path, e.what());
    }
}

extern "C" bool
cg_oiio_write(const char *path, int width, int height, cg_oiio_pixel_type type, const void *pixels, bool srgb,
              cg_error *err)
{
    try {
        return write_pixels(path, width, height, type, pixels, srgb, err);
    } catch (const std::bad_alloc &) {
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory writing the image", path);
    } catch (const std::exception &e) {
        return cg_fail(err, CG_ERR_IO, "%s: %s", path, e.what());
    }
}
