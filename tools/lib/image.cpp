// SPDX-License-Identifier: MIT
#include "tools/lib/image.h"

#include <dlfcn.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <limits>
#include <thread>

#include "hle/pixel_format.h"
#include "tools/lib/png_encode.h"

namespace ge::tools {

namespace fs = std::filesystem;

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

namespace {

bool hasPngExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".png";
}

// Other formats go through OpenImageIO in a module loaded on first use (tools/oiio_module): linking
// OpenImageIO into the CLI costs its ~260 shared libraries at every process start (0.25–0.6 s here),
// more than rendering a frame.
struct OiioModule {
    void* handle = nullptr;
    int (*read)(const char*, int*, int*, unsigned**, char*, unsigned long) = nullptr;
    int (*write)(const char*, int, int, const unsigned*, char*, unsigned long) = nullptr;
    void (*release)(unsigned*) = nullptr;
};

struct OiioLoad {
    OiioModule module;
    std::string error;  // empty when loaded
};

OiioLoad loadOiio() {
    OiioLoad load;
    OiioModule& m = load.module;
    std::vector<std::string> candidates;
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((self.parent_path() / GE2GL_OIIO_MODULE_NAME).string());
    candidates.push_back((fs::path(GE2GL_OIIO_BUILD_DIR) / GE2GL_OIIO_MODULE_NAME).string());
    candidates.push_back(GE2GL_OIIO_MODULE_NAME);
    for (const std::string& c : candidates) {
        m.handle = dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (m.handle) break;
    }
    if (!m.handle) {
        const char* why = dlerror();
        load.error = std::string("formats other than PNG need ") + GE2GL_OIIO_MODULE_NAME + " (OpenImageIO): " +
                     (why ? why : "not found");
        return load;
    }
    m.read = reinterpret_cast<decltype(m.read)>(dlsym(m.handle, "ge2gl_oiio_read"));
    m.write = reinterpret_cast<decltype(m.write)>(dlsym(m.handle, "ge2gl_oiio_write"));
    m.release = reinterpret_cast<decltype(m.release)>(dlsym(m.handle, "ge2gl_oiio_free"));
    if (!m.read || !m.write || !m.release) load.error = std::string(GE2GL_OIIO_MODULE_NAME) + " lacks its entry points";
    return load;
}

// Loaded once per process on first use (thread-safe static initialisation), never unloaded: OIIO
// keeps static state that a dlclose would leave dangling. Immutable afterwards.
const OiioModule* oiio(std::string& err) {
    static const OiioLoad load = loadOiio();
    if (!load.error.empty()) {
        err = load.error;
        return nullptr;
    }
    return &load.module;
}

}  // namespace

bool writePng(const std::string& path, const Image& img, std::string& err) {
    if (img.width <= 0 || img.height <= 0 || img.rgba.size() != size_t(img.width) * img.height) {
        err = "cannot write " + path + ": empty image";
        return false;
    }
    if (!hasPngExtension(path)) {
        const OiioModule* m = oiio(err);
        if (!m) return false;
        char msg[512] = {};
        if (!m->write(path.c_str(), img.width, img.height, img.rgba.data(), msg, sizeof msg)) {
            err = "cannot write " + path + ": " + msg;
            return false;
        }
        return true;
    }
    // tools/lib/png_encode.cpp says why the PNG is not written through libpng.
    const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
    const std::vector<u8> png = encodePng(img.rgba.data(), img.width, img.height, threads);
    if (png.empty()) {
        err = "cannot write " + path + ": out of memory encoding the PNG";
        return false;
    }
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) {
        err = "cannot write " + path + ": " + std::strerror(errno);
        return false;
    }
    const bool written = std::fwrite(png.data(), 1, png.size(), f) == png.size();
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) {
        err = "cannot write " + path + ": write error (disk full?)";
        return false;
    }
    return true;
}

