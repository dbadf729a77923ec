// SPDX-License-Identifier: MIT
#include "tools/lib/bisect.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <thread>

#include "hle/disasm.h"
#include "hle/pixel_format.h"
#include "tools/lib/draw_hook.h"
#include "tools/lib/json_io.h"

namespace ge::tools {

std::vector<u32> commandsBeforeDraw(const dump::Dump& d, u64 n, size_t maxWords, bool& truncated) {
    truncated = false;
    std::vector<u32> cur;
    u64 k = 0;
    for (const dump::Record& r : d.records) {
        if (r.type != dump::REGISTERS) continue;
        const u8* p = d.payload(r);
        if (!p) continue;
        for (u32 i = 0; i < r.size / 4; ++i) {
            const u32 w = readLE32(p + 4 * i);
            cur.push_back(w);
            const u8 op = u8(w >> 24);
            bool draw = false;
            if (op == GE_CMD_PRIM) draw = (w & 0xFFFF) != 0;
            else if (op == GE_CMD_BEZIER || op == GE_CMD_SPLINE) draw = (w & 0xFF) && ((w >> 8) & 0xFF);
            if (!draw) {
                if (cur.size() > 4 * maxWords + 64) {  // keep memory bounded on long stretches
                    cur.erase(cur.begin(), cur.end() - long(maxWords));
                    truncated = true;
                }
                continue;
            }
            if (++k == n) {
                if (cur.size() > maxWords) {
                    cur.erase(cur.begin(), cur.end() - long(maxWords));
                    truncated = true;
                }
                return cur;
            }
            cur.clear();
            truncated = false;
        }
    }
    return {};
}

namespace {

struct Side {
    const dump::Dump* dump = nullptr;
    RenderOptions ro;
    std::unique_ptr<Memory> mem;
    std::unique_ptr<Renderer> backend;
    std::unique_ptr<DrawHook> hook;
    std::unique_ptr<GeEngine> eng;
    dump::ReplayResult res;
    std::string err;
    bool ok = false;
};

u32 pixelRGBA(const u8* p, u32 fmt) {
    if ((fmt & 3) == GE_FORMAT_8888) return readLE32(p);
    return decodePixel16(readLE16(p), GeBufferFormat(fmt & 3));
}

class Lockstep {
public:
    Lockstep(Side (&s)[2], const BisectOptions& bo, BisectResult& out) : s_(s), bo_(bo), out_(out) {}
    std::atomic<bool> stop{false};

