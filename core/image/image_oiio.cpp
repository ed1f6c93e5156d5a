// The OpenImageIO module behind cg/image.h (see image_oiio.h): the only C++ in image I/O,
// and the only code that links OpenImageIO.
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

// Core's functions, from the loader (cg_oiio_module).
const cg_oiio_host *host;

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

// The file opened for reading with `config`, or null with *err filled.
std::unique_ptr<OIIO::ImageInput>
open_input(const char *path, const OIIO::ImageSpec &config, cg_error *err)
{
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        std::string why = OIIO::geterror();
        host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: not an image OpenImageIO can read: %s", path,
                   why.empty() ? "unknown format" : why.c_str());
    }
    return in;
}

bool
read_pixels(const char *path, cg_image *out, cg_oiio_transfer *transfer, float *gamma, char *colour_space,
            size_t colour_space_size, int *bits, bool *floating, cg_error *err)
{
    // Colour channels as stored: PNG's alpha is unassociated and OIIO would otherwise
    // premultiply it in (lossy at 8 bits, and in encoded space).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = open_input(path, config, err);
    if (!in)
        return false;
    const OIIO::ImageSpec &spec = in->spec();
    int w = spec.width, h = spec.height, n = spec.nchannels;
    if (w <= 0 || h <= 0 || n <= 0 || spec.depth > 1)
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: %dx%dx%d image with %d channels: expected a 2D image",
                          path, w, h, spec.depth, n);
    *transfer = transfer_of(spec, gamma);
    *bits = (int)spec.format.size() * 8;
    *floating = spec.format.is_floating_point();
    std::snprintf(colour_space, colour_space_size, "%s", spec.get_string_attribute("oiio:ColorSpace").c_str());

    std::vector<float> src((size_t)w * h * n);
    if (!in->read_image(0, 0, 0, n, OIIO::TypeDesc::FLOAT, src.data())) {
        std::string why = in->geterror();
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: cannot read pixels: %s", path, why.c_str());
    }
    in->close();

    if (!host->image_alloc(out, w, h, err))
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
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: OpenImageIO cannot write this format: %s", path,
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
        return host->fail(err, CG_ERR_IO, "%s: cannot create: %s", path, why.c_str());
    }
    bool ok = out->write_image(given, pixels);
    std::string why = ok ? std::string() : out->geterror();
    if (!out->close() && ok) {
        ok = false;
        why = out->geterror();
    }
    if (!ok)
        return host->fail(err, CG_ERR_IO, "%s: write failed: %s", path, why.c_str());
    return true;
}

// One channel as stored (cg_image_read_samples): no colour management, since a sample of a
// data image is a number, not a colour (a 16-bit PNG tagged sRGB or with a gAMA chunk must not
// be linearised).
bool
read_channel(const char *path, long long max_samples, cg_image_samples *out, cg_error *err)
{
    OIIO::ImageSpec config;
    config.attribute("oiio:RawColor", 1);
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = open_input(path, config, err);
    if (!in)
        return false;
    const OIIO::ImageSpec &spec = in->spec();
    int w = spec.width, h = spec.height;
    if (w <= 0 || h <= 0 || spec.nchannels < 1 || spec.depth > 1)
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: %dx%dx%d image with %d channels: expected a 2D image",
                          path, w, h, spec.depth, spec.nchannels);
    if ((long long)w * h > max_samples)
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: %dx%d samples: at most %lld are read at once", path, w, h,
                          max_samples);
    OIIO::TypeDesc type = spec.format;
    // Integers as the integers stored: OIIO normalises them to [0, 1] when converting to float,
    // so undo that by the type's largest value (exact in double for 8, 16 and 32 bits).
    double scale = 1.0;
    switch (type.basetype) {
    case OIIO::TypeDesc::UINT8: scale = 255.0; break;
    case OIIO::TypeDesc::INT8: scale = 127.0; break;
    case OIIO::TypeDesc::UINT16: scale = 65535.0; break;
    case OIIO::TypeDesc::INT16: scale = 32767.0; break;
    case OIIO::TypeDesc::UINT32: scale = 4294967295.0; break;
    case OIIO::TypeDesc::INT32: scale = 2147483647.0; break;
    default: break;
    }
    std::vector<double> samples((size_t)w * h);
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::DOUBLE, samples.data())) {
        std::string why = in->geterror();
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: cannot read the samples: %s", path, why.c_str());
    }
    in->close();
    out->value = (float *)std::malloc((size_t)w * h * sizeof(float));
    if (!out->value)
        return host->fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory for %dx%d samples", path, w, h);
    for (size_t i = 0; i < samples.size(); i++)
        out->value[i] = (float)(samples[i] * scale);
    out->width = w;
    out->height = h;
    std::snprintf(out->format, sizeof out->format, "%s", type.c_str());
    return true;
}

// C entry points: no exception may cross into C.
bool
oiio_read(const char *path, cg_image *out, cg_oiio_transfer *transfer, float *gamma, char *colour_space,
          size_t colour_space_size, int *bits, bool *floating, cg_error *err)
{
    try {
        return read_pixels(path, out, transfer, gamma, colour_space, colour_space_size, bits, floating, err);
    } catch (const std::bad_alloc &) {
        host->image_free(out);
        return host->fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory reading the image", path);
    } catch (const std::exception &e) {
        host->image_free(out);
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: %s", path, e.what());
    }
}

bool
oiio_write(const char *path, int width, int height, cg_oiio_pixel_type type, const void *pixels, bool srgb,
           cg_error *err)
{
    try {
        return write_pixels(path, width, height, type, pixels, srgb, err);
    } catch (const std::bad_alloc &) {
        return host->fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory writing the image", path);
    } catch (const std::exception &e) {
        return host->fail(err, CG_ERR_IO, "%s: %s", path, e.what());
    }
}

bool
oiio_read_samples(const char *path, long long max_samples, cg_image_samples *out, cg_error *err)
{
    std::memset(out, 0, sizeof *out);
    try {
        return read_channel(path, max_samples, out, err);
    } catch (const std::bad_alloc &) {
        std::free(out->value);
        std::memset(out, 0, sizeof *out);
        return host->fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory reading the samples", path);
    } catch (const std::exception &e) {
        std::free(out->value);
        std::memset(out, 0, sizeof *out);
        return host->fail(err, CG_ERR_IMAGE_FORMAT, "%s: %s", path, e.what());
    }
}

const cg_oiio_api api = { oiio_read, oiio_write, oiio_read_samples };

} // namespace

// The module's one exported symbol (the module is built with hidden visibility).
extern "C" __attribute__((visibility("default"))) const cg_oiio_api *
cg_oiio_module(int abi, const cg_oiio_host *core)
{
    if (abi != CG_OIIO_MODULE_ABI)
        return nullptr;
    host = core;
    return &api;
}
