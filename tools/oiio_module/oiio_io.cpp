// SPDX-License-Identifier: MIT
// ge2gl's OpenImageIO module: reading and writing image formats other than PNG for the CLI and the
// tests. Built as a separate shared object and loaded with dlopen on first use (tools/lib/image.cpp)
// so that processes that only touch PNGs do not pay for OpenImageIO's dependency tree at start-up.
// Pixels are RGBA8 in memory order R, G, B, A (one u32 per pixel, little endian).
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

void setError(char* err, unsigned long len, const std::string& msg) {
    if (err && len) std::snprintf(err, len, "%s", msg.c_str());
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int ge2gl_oiio_read(const char* path, int* width, int* height,
                                                           unsigned** pixels, char* err, unsigned long errLen) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        setError(err, errLen, OIIO::geterror());
        return 0;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.width > 8192 || spec.height > 8192 || spec.nchannels < 1) {
        setError(err, errLen, "unsupported image size");
        return 0;
    }
    const size_t count = size_t(spec.width) * size_t(spec.height);
    const int nc = spec.nchannels;
    std::vector<unsigned char> buf(count * size_t(nc));
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, buf.data())) {
        setError(err, errLen, in->geterror());
        return 0;
    }
    auto* out = static_cast<unsigned*>(std::malloc(count * sizeof(unsigned)));
    if (!out) {
        setError(err, errLen, "out of memory");
        return 0;
    }
    for (size_t i = 0; i < count; ++i) {
        const unsigned char* p = &buf[i * size_t(nc)];
        // Grey images replicate their channel; images without alpha are opaque.
        const unsigned r = p[0], g = nc >= 3 ? p[1] : p[0], b = nc >= 3 ? p[2] : p[0], a = nc >= 4 ? p[3] : 255u;
        out[i] = r | g << 8 | b << 16 | a << 24;
    }
    *width = spec.width;
    *height = spec.height;
    *pixels = out;
    return 1;
}

__attribute__((visibility("default"))) int ge2gl_oiio_write(const char* path, int width, int height,
                                                            const unsigned* pixels, char* err, unsigned long errLen) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        setError(err, errLen, OIIO::geterror());
        return 0;
    }
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec)) {
        setError(err, errLen, out->geterror());
        return 0;
    }
    const bool ok = out->write_image(OIIO::TypeDesc::UINT8, pixels);
    if (!ok) setError(err, errLen, out->geterror());
    out->close();
    return ok ? 1 : 0;
}

__attribute__((visibility("default"))) void ge2gl_oiio_free(unsigned* pixels) { std::free(pixels); }

}  // extern "C"
