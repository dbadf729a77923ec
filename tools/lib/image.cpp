#include "tools/lib/image.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <limits>

#include "hle/pixel_format.h"

namespace ge::tools {

Image readFrame(const Memory& mem, u32 addr, u32 stride, u32 format, int width, int height) {
    Image img;
    img.width = width;
    img.height = height;
    img.rgba.assign(size_t(width) * height, 0xFF000000u);
    const u32 bpp = (format & 3) == GE_FORMAT_8888 ? 4 : 2;
    for (int y = 0; y < height; ++y) {
        const u8* row = mem.ptr(addr + u32(y) * stride * bpp, u32(width) * bpp);
        if (!row) continue;
        convertToRGBA8888(row, GeBufferFormat(format & 3), u32(width), 1, stride, &img.rgba[size_t(y) * width]);
        for (int x = 0; x < width; ++x) img.rgba[size_t(y) * width + x] |= 0xFF000000u;
    }
    return img;
}

bool writePng(const std::string& path, const Image& img, std::string& err) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        err = "cannot write " + path + ": " + OIIO::geterror();
        return false;
    }
    OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec)) {
        err = "cannot write " + path + ": " + out->geterror();
        return false;
    }
    bool ok = out->write_image(OIIO::TypeDesc::UINT8, img.rgba.data());
    if (!ok) err = "cannot write " + path + ": " + out->geterror();
    out->close();
    return ok;
}

bool readImage(const std::string& path, Image& img, std::string& err) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        err = "cannot read " + path + ": " + OIIO::geterror();
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.width > 8192 || spec.height > 8192 || spec.nchannels < 1) {
        err = "unsupported image size in " + path;
        return false;
    }
    std::vector<u8> buf(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, buf.data())) {
        err = "cannot decode " + path + ": " + in->geterror();
        return false;
    }
    img.width = spec.width;
    img.height = spec.height;
    img.rgba.resize(size_t(img.width) * img.height);
    const int nc = spec.nchannels;
    for (size_t i = 0; i < img.rgba.size(); ++i) {
        const u8* p = &buf[i * nc];
        u8 r = p[0], g = nc >= 3 ? p[1] : p[0], b = nc >= 3 ? p[2] : p[0], a = nc >= 4 ? p[3] : 255;
        img.rgba[i] = u32(r) | u32(g) << 8 | u32(b) << 16 | u32(a) << 24;
    }
    return true;
}

double mseRGB(const Image& a, const Image& b, int w, int h) {
    if (a.width < w || a.height < h || b.width < w || b.height < h) return -1;
    u64 sum = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            u32 p = a.at(x, y), q = b.at(x, y);
            for (int c = 0; c < 3; ++c) {
                int d = int((p >> (8 * c)) & 0xFF) - int((q >> (8 * c)) & 0xFF);
                sum += u64(d * d);
            }
        }
    return double(sum) / (double(w) * h * 3);
}

double psnrFromMse(double mse) {
    if (mse <= 0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(255.0 * 255.0 / mse);
}

Image diffImage(const Image& a, const Image& b, int w, int h) {
    Image d;
    d.width = w;
    d.height = h;
    d.rgba.assign(size_t(w) * h, 0xFF000000u);
    for (int y = 0; y < h && y < a.height && y < b.height; ++y)
        for (int x = 0; x < w && x < a.width && x < b.width; ++x) {
            u32 p = a.at(x, y), q = b.at(x, y);
            if ((p & 0xFFFFFF) != (q & 0xFFFFFF)) {
                d.rgba[size_t(y) * w + x] = 0xFFFF00FFu;
            } else {
                u32 grey = (((p & 0xFF) + ((p >> 8) & 0xFF) + ((p >> 16) & 0xFF)) / 3) / 3;
                d.rgba[size_t(y) * w + x] = 0xFF000000u | grey | grey << 8 | grey << 16;
            }
        }
    return d;
}

}  // namespace ge::tools
