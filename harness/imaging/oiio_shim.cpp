// gibench — the one C++ file: OpenImageIO 2.4 has no C API, so the C harness reads and writes
// non-EXR images through these two extern "C" functions (oiio_shim.h).
#include "oiio_shim.h"
#include "rgba_expand.h"

#include <OpenImageIO/imageio.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace OIIO;

static int shim_fail(char *errbuf, int errbuf_len, const char *fmt, ...)
{
    if (errbuf && errbuf_len > 0) {
        va_list ap;
        va_start(ap, fmt);
        std::vsnprintf(errbuf, (size_t)errbuf_len, fmt, ap);
        va_end(ap);
    }
    return -1;
}

extern "C" int gib_oiio_read_rgba(const char *path, int *width, int *height, float **rgba,
                                  char *errbuf, int errbuf_len)
{
    *rgba = nullptr;
    // Catch everything: a C++ exception must never unwind into C frames.
    try {
        auto in = ImageInput::open(path);
        if (!in) {
            std::string e = OIIO::geterror();
            return shim_fail(errbuf, errbuf_len, "cannot open image '%s': %s", path, e.c_str());
        }
        const ImageSpec &spec = in->spec();
        const int w = spec.width, h = spec.height, nc = spec.nchannels;
        if (w <= 0 || h <= 0 || nc <= 0) {
            in->close();
            return shim_fail(errbuf, errbuf_len, "image '%s': invalid size %dx%d with %d channels",
                             path, w, h, nc);
        }
        // A few bytes of header can claim any size: bounded before anything of that size is
        // allocated (a 69-byte PNG claiming 60000x60000 asked for 58 GB).
        if ((long long)w * h > GIB_IMAGE_MAX_PIXELS || nc > GIB_IMAGE_MAX_CHANNELS) {
            in->close();
            return shim_fail(errbuf, errbuf_len, "image '%s' claims %dx%d pixels with %d channels: "
                             "over gibench's limit of %lld pixels and %d channels", path, w, h,
                             nc, (long long)GIB_IMAGE_MAX_PIXELS, GIB_IMAGE_MAX_CHANNELS);
        }
        std::vector<float> src((size_t)w * h * nc);
        // FLOAT conversion scales integer formats to [0,1] without touching the transfer curve.
        if (!in->read_image(0, 0, 0, nc, TypeDesc::FLOAT, src.data())) {
            std::string e = in->geterror();
            in->close();
            return shim_fail(errbuf, errbuf_len, "cannot read image '%s': %s", path, e.c_str());
        }
        in->close();

        float *out = (float *)std::malloc((size_t)w * h * 4 * sizeof(float));
        if (!out)
            return shim_fail(errbuf, errbuf_len, "image '%s': out of memory (%dx%d)", path, w, h);
        const size_t n = (size_t)w * h;
        for (size_t i = 0; i < n; ++i) {
            gib_rgba_expand(&src[i * nc], nc, &out[i * 4]);
        }
        *width = w;
        *height = h;
        *rgba = out;
        return 0;
    } catch (const std::exception &e) {
        return shim_fail(errbuf, errbuf_len, "image '%s': %s", path, e.what());
    } catch (...) {
        return shim_fail(errbuf, errbuf_len, "image '%s': unknown OpenImageIO error", path);
    }
}

extern "C" int gib_oiio_write_png8(const char *path, int width, int height, int channels,
                                   const unsigned char *data, char *errbuf, int errbuf_len)
{
    if (width <= 0 || height <= 0 || (channels != 1 && channels != 3 && channels != 4))
        return shim_fail(errbuf, errbuf_len, "png '%s': invalid size %dx%d with %d channels", path,
                         width, height, channels);
    try {
        // Force PNG regardless of the file name's extension: the contract is "write PNG".
        auto out = ImageOutput::create("png");
        if (!out) {
            std::string e = OIIO::geterror();
            return shim_fail(errbuf, errbuf_len, "png '%s': no PNG writer: %s", path, e.c_str());
        }
        ImageSpec spec(width, height, channels, TypeDesc::UINT8);
        if (!out->open(path, spec)) {
            std::string e = out->geterror();
            return shim_fail(errbuf, errbuf_len, "cannot create png '%s': %s", path, e.c_str());
        }
        if (!out->write_image(TypeDesc::UINT8, data)) {
            std::string e = out->geterror();
            out->close();
            return shim_fail(errbuf, errbuf_len, "cannot write png '%s': %s", path, e.c_str());
        }
        if (!out->close()) {
            std::string e = out->geterror();
            return shim_fail(errbuf, errbuf_len, "cannot finish png '%s': %s", path, e.c_str());
        }
        return 0;
    } catch (const std::exception &e) {
        return shim_fail(errbuf, errbuf_len, "png '%s': %s", path, e.what());
    } catch (...) {
        return shim_fail(errbuf, errbuf_len, "png '%s': unknown OpenImageIO error", path);
    }
}
