// SPDX-License-Identifier: MIT
// Why the tools encode PNG themselves instead of through libpng's writer: libpng deflates the whole
// image on the calling thread, and the image is written at the end of a `ge2gl render` process of
// 30-100 ms, where that deflate took 3-7 ms (docs/benchmarks.md, "Sixth round"). A zlib stream may
// be made of pieces deflated independently: every piece but the last ends with a sync flush (a
// byte boundary, no final-block bit) and none refers back past its own start, so pieces deflated
// on separate threads concatenate into one valid stream (RFC 1951 §3.2.3-3.2.4; the way pigz
// splits its work). Deflating stays zlib's; what is written here is the container around it: the
// signature and the IHDR, IDAT and IEND chunks with their CRC-32s (PNG specification §5, §11.2).
#include "tools/lib/png_encode.h"

#include <zlib.h>

#include <algorithm>
#include <thread>

namespace ge::tools {

namespace {

void put32(std::vector<u8>& out, u32 v) {
    const u8 b[4] = {u8(v >> 24), u8(v >> 16), u8(v >> 8), u8(v)};
    out.insert(out.end(), b, b + 4);
}

// PNG §5.3: length, type, data, CRC-32 of type and data; all numbers big-endian.
void putChunk(std::vector<u8>& out, const char (&type)[5], const u8* data, size_t n) {
    put32(out, u32(n));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    if (n) out.insert(out.end(), data, data + n);
    put32(out, u32(crc32_z(crc32_z(0, nullptr, 0), out.data() + start, n + 4)));
}

// Raw deflate (no zlib header) of n bytes at level 1. `last` closes the stream with the final
// block; any other piece ends on a byte boundary after a sync flush. False when zlib fails.
bool deflatePiece(const u8* src, size_t n, bool last, std::vector<u8>& out) {
    z_stream z{};
    if (deflateInit2(&z, 1, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return false;
    out.resize(deflateBound(&z, uLong(n)) + 16);  // + the sync flush's empty stored block
    z.next_in = const_cast<Bytef*>(src);
    z.avail_in = uInt(n);
    z.next_out = out.data();
    z.avail_out = uInt(out.size());
    const int r = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
    const bool ok = last ? r == Z_STREAM_END : (r == Z_OK && z.avail_in == 0 && z.avail_out != 0);
    out.resize(z.total_out);
    deflateEnd(&z);
    return ok;
}

}  // namespace

std::vector<u8> encodePng(const u32* rgba, int width, int height, int threads) {
    if (width <= 0 || height <= 0) return {};
    const size_t pixels = size_t(width) * size_t(height);
    // Every frame readFrame makes is opaque: RGB is a quarter fewer bytes to deflate, and a reader
    // gets the same alpha (255) back.
    const bool opaque = std::all_of(rgba, rgba + pixels, [](u32 p) { return (p >> 24) == 0xFF; });
    const size_t bpp = opaque ? 3 : 4, rowBytes = 1 + size_t(width) * bpp;
    // The scanlines as PNG stores them: filter type 0 (none) and the pixels' bytes. Without row
    // filters level 1 compresses a game frame's flat areas as well as libpng's defaults did (Monster
    // Hunter 3rd: 176 KB against 180 KB) for a fraction of the time.
    std::vector<u8> raw(rowBytes * size_t(height));
    for (int y = 0; y < height; ++y) {
        u8* d = raw.data() + size_t(y) * rowBytes;
        *d++ = 0;
        const u32* s = rgba + size_t(y) * size_t(width);
        for (int x = 0; x < width; ++x, d += bpp) {
            d[0] = u8(s[x]), d[1] = u8(s[x] >> 8), d[2] = u8(s[x] >> 16);
            if (!opaque) d[3] = u8(s[x] >> 24);
        }
    }
    // Pieces of whole rows, none under 128 KiB: a thread costs more than deflating less.
    const size_t maxPieces = std::max<size_t>(1, raw.size() / (size_t(128) << 10));
    const int pieces = int(std::min<size_t>({size_t(std::max(threads, 1)), maxPieces, size_t(height)}));
    std::vector<std::vector<u8>> parts(static_cast<size_t>(pieces));
    std::vector<char> ok(static_cast<size_t>(pieces), 0);
    auto work = [&](int k) {
        const size_t r0 = size_t(height) * size_t(k) / size_t(pieces);
        const size_t r1 = size_t(height) * size_t(k + 1) / size_t(pieces);
        ok[size_t(k)] = deflatePiece(raw.data() + r0 * rowBytes, (r1 - r0) * rowBytes, k == pieces - 1, parts[size_t(k)]);
    };
    std::vector<std::thread> helpers;
    for (int k = 1; k < pieces; ++k) helpers.emplace_back(work, k);
    work(0);
    const u32 adler = u32(adler32_z(adler32_z(0, nullptr, 0), raw.data(), raw.size()));
    for (std::thread& t : helpers) t.join();
    if (std::find(ok.begin(), ok.end(), 0) != ok.end()) return {};

    // zlib stream (RFC 1950): CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (fastest level, check
    // bits making 0x7801 a multiple of 31), the pieces, the Adler-32 of all scanline bytes.
    std::vector<u8> idat = {0x78, 0x01};
    for (const std::vector<u8>& p : parts) idat.insert(idat.end(), p.begin(), p.end());
    put32(idat, adler);

    std::vector<u8> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<u8> ihdr;
    put32(ihdr, u32(width));
    put32(ihdr, u32(height));
    // Bit depth 8; colour type 2 (RGB) or 6 (RGBA); deflate; adaptive filtering method 0 (each
    // row says its filter, here none); no interlace.
    ihdr.insert(ihdr.end(), {8, u8(opaque ? 2 : 6), 0, 0, 0});
    png.reserve(png.size() + 12 + ihdr.size() + 12 + idat.size() + 12);
    putChunk(png, "IHDR", ihdr.data(), ihdr.size());
    putChunk(png, "IDAT", idat.data(), idat.size());
    putChunk(png, "IEND", nullptr, 0);
    return png;
}

}  // namespace ge::tools