    // Side i has just drawn draw n.
    void arrive(int i, u64 n) {
        if (stop) return;
        sync(s_[i]);
        std::unique_lock lk(m_);
        if (stop) return;
        if (++arrived_ == 2) {
            compare(n);
            release();
            return;
        }
        if (done_[1 - i]) {
            extraDraw(i, n);
            release();
            return;
        }
        const u64 g = gen_;
        cv_.wait(lk, [&] { return gen_ != g || done_[1 - i]; });
        if (gen_ == g) {  // the other side ended while this one waited
            extraDraw(i, n);
            release();
        }
    }
    void finished(int i, bool failed) {
        std::lock_guard lk(m_);
        done_[i] = true;
        if (failed) stop = true;
        cv_.notify_all();
    }

private:
    void release() {
        arrived_ = 0;
        ++gen_;
        cv_.notify_all();
    }
    static void scissor(const GeState& st, int& x0, int& y0, int& x1, int& y1) {
        x0 = int(st.SCISSOR1_x()), y0 = int(st.SCISSOR1_y());
        x1 = int(st.SCISSOR2_x()), y1 = int(st.SCISSOR2_y());
    }
    void sync(Side& s) {
        if (bo_.allVram) {
            s.backend->syncMemoryForRead(Memory::kVramBase, Memory::kVramSize);
            return;
        }
        const GeState& st = s.eng->state();
        int x0, y0, x1, y1;
        scissor(st, x0, y0, x1, y1);
        if (x1 < x0 || y1 < y0) return;
        const u32 bpp = st.framebufFormat() == GE_FORMAT_8888 ? 4 : 2;
        const u32 stride = st.framebufStride();
        s.backend->syncMemoryForRead(st.framebufAddr() + (u32(y0) * stride + u32(x0)) * bpp,
                                     ((u32(y1 - y0)) * stride + u32(x1 - x0 + 1)) * bpp);
        if (!bo_.ignoreDepth) {
            const u32 zs = st.depthbufStride();
            s.backend->syncMemoryForRead(st.depthbufAddr() + (u32(y0) * zs + u32(x0)) * 2,
                                         ((u32(y1 - y0)) * zs + u32(x1 - x0 + 1)) * 2);
        }
    }
    DrawInfo info(Side& s, u64 n) {
        DrawInfo d = s.hook->last();
        d.draw = n;
        const GeState& st = s.eng->state();
        d.state = stateSummary(st);
        d.fbAddr = st.framebufAddr();
        d.fbStride = st.framebufStride();
        d.fbFormat = st.framebufFormat();
        return d;
    }
    void found(u64 n, const char* reason) {
        out_.found = true;
        out_.draw = n;
        out_.reason = reason;
        out_.infoA = info(s_[0], n);
        out_.infoB = info(s_[1], n);
        stop = true;
    }
    void extraDraw(int i, u64 n) {
        out_.found = true;
        out_.draw = n;
        out_.reason = "draw count";
        (i == 0 ? out_.infoA : out_.infoB) = info(s_[i], n);
        stop = true;
    }
    void grow(int x, int y) {
        if (out_.x1 < out_.x0) {
            out_.x0 = out_.x1 = x, out_.y0 = out_.y1 = y;
            return;
        }
        out_.x0 = std::min(out_.x0, x), out_.x1 = std::max(out_.x1, x);
        out_.y0 = std::min(out_.y0, y), out_.y1 = std::max(out_.y1, y);
    }
    void compare(u64 n) {
        const Memory& ma = *s_[0].mem;
        const Memory& mb = *s_[1].mem;
        if (bo_.allVram) {
            const u8* a = ma.vram();
            const u8* b = mb.vram();
            if (std::memcmp(a, b, Memory::kVramSize) == 0) return;
            u64 count = 0;
            for (u32 k = 0; k < Memory::kVramSize; ++k)
                if (a[k] != b[k]) {
                    if (!count) out_.firstVramAddr = Memory::kVramBase + k;
                    out_.lastVramAddr = Memory::kVramBase + k;
                    ++count;
                }
            out_.vramBytes = count;
            found(n, "vram");
            return;
        }
        const GeState& sa = s_[0].eng->state();
        const GeState& sb = s_[1].eng->state();
        int ax0, ay0, ax1, ay1, bx0, by0, bx1, by1;
        scissor(sa, ax0, ay0, ax1, ay1);
        scissor(sb, bx0, by0, bx1, by1);
        const bool emptyA = ax1 < ax0 || ay1 < ay0, emptyB = bx1 < bx0 || by1 < by0;
        int x0 = emptyA ? bx0 : emptyB ? ax0 : std::min(ax0, bx0);
        int y0 = emptyA ? by0 : emptyB ? ay0 : std::min(ay0, by0);
        int x1 = emptyA ? bx1 : emptyB ? ax1 : std::max(ax1, bx1);
        int y1 = emptyA ? by1 : emptyB ? ay1 : std::max(ay1, by1);
        out_.rx0 = x0, out_.ry0 = y0, out_.rx1 = x1, out_.ry1 = y1;
        if (sa.framebufAddr() != sb.framebufAddr() || sa.framebufStride() != sb.framebufStride() ||
            sa.framebufFormat() != sb.framebufFormat() ||
            (!bo_.ignoreDepth && (sa.depthbufAddr() != sb.depthbufAddr() || sa.depthbufStride() != sb.depthbufStride()))) {
            found(n, "target");
            return;
        }
        if (x1 < x0 || y1 < y0) return;
        const u32 fmt = sa.framebufFormat(), bpp = fmt == GE_FORMAT_8888 ? 4 : 2, stride = sa.framebufStride();
        const u32 fb = sa.framebufAddr(), zb = sa.depthbufAddr(), zs = sa.depthbufStride();
        const u32 w = u32(x1 - x0 + 1);
        const int tol = bo_.tolerance;
        u64 colour = 0, depth = 0;
        for (int y = y0; y <= y1; ++y) {
            const u32 rowAddr = fb + (u32(y) * stride + u32(x0)) * bpp;
            const u8* pa = ma.ptr(rowAddr, w * bpp);
            const u8* pb = mb.ptr(rowAddr, w * bpp);
            if (pa && pb && std::memcmp(pa, pb, w * bpp) != 0) {
                for (u32 x = 0; x < w; ++x) {
                    const u32 ca = pixelRGBA(pa + x * bpp, fmt), cb = pixelRGBA(pb + x * bpp, fmt);
                    if (ca == cb) continue;
                    bool differs = false;
                    for (int c = 0; c < 4 && !differs; ++c)
                        differs = std::abs(int((ca >> (8 * c)) & 0xFF) - int((cb >> (8 * c)) & 0xFF)) > tol;
                    if (!differs) continue;
                    ++colour;
                    grow(x0 + int(x), y);
                }
            }
            if (bo_.ignoreDepth) continue;
            const u32 zAddr = zb + (u32(y) * zs + u32(x0)) * 2;
            const u8* za = ma.ptr(zAddr, w * 2);
            const u8* zbp = mb.ptr(zAddr, w * 2);
            if (za && zbp && std::memcmp(za, zbp, w * 2) != 0) {
                for (u32 x = 0; x < w; ++x) {
                    if (readLE16(za + 2 * x) == readLE16(zbp + 2 * x)) continue;
                    ++depth;
                    grow(x0 + int(x), y);
                }
            }
        }
        if (!colour && !depth) return;
        out_.colourPixels = colour;
        out_.depthPixels = depth;
        found(n, colour ? "colour" : "depth");
    }

