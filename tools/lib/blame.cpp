// SPDX-License-Identifier: MIT
#include "tools/lib/blame.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <unordered_map>

#include "tools/lib/draw_hook.h"
#include "tools/lib/json_io.h"

namespace ge::tools {

// ---------------------------------------------------------------------------------------------
// Shared helpers

const char* primTypeName(GePrimType p) {
    static const char* const names[8] = {"POINTS",         "LINES",          "LINE_STRIP", "TRIANGLES",
                                         "TRIANGLE_STRIP", "TRIANGLE_FAN",   "RECTANGLES", "KEEP_PREVIOUS"};
    return names[u32(p) & 7];
}

const char* bufferFormatName(u32 fmt) {
    static const char* const names[4] = {"565", "5551", "4444", "8888"};
    return names[fmt & 3];
}

namespace {

std::string fmtStr(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string fmtStr(const char* f, ...) {
    char buf[256];
    va_list ap;
    va_start(ap, f);
    std::vsnprintf(buf, sizeof buf, f, ap);
    va_end(ap);
    return buf;
}

const char* cmpName(u32 f) {
    static const char* const n[8] = {"never", "always", "eq", "ne", "lt", "le", "gt", "ge"};
    return n[f & 7];
}

const char* blendFactorName(u32 f, bool src) {
    static const char* const a[11] = {"dstc", "1-dstc", "srca", "1-srca", "dsta", "1-dsta",
                                      "2srca", "1-2srca", "2dsta", "1-2dsta", "fix"};
    if (f == 0) return src ? "dstc" : "srcc";
    if (f == 1) return src ? "1-dstc" : "1-srcc";
    return f < 11 ? a[f] : "fix";  // 11–15 act as fixed
}

const char* texFormatName(u32 f) {
    static const char* const n[11] = {"5650", "5551", "4444", "8888", "CLUT4", "CLUT8",
                                      "CLUT16", "CLUT32", "DXT1", "DXT3", "DXT5"};
    return f < 11 ? n[f] : "?";
}

std::string filterName(u32 f) {
    std::string s = (f & 1) ? "linear" : "nearest";
    if (f & 4) s += (f & 2) ? "/mip-linear" : "/mip-nearest";
    return s;
}

// Folds VRAM mirrors onto 0x04000000–0x041FFFFF; other addresses lose only their top bits.
u32 foldAddr(u32 a) {
    a = Memory::normalize(a);
    if (a >= Memory::kVramBase && a < Memory::kVramMirrorsEnd) return Memory::kVramBase + (a & (Memory::kVramSize - 1));
    return a;
}

}  // namespace

std::string stateSummary(const GeState& st) {
    std::string s = st.isThrough() ? "through" : "transform";
    if (st.isClearMode()) {
        s += fmtStr("; CLEAR mode (colour %s, alpha/stencil %s, depth %s)", st.CMODE_color() ? "on" : "off",
                    st.CMODE_alpha() ? "on" : "off", st.CMODE_depth() ? "on" : "off");
    }
    if (st.TME_on()) {
        const u32 tf = st.textureFormat();
        s += fmtStr("; tex %s %ux%u @0x%08x", texFormatName(tf), st.textureWidth(0), st.textureHeight(0),
                    st.textureAddr(0));
        if (tf >= GE_TFMT_CLUT4 && tf <= GE_TFMT_CLUT32)
            s += fmtStr(" clut %s shift %u mask 0x%02x start %u", bufferFormatName(st.CLUT_format()), st.CLUT_shift(),
                        st.CLUT_mask(), st.CLUT_start());
        if (st.TMODE_swizzle()) s += " swizzled";
        if (st.TMODE_maxlevel()) s += fmtStr(" levels %u", st.TMODE_maxlevel() + 1);
        s += " min " + filterName(st.TFILTER_min()) + " mag " + filterName(st.TFILTER_mag());
        static const char* const fn[8] = {"modulate", "decal", "blend", "replace", "add", "add?", "add?", "add?"};
        s += fmtStr(" func %s%s%s", fn[st.TFUNC_func() & 7], st.TFUNC_rgba() ? " rgba" : " rgb",
                    st.TFUNC_double() ? " x2" : "");
        s += fmtStr(" wrap %s/%s", st.TWRAP_uclamp() ? "clamp" : "repeat", st.TWRAP_vclamp() ? "clamp" : "repeat");
    } else {
        s += "; tex off";
    }
    if (!st.isClearMode()) {
        if (st.ABE_on()) {
            static const char* const eq[8] = {"add", "sub", "rsub", "min", "max", "abs", "eq6", "eq7"};
            s += fmtStr("; blend %s(%s, %s)", eq[st.BLEND_eq() & 7], blendFactorName(st.BLEND_a(), true),
                        blendFactorName(st.BLEND_b(), false));
            if (st.BLEND_a() >= 10 || st.BLEND_b() >= 10) s += fmtStr(" fix 0x%06x/0x%06x", st.FIXA_rgb(), st.FIXB_rgb());
        } else {
            s += "; blend off";
        }
        if (st.LOE_on()) s += fmtStr("; logic op %u", st.LOP_op());
        if (st.ATE_on()) s += fmtStr("; alpha test %s 0x%02x mask 0x%02x", cmpName(st.ATEST_func()), st.ATEST_ref(), st.ATEST_mask());
        if (st.CTE_on()) s += fmtStr("; colour test %s", cmpName(st.CTEST_func() & 3));
        if (st.ZTE_on()) s += fmtStr("; depth test %s%s", cmpName(st.ZTEST_func()), st.ZMSK_nowrite() ? " no-write" : "");
        else s += "; depth test off";
        if (st.STE_on())
            s += fmtStr("; stencil %s 0x%02x mask 0x%02x ops %u/%u/%u", cmpName(st.STEST_func()), st.STEST_ref(),
                        st.STEST_mask(), st.SOP_sfail(), st.SOP_zfail(), st.SOP_zpass());
        if (st.FGE_on() && !st.isThrough()) s += fmtStr("; fog 0x%06x", st.FC_rgb());
        if (st.LTE_on() && !st.isThrough()) s += "; lighting";
        if (st.DTE_on()) s += "; dither";
    }
    if (st.PMSK1_rgb() || st.PMSK2_alpha()) s += fmtStr("; pixel mask 0x%06x/0x%02x", st.PMSK1_rgb(), st.PMSK2_alpha());
    s += fmtStr("; fb 0x%08x/%u %s; z 0x%08x/%u", st.framebufAddr(), st.framebufStride(),
                bufferFormatName(st.framebufFormat()), st.depthbufAddr(), st.depthbufStride());
    return s;
}

std::string drawDescription(const DrawInfo& d) {
    if (d.draw == 0) return "not a draw (VRAM as loaded, transfers, CPU copies)";
    if (d.kind == "bezier" || d.kind == "spline") return d.kind + fmtStr(", %u control points", d.vertices);
    return d.kind + " " + primTypeName(d.prim) + fmtStr(", %u vertices", d.vertices);
}

// ---------------------------------------------------------------------------------------------
// Ownership replay

namespace {

constexpr int kW = 480, kH = 272;

struct Ownership {
    Memory& mem;
    u32 addr, stride, bpp;
    std::vector<u8> snap;
    std::vector<u32>& owner;
    u32 spanBegin, spanBytes;

