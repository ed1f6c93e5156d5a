// OpenImageIO adapter of the DEM loader (see dem_oiio.h): the only C++ behind dem.c.
#include "dem_oiio.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

extern "C" bool
cg_dem_read(const char *path, cg_dem_samples *out, cg_error *err)
{
    std::memset(out, 0, sizeof *out);
    std::FILE *f = std::fopen(path, "rb");
    if (!f)
        return cg_fail(err, CG_ERR_FILE_NOT_FOUND, "%s: cannot open the DEM image", path);
    std::fclose(f);
    // No colour management: an elevation is a number, not a colour (a 16-bit PNG tagged sRGB
    // or with a gAMA chunk must not be linearised).
    OIIO::ImageSpec config;
    config.attribute("oiio:RawColor", 1);
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        std::string why = OIIO::geterror();
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: not an image OpenImageIO can read: %s", path,
                       why.empty() ? "unknown format" : why.c_str());
    }
    const OIIO::ImageSpec &spec = in->spec();
    int w = spec.width, h = spec.height;
    if (w < 2 || h < 2 || spec.nchannels < 1 || spec.depth > 1)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT,
                       "%s: a %dx%d image with %d channels: a DEM needs at least 2x2 samples in one channel", path, w,
                       h, spec.nchannels);
    if ((long long)w * h > (1ll << 28))
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: %dx%d samples: at most 2^28 (use the stride key)", path, w, h);
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
    std::vector<double> row((size_t)w * h);
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::DOUBLE, row.data())) {
        std::string why = in->geterror();
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: cannot read the samples: %s", path, why.c_str());
    }
    in->close();
    out->value = (float *)std::malloc((size_t)w * h * sizeof(float));
    if (!out->value)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory for %dx%d samples", path, w, h);
    for (size_t i = 0; i < row.size(); i++)
        out->value[i] = (float)(row[i] * scale);
    out->width = w;
    out->height = h;
    std::snprintf(out->format, sizeof out->format, "%s", type.c_str());
    return true;
}

extern "C" void
cg_dem_samples_free(cg_dem_samples *s)
{
    std::free(s->value);
    std::memset(s, 0, sizeof *s);
}