    Side (&s_)[2];
    const BisectOptions& bo_;
    BisectResult& out_;
    std::mutex m_;
    std::condition_variable cv_;
    int arrived_ = 0;
    u64 gen_ = 0;
    bool done_[2] = {false, false};
};

void runSide(Side& s, int i, Lockstep& ls) {
    s.mem = std::make_unique<Memory>();
    s.backend = createBackend(s.ro, *s.mem, s.err).renderer;
    if (!s.backend) {
        ls.finished(i, true);
        return;
    }
    s.hook = std::make_unique<DrawHook>(*s.backend);
    s.eng = std::make_unique<GeEngine>(*s.mem, s.hook.get());
    s.hook->keep = [&ls](u64) { return !ls.stop.load(); };
    s.hook->after = [&ls, i](u64 n) { ls.arrive(i, n); };
    dump::ReplayOptions opt;
    opt.replayEnd = s.ro.replayEnd;
    opt.timing = s.ro.replayTiming;
    opt.maxGeMs = s.ro.maxGeMs;
    s.ok = dump::replayDump(*s.dump, *s.eng, opt, s.res, s.err);
    ls.finished(i, !s.ok);
}

}  // namespace

bool bisectDumps(const dump::Dump& a, const RenderOptions& roA, const dump::Dump& b, const RenderOptions& roB,
                 const BisectOptions& bo, BisectResult& out, std::string& err) {
    if (roA.scale != 1 || roB.scale != 1) {
        err = "bisect works at render scale 1";
        return false;
    }
    Side sides[2];
    sides[0].dump = &a, sides[0].ro = roA;
    sides[1].dump = &b, sides[1].ro = roB;
    Lockstep ls(sides, bo, out);
    std::thread tb([&] { runSide(sides[1], 1, ls); });
    runSide(sides[0], 0, ls);
    tb.join();
    for (int i = 0; i < 2; ++i)
        if (!sides[i].ok) {
            err = std::string(i ? "reference side: " : "") + (sides[i].err.empty() ? "replay failed" : sides[i].err);
            return false;
        }
    out.drawsA = sides[0].hook->draws();
    out.drawsB = sides[1].hook->draws();
    return true;
}

int runBisectCommand(const std::string& dumpPath, const RenderOptions& ro, const BisectOptions& bo) {
    auto fail = [](const std::string& m) {
        std::fprintf(stderr, "ge2gl: %s\n", m.c_str());
        return 1;
    };
    if (bo.refBackend.empty() == bo.refDumpPath.empty()) return fail("bisect needs exactly one of --ref-backend or --ref-dump");
    dump::Dump a, other;
    std::string err;
    if (!dump::loadDump(dumpPath, a, err)) return fail(err);
    if (!bo.refDumpPath.empty() && !dump::loadDump(bo.refDumpPath, other, err)) return fail(err);
    const dump::Dump& b = bo.refDumpPath.empty() ? a : other;
    RenderOptions roB = ro;
    if (!bo.refBackend.empty()) roB.backend = bo.refBackend;
    BisectResult r;
    if (!bisectDumps(a, ro, b, roB, bo, r, err)) return fail(dumpPath + ": " + err);

    const std::string nameB = bo.refDumpPath.empty() ? dumpPath : bo.refDumpPath;
    std::string compared;
    if (bo.allVram) {
        compared = "all 2 MiB of VRAM, byte for byte";
    } else {
        compared = "colour of each draw's target in its scissor rectangle (RGBA, tolerance " + std::to_string(bo.tolerance) + ")";
        compared += bo.ignoreDepth ? ", depth ignored" : " and its depth buffer (exact)";
    }
    std::printf("bisect %s (%s) vs %s (%s)\n", dumpPath.c_str(), ro.backend.c_str(), nameB.c_str(), roB.backend.c_str());
    std::printf("compared after each draw: %s\n", compared.c_str());
    constexpr size_t kMaxWords = 200;
    bool truncA = false, truncB = false;
    if (r.found) {
        r.commandsA = commandsBeforeDraw(a, r.draw, kMaxWords, truncA);
        if (!bo.refDumpPath.empty()) r.commandsB = commandsBeforeDraw(b, r.draw, kMaxWords, truncB);
    }
    if (!r.found) {
        std::printf("no difference: %llu draws on each side\n", (unsigned long long)r.drawsA);
    } else {
        std::printf("first difference after draw %llu (%s); %llu draws in %s, %llu in the reference\n",
                    (unsigned long long)r.draw, r.reason.c_str(), (unsigned long long)r.drawsA, dumpPath.c_str(),
                    (unsigned long long)r.drawsB);
        if (r.reason == "vram") {
            std::printf("differing VRAM bytes: %llu, from 0x%08x to 0x%08x\n", (unsigned long long)r.vramBytes,
                        r.firstVramAddr, r.lastVramAddr);
        } else if (r.reason == "colour" || r.reason == "depth") {
            std::printf("differing: %llu colour pixels, %llu depth values; bbox (%d,%d)-(%d,%d) in (%d,%d)-(%d,%d)\n",
                        (unsigned long long)r.colourPixels, (unsigned long long)r.depthPixels, r.x0, r.y0, r.x1, r.y1,
                        r.rx0, r.ry0, r.rx1, r.ry1);
        } else if (r.reason == "target") {
            std::printf("the draw's frame/depth buffers differ between the sides\n");
        } else {
            std::printf("only one side has this draw\n");
        }
        if (r.infoA.draw) {
            std::printf("draw %llu: %s\n  state: %s\n", (unsigned long long)r.draw, drawDescription(r.infoA).c_str(),
                        r.infoA.state.c_str());
        }
        if (r.infoB.draw && (r.infoB.state != r.infoA.state || drawDescription(r.infoB) != drawDescription(r.infoA)))
            std::printf("reference draw %llu: %s\n  state: %s\n", (unsigned long long)r.draw,
                        drawDescription(r.infoB).c_str(), r.infoB.state.c_str());
        auto printCmds = [&](const std::vector<u32>& c, bool trunc, const std::string& name) {
            std::printf("commands since draw %llu in %s%s:\n", (unsigned long long)(r.draw - 1), name.c_str(),
                        trunc ? " (the last 200)" : "");
            for (u32 w : c) std::printf("  %08x  %s\n", w, disassemble(w).c_str());
        };
        if (!r.commandsA.empty()) printCmds(r.commandsA, truncA, dumpPath);
        if (!r.commandsB.empty() && r.commandsB != r.commandsA) printCmds(r.commandsB, truncB, nameB);
    }
    if (!bo.jsonPath.empty()) {
        Json j;
        j["dump"] = dumpPath;
        j["reference"] = nameB;
        j["backend"] = ro.backend;
        j["ref_backend"] = roB.backend;
        j["compared"] = compared;
        j["tolerance"] = bo.tolerance;
        j["found"] = r.found;
        j["draw"] = r.draw;
        j["draws"] = r.drawsA;
        j["ref_draws"] = r.drawsB;
        if (r.found) {
            j["reason"] = r.reason;
            j["colour_pixels"] = r.colourPixels;
            j["depth_pixels"] = r.depthPixels;
            j["bbox"] = {r.x0, r.y0, r.x1, r.y1};
            j["vram_bytes"] = r.vramBytes;
            if (r.infoA.draw) {
                j["kind"] = r.infoA.kind;
                j["vertices"] = r.infoA.vertices;
                if (r.infoA.kind != "bezier" && r.infoA.kind != "spline") j["prim"] = primTypeName(r.infoA.prim);
                j["state"] = r.infoA.state;
            }
            if (r.infoB.draw) j["ref_state"] = r.infoB.state;
            Json& commands = j["commands"] = Json::array();
            for (u32 w : r.commandsA) {
                char hex[12];
                std::snprintf(hex, sizeof hex, "%08x ", w);
                commands.push_back(hex + disassemble(w));
            }
        }
        std::ofstream f(bo.jsonPath);
        f << jsonDocument(j);
        if (!f) return fail("cannot write " + bo.jsonPath);
    }
    std::fflush(stdout);
    return 0;
}

}  // namespace ge::tools