    Ownership(Memory& m, u32 a, u32 s, u32 fmt, std::vector<u32>& own)
        : mem(m), addr(a), stride(s), bpp((fmt & 3) == GE_FORMAT_8888 ? 4 : 2), owner(own) {
        snap.assign(size_t(kW) * kH * bpp, 0);
        owner.assign(size_t(kW) * kH, 0);
        spanBegin = foldAddr(addr);
        spanBytes = ((kH - 1) * stride + kW) * bpp;
        diff(0);
    }
    bool overlaps(u32 a, u32 size) const {
        if (size >= Memory::kVramSize) return true;
        const u64 b = foldAddr(a);
        return b < u64(spanBegin) + spanBytes && u64(spanBegin) < b + size;
    }
    // Pixels whose bytes changed since the snapshot become `who`'s. Returns how many.
    u64 diff(u32 who) {
        u64 changed = 0;
        const size_t rowBytes = size_t(kW) * bpp;
        for (int y = 0; y < kH; ++y) {
            const u8* p = mem.ptr(addr + u32(y) * stride * bpp, u32(rowBytes));
            if (!p) continue;
            u8* s = &snap[size_t(y) * rowBytes];
            if (std::memcmp(p, s, rowBytes) == 0) continue;
            for (int x = 0; x < kW; ++x) {
                if (std::memcmp(p + x * bpp, s + x * bpp, bpp) == 0) continue;
                std::memcpy(s + x * bpp, p + x * bpp, bpp);
                owner[size_t(y) * kW + x] = who;
                ++changed;
            }
        }
        return changed;
    }
};

bool ownershipReplay(const dump::Dump& d, const RenderOptions& ro, u32 addr, u32 stride, u32 fmt, BlameResult& out,
                     std::unordered_map<u32, DrawInfo>& infos, u32& shownAddr, u32& shownStride, u32& shownFmt,
                     std::string& err) {
    Memory mem;
    std::unique_ptr<Renderer> backend = createBackend(ro, mem, err).renderer;
    if (!backend) return false;
    DrawHook hook(*backend);
    GeEngine eng(mem, &hook);
    Ownership own(mem, addr, stride, fmt, out.owner);
    infos.clear();
    hook.afterWrite = [&](u32 a, u32 size, bool transfer) {
        if (!own.overlaps(a, size)) return;
        if (transfer) backend->syncMemoryForRead(addr, own.spanBytes);
        own.diff(0);
    };
    hook.after = [&](u64 n) {
        backend->syncMemoryForRead(addr, own.spanBytes);
        if (own.diff(u32(n))) {
            DrawInfo info = hook.last();
            info.draw = n;
            const GeState& st = eng.state();
            info.state = stateSummary(st);
            info.fbAddr = st.framebufAddr();
            info.fbStride = st.framebufStride();
            info.fbFormat = st.framebufFormat();
            infos[u32(n)] = std::move(info);
        }
    };
    dump::ReplayOptions opt;
    opt.replayEnd = ro.replayEnd;
    opt.timing = ro.replayTiming;
    opt.maxGeMs = ro.maxGeMs;
    dump::ReplayResult res;
    if (!dump::replayDump(d, eng, opt, res, err)) return false;
    hook.after = nullptr;
    hook.afterWrite = nullptr;
    backend->flushToMemory();
    own.diff(0);  // anything the end of the frame changed without a draw
    out.draws = hook.draws();
    out.warning = res.warning;
    dump::displayedFramebuffer(res, eng.state(), shownAddr, shownStride, shownFmt);
    out.frame = readFrame(mem, addr, stride, fmt);
    return true;
}

}  // namespace

bool blameDump(const dump::Dump& d, const RenderOptions& ro, const BlameOptions& bo, BlameResult& out, std::string& err) {
    if (ro.scale != 1) {
        err = "blame works at render scale 1";
        return false;
    }
    // Pass 1: where is the displayed frame? (null backend: the engine state alone decides it)
    {
        Memory mem;
        NullRenderer null;
        GeEngine eng(mem, &null);
        dump::ReplayOptions opt;
        opt.replayEnd = ro.replayEnd;
        opt.timing = ro.replayTiming;
        opt.maxGeMs = ro.maxGeMs;
        dump::ReplayResult res;
        if (!dump::replayDump(d, eng, opt, res, err)) return false;
        dump::displayedFramebuffer(res, eng.state(), out.displayAddr, out.displayStride, out.displayFormat);
    }
    // Pass 2 (again if the real backend displayed another buffer).
    std::unordered_map<u32, DrawInfo> infos;
    for (int attempt = 0; attempt < 2; ++attempt) {
        u32 a = 0, s = 0, f = 0;
        if (!ownershipReplay(d, ro, out.displayAddr, out.displayStride, out.displayFormat, out, infos, a, s, f, err))
            return false;
        if (a == out.displayAddr && s == out.displayStride && f == out.displayFormat) break;
        out.displayAddr = a, out.displayStride = s, out.displayFormat = f;
    }
    // Reference.
    if (!bo.refPng.empty()) {
        if (!readImage(bo.refPng, out.reference, err)) return false;
    } else if (!bo.refBackend.empty()) {
        RenderOptions r2 = ro;
        r2.backend = bo.refBackend;
        RenderOutput ref;
        if (!renderDump(d, r2, ref, err)) {
            err = "reference backend " + bo.refBackend + ": " + err;
            return false;
        }
        out.reference = ref.frame;
    } else {
        err = "blame needs --ref PNG or --ref-backend B";
        return false;
    }
    if (out.reference.width < kW || out.reference.height < kH) {
        err = "reference image smaller than 480x272";
        return false;
    }
    // Differences per owner.
    std::map<u32, BlameOwner> by;
    double total = 0;
    out.differing = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const u32 a = out.frame.at(x, y), b = out.reference.at(x, y);
            double se = 0;
            for (int c = 0; c < 3; ++c) {
                const int dv = int((a >> (8 * c)) & 0xFF) - int((b >> (8 * c)) & 0xFF);
                se += double(dv * dv);
            }
            if (se == 0) continue;
            ++out.differing;
            total += se;
            const u32 who = out.owner[size_t(y) * kW + x];
            BlameOwner& o = by[who];
            if (o.pixels == 0) {
                o.x0 = o.x1 = x;
                o.y0 = o.y1 = y;
                auto it = infos.find(who);
                if (it != infos.end()) o.info = it->second;
                o.info.draw = who;
            }
            ++o.pixels;
            o.sqErr += se;
            o.x0 = std::min(o.x0, x), o.x1 = std::max(o.x1, x);
            o.y0 = std::min(o.y0, y), o.y1 = std::max(o.y1, y);
        }
    out.mse = total / (double(kW) * kH * 3);
    out.owners.clear();
    for (auto& [who, o] : by) {
        o.mse = o.sqErr / (double(kW) * kH * 3);
        o.share = total > 0 ? o.sqErr / total : 0;
        out.owners.push_back(o);
    }
    std::sort(out.owners.begin(), out.owners.end(), [](const BlameOwner& a, const BlameOwner& b) {
        if (a.sqErr != b.sqErr) return a.sqErr > b.sqErr;
        if (a.pixels != b.pixels) return a.pixels > b.pixels;
        return a.info.draw < b.info.draw;
    });
    return true;
}

namespace {
constexpr u32 kPalette[12] = {0xFF0000FF, 0xFF00FF00, 0xFFFF6000, 0xFF00FFFF, 0xFFFFFF00, 0xFFFF00FF,
                              0xFF0080FF, 0xFFFF0080, 0xFF80FF80, 0xFF8080FF, 0xFF008080, 0xFF404080};
}  // namespace

Image blamePicture(const BlameResult& r, int top) {
    Image img = r.frame;
    for (u32& p : img.rgba) {
        const u32 grey = (((p & 0xFF) + ((p >> 8) & 0xFF) + ((p >> 16) & 0xFF)) / 3) * 2 / 5;
        p = 0xFF000000u | grey << 16 | grey << 8 | grey;
    }
    std::unordered_map<u32, int> rank;
    for (int i = 0; i < int(r.owners.size()) && i < top; ++i) rank[r.owners[size_t(i)].info.draw] = i;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const u32 a = r.frame.at(x, y), b = r.reference.at(x, y);
            if (((a ^ b) & 0xFFFFFF) == 0) continue;
            auto it = rank.find(r.owner[size_t(y) * kW + x]);
            img.rgba[size_t(y) * kW + x] = it == rank.end() ? 0xFFFFFFFFu : kPalette[it->second % 12];
        }
    for (int i = 0; i < int(r.owners.size()) && i < top; ++i) {
        const BlameOwner& o = r.owners[size_t(i)];
        const u32 c = kPalette[i % 12];
        const int x0 = std::max(0, o.x0 - 1), y0 = std::max(0, o.y0 - 1);
        const int x1 = std::min(kW - 1, o.x1 + 1), y1 = std::min(kH - 1, o.y1 + 1);
        for (int x = x0; x <= x1; ++x) img.rgba[size_t(y0) * kW + x] = img.rgba[size_t(y1) * kW + x] = c;
        for (int y = y0; y <= y1; ++y) img.rgba[size_t(y) * kW + x0] = img.rgba[size_t(y) * kW + x1] = c;
    }
    return img;
}