bool readImage(const std::string& path, Image& img, std::string& err) {
    if (!hasPngExtension(path)) {
        const OiioModule* m = oiio(err);
        if (!m) return false;
        char msg[512] = {};
        int w = 0, h = 0;
        unsigned* px = nullptr;
        if (!m->read(path.c_str(), &w, &h, &px, msg, sizeof msg)) {
            err = "cannot read " + path + ": " + msg;
            return false;
        }
        img.width = w;
        img.height = h;
        img.rgba.assign(px, px + size_t(w) * h);
        m->release(px);
        return true;
    }
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str())) {
        err = "cannot read " + path + ": " + png.message;
        return false;
    }
    if (png.width == 0 || png.height == 0 || png.width > 8192 || png.height > 8192) {
        png_image_free(&png);
        err = "unsupported image size in " + path;
        return false;
    }
    // libpng converts every PNG colour type and depth (grey, palette, 16-bit, with or without
    // alpha) to 8-bit RGBA; a PNG without alpha reads as opaque.
    png.format = PNG_FORMAT_RGBA;
    img.width = int(png.width);
    img.height = int(png.height);
    img.rgba.assign(size_t(img.width) * img.height, 0);
    if (!png_image_finish_read(&png, nullptr, img.rgba.data(), 0, nullptr)) {
        err = "cannot decode " + path + ": " + png.message;
        png_image_free(&png);
        img = Image{};
        return false;
    }
    return true;
}

Image boxDownsample(const Image& img, int n) {
    if (n <= 1) return img;
    Image out;
    out.width = img.width / n;
    out.height = img.height / n;
    out.rgba.assign(size_t(out.width) * size_t(out.height), 0);
    const u32 area = u32(n * n);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            u32 sum[4] = {};
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const u32 p = img.at(x * n + i, y * n + j);
                    for (int c = 0; c < 4; ++c) sum[c] += (p >> (8 * c)) & 0xFF;
                }
            u32 p = 0;
            for (int c = 0; c < 4; ++c) p |= ((sum[c] + area / 2) / area) << (8 * c);
            out.rgba[size_t(y) * size_t(out.width) + size_t(x)] = p;
        }
    return out;
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

namespace {

// A picture of a and b's differences: each differing pixel coloured by `mark(p, q)`, the others a
// dim grey copy of a (a third of the channels' mean).
template <class Mark>
Image differencePicture(const Image& a, const Image& b, int w, int h, Mark mark) {
    Image d;
    d.width = w;
    d.height = h;
    d.rgba.assign(size_t(w) * h, 0xFF000000u);
    for (int y = 0; y < h && y < a.height && y < b.height; ++y)
        for (int x = 0; x < w && x < a.width && x < b.width; ++x) {
            const u32 p = a.at(x, y), q = b.at(x, y);
            u32& o = d.rgba[size_t(y) * w + x];
            if ((p & 0xFFFFFF) != (q & 0xFFFFFF)) {
                o = mark(p, q);
            } else {
                const u32 grey = (((p & 0xFF) + ((p >> 8) & 0xFF) + ((p >> 16) & 0xFF)) / 3) / 3;
                o = 0xFF000000u | grey | grey << 8 | grey << 16;
            }
        }
    return d;
}

}  // namespace

Image diffImage(const Image& a, const Image& b, int w, int h) {
    return differencePicture(a, b, w, h, [](u32, u32) { return 0xFFFF00FFu; });
}

u32 heatColour(int d) {
    if (d <= 0) return 0xFF000000u;
    struct Stop {
        double t;
        int r, g, b;
    };
    static constexpr Stop kStops[] = {{0.125, 40, 40, 255}, {0.33, 0, 210, 230}, {0.55, 70, 220, 0},
                                      {0.75, 255, 220, 0}, {1.0, 255, 0, 0}};
    const double t = std::min(1.0, std::log2(1.0 + std::min(d, 255)) / 8.0);
    size_t i = 1;
    while (i + 1 < std::size(kStops) && t > kStops[i].t) ++i;
    const Stop &a = kStops[i - 1], &b = kStops[i];
    const double f = std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0);
    auto mix = [f](int x, int y) { return u32(std::lround(x + (y - x) * f)); };
    return 0xFF000000u | mix(a.r, b.r) | mix(a.g, b.g) << 8 | mix(a.b, b.b) << 16;
}

Image heatImage(const Image& a, const Image& b, int w, int h) {
    return differencePicture(a, b, w, h, [](u32 p, u32 q) {
        int diff = 0;
        for (int c = 0; c < 24; c += 8) diff = std::max(diff, std::abs(int((p >> c) & 0xFF) - int((q >> c) & 0xFF)));
        return heatColour(diff);
    });
}

}  // namespace ge::tools