int runBlameCommand(const std::string& dumpPath, const RenderOptions& ro, const BlameOptions& bo) {
    auto fail = [](const std::string& m) {
        std::fprintf(stderr, "ge2gl: %s\n", m.c_str());
        return 1;
    };
    if (bo.refPng.empty() == bo.refBackend.empty()) return fail("blame needs exactly one of --ref or --ref-backend");
    dump::Dump d;
    std::string err;
    if (!dump::loadDump(dumpPath, d, err)) return fail(err);
    BlameResult r;
    if (!blameDump(d, ro, bo, r, err)) return fail(dumpPath + ": " + err);
    if (!r.warning.empty()) std::fprintf(stderr, "ge2gl: warning: %s\n", r.warning.c_str());
    const std::string refName = bo.refPng.empty() ? "backend " + bo.refBackend : bo.refPng;
    std::printf("blame %s: backend %s vs %s\n", dumpPath.c_str(), ro.backend.c_str(), refName.c_str());
    std::printf("displayed: 0x%08x stride %u %s; %llu draws\n", r.displayAddr, r.displayStride,
                bufferFormatName(r.displayFormat), (unsigned long long)r.draws);
    std::printf("differing pixels: %llu of %d, MSE %.4f; %zu owners (draw 0: not a draw)\n",
                (unsigned long long)r.differing, kW * kH, r.mse, r.owners.size());
    if (!r.owners.empty()) std::printf("%4s %7s %8s %8s %10s  %-19s %s\n", "rank", "draw", "pixels", "share", "MSE", "bbox", "draw");
    const int top = std::max(0, bo.top);
    for (int i = 0; i < int(r.owners.size()) && i < top; ++i) {
        const BlameOwner& o = r.owners[size_t(i)];
        char bbox[48];
        std::snprintf(bbox, sizeof bbox, "(%d,%d)-(%d,%d)", o.x0, o.y0, o.x1, o.y1);
        std::printf("%4d %7llu %8llu %7.2f%% %10.4f  %-19s %s\n", i + 1, (unsigned long long)o.info.draw,
                    (unsigned long long)o.pixels, 100 * o.share, o.mse, bbox, drawDescription(o.info).c_str());
        if (o.info.draw) std::printf("%40s state: %s\n", "", o.info.state.c_str());
    }
    if (!bo.picturePath.empty() && !writePng(bo.picturePath, blamePicture(r, top), err)) return fail(err);
    if (!bo.jsonPath.empty()) {
        // Measurements with 6 significant digits, as this file has always had them.
        Json j;
        j["dump"] = dumpPath;
        j["backend"] = ro.backend;
        j["reference"] = refName;
        Json& display = j["display"];
        display["addr"] = r.displayAddr;
        display["stride"] = r.displayStride;
        display["format"] = bufferFormatName(r.displayFormat);
        j["draws"] = r.draws;
        j["differing_pixels"] = r.differing;
        j["mse"] = number6Value(r.mse);
        j["owner_count"] = r.owners.size();
        Json& ranked = j["top"] = Json::array();
        for (int i = 0; i < int(r.owners.size()) && i < top; ++i) {
            const BlameOwner& o = r.owners[size_t(i)];
            Json e;
            e["rank"] = i + 1;
            e["draw"] = o.info.draw;
            e["pixels"] = o.pixels;
            e["share"] = number6Value(o.share);
            e["mse"] = number6Value(o.mse);
            e["bbox"] = {o.x0, o.y0, o.x1, o.y1};
            e["kind"] = o.info.draw ? o.info.kind : "none";
            if (o.info.draw) {
                if (o.info.kind != "bezier" && o.info.kind != "spline") e["prim"] = primTypeName(o.info.prim);
                e["vertices"] = o.info.vertices;
                e["state"] = o.info.state;
            }
            ranked.push_back(std::move(e));
        }
        JsonLayout layout;
        layout.rowArrays = {"top"};
        std::ofstream f(bo.jsonPath);
        f << jsonDocument(j, layout);
        if (!f) return fail("cannot write " + bo.jsonPath);
    }
    std::fflush(stdout);
    return 0;
}

}  // namespace ge::tools
