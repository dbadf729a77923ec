// SPDX-License-Identifier: MIT
#include "tools/lib/render.h"

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <thread>

#include "tools/lib/draw_hook.h"

namespace ge::tools {

namespace {

// The backend options a render asks for; false + err for an unknown name or a backend not built.
bool backendOptions(const RenderOptions& opt, backend::BackendOptions& bo, std::string& err) {
    if (!geo::AccuracyProfile::fromName(opt.accuracy.c_str(), bo.accuracy)) {
        err = "unknown accuracy profile '" + opt.accuracy + "' (use psp or ppsspp, optionally +SWITCH/-SWITCH)";
        return false;
    }
    if (opt.backend == "null") {
        bo.kind = backend::BackendKind::Null;
    } else if (opt.backend == "soft") {
        bo.kind = backend::BackendKind::Soft;
        bo.threads = opt.threads;
    } else if (opt.backend == "gl") {
        if (!backend::backendBuilt(backend::BackendKind::Gl)) {
            err = "backend 'gl' is not built in this version of ge2gl";
            return false;
        }
        bo.kind = backend::BackendKind::Gl;
        if (opt.glContext == "egl") bo.glContext = backend::GlContext::EGL;
        else if (opt.glContext == "null") bo.glContext = backend::GlContext::Null;
        else if (opt.glContext != "osmesa") {
            err = "unknown GL context '" + opt.glContext + "' (use osmesa, egl or null)";
            return false;
        }
        bo.glBaseline = opt.glBaseline;
        if (opt.glMode == "hw") bo.glMode = backend::GlMode::Hw;
        else if (opt.glMode != "exact") {
            err = "unknown GL mode '" + opt.glMode + "' (use exact or hw)";
            return false;
        }
        bo.scale = opt.scale;
        if (opt.glVertices == "gpu") bo.glVertices = backend::GlVertices::Gpu;
        else if (opt.glVertices == "cpu") bo.glVertices = backend::GlVertices::Cpu;
        else if (opt.glVertices != "auto") {
            err = "unknown vertex path '" + opt.glVertices + "' (use auto, gpu or cpu)";
            return false;
        }
        bo.shaderDumpDir = opt.shaderDumpDir;
        bo.programCacheDir = opt.programCacheDir;
    } else {
        err = "unknown backend '" + opt.backend + "' (use soft, gl or null)";
        return false;
    }
    return true;
}

}  // namespace

backend::Backend createBackend(const RenderOptions& opt, Memory& mem, std::string& err) {
    backend::BackendOptions bo;
    if (!backendOptions(opt, bo, err)) return {};
    backend::Backend b = backend::createBackend(mem, bo, err);
    if (!b && err.empty()) err = "could not create the GL backend";  // soft and null always start
    return b;
}

std::string backendStats(const backend::Backend& b) { return b.stats ? b.stats->statsText() : std::string(); }

bool renderDump(const dump::Dump& d, const RenderOptions& opt, RenderOutput& out, std::string& err,
                std::vector<u8>* vramOut, std::vector<u16>* depthOut, Memory* reuse, backend::Backend* held) {
    auto t0 = std::chrono::steady_clock::now();
    std::optional<Memory> fresh;
    if (reuse) reuse->clear();
    Memory& mem = reuse ? *reuse : fresh.emplace();
    backend::Backend own;
    const bool keep = held && reuse;
    backend::Backend& be = keep ? *held : own;
    const bool reused = bool(be);
    if (!be) {
        be = createBackend(opt, mem, err);
        if (!be) return false;
    }
    Renderer* r = be.renderer.get();
    // A backend working in a GL context is created with it current (entered). One held between
    // replays leaves it and enters again for each replay: another GL renderer created or
    // destroyed on this thread in between (the fuzzer's fresh re-checks, blame) changes the
    // current context, and a held renderer that stayed "entered" sent its GL calls to no context
    // (black frames).
    struct HostScope {
        backend::HostContextUser* host = nullptr;
        ~HostScope() {
            if (host) host->hostLeave();
        }
    } hostScope;
    if (keep && be.host) {
        if (!reused) be.host->hostLeave();
        if (!be.host->hostEnter(err)) return false;
        hostScope.host = be.host;
    }
    if (reused) {
        // Everything the backend cached from memory is stale: the replay starts from cleared memory.
        r->memoryWritten(0x04000000, Memory::kVramSize);
        r->memoryWritten(0x08000000, mem.ramSize());
        r->textureFlush();
    }
    // --skip / --only: the hook sits between the engine and the backend; everything else
    // (readback, scaled frame, stats) talks to the backend itself.
    std::optional<DrawHook> hook;
    if (opt.keepDraw) hook.emplace(*r).keep = opt.keepDraw;
    GeEngine eng(mem, hook ? static_cast<Renderer*>(&*hook) : r);
    dump::ReplayOptions ro;
    ro.replayEnd = opt.replayEnd;
    ro.timing = opt.replayTiming;
    ro.maxGeMs = opt.maxGeMs;
    if (!dump::replayDump(d, eng, ro, out.replay, err)) return false;
    dump::displayedFramebuffer(out.replay, eng.state(), out.displayAddr, out.displayStride, out.displayFormat);
    out.frame = readFrame(mem, out.displayAddr, out.displayStride, out.displayFormat);
    if (be.scaled && opt.scale > 1) {
        // The displayed frame at render scale, from what the backend drew at that scale.
        Image& hi = out.frameScaled;
        hi.width = 480 * opt.scale, hi.height = 272 * opt.scale;
        be.scaled->readScaledFrame(out.displayAddr, out.displayStride, GeBufferFormat(out.displayFormat & 3), 480, 272,
                                   hi.rgba);
        out.frame = boxDownsample(hi, opt.scale);
    }
    out.engineStats = eng.stats();
    out.backendStats = backendStats(be);
    out.depthAddr = eng.state().depthbufAddr();
    out.depthStride = eng.state().depthbufStride();
    if (vramOut) vramOut->assign(mem.vram(), mem.vram() + Memory::kVramSize);
    if (depthOut) {
        depthOut->assign(480 * 272, 0);
        const u32 stride = out.depthStride ? out.depthStride : 512;
        for (u32 y = 0; y < 272; ++y)
            for (u32 x = 0; x < 480; ++x) (*depthOut)[y * 480 + x] = mem.read16(out.depthAddr + 2 * (y * stride + x));
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return true;
}

std::string defaultProgramCacheDir() {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    if (xdg && xdg[0] == '/') return std::string(xdg) + "/ge2gl/programs";  // the spec ignores relative paths
    const char* home = std::getenv("HOME");
    if (home && home[0]) return std::string(home) + "/.cache/ge2gl/programs";
    return {};
}

bool renderDumpFile(const std::string& path, const RenderOptions& opt, RenderOutput& out, std::string& err,
                    std::vector<u8>* vramOut, std::vector<u16>* depthOut) {
    auto t0 = std::chrono::steady_clock::now();
    dump::Dump d;
    // A GL context's library (OSMesa or EGL, with libLLVM: tens of milliseconds to load and
    // relocate) loads on another thread while the dump is read and decompressed.
    std::thread preload;
    backend::BackendOptions bo;
    std::string ignored;  // a bad option is reported when the backend is made
    if (backendOptions(opt, bo, ignored) && bo.kind == backend::BackendKind::Gl)
        preload = std::thread([bo] { backend::preloadBackend(bo); });
    const bool loaded = dump::loadDump(path, d, err);
    if (preload.joinable()) preload.join();
    if (!loaded) return false;
    if (!renderDump(d, opt, out, err, vramOut, depthOut)) {
        err = path + ": " + err;  // load errors already name the file
        return false;
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return true;
}

std::string dumpName(const std::string& path) {
    std::string n = std::filesystem::path(path).filename().string();
    auto strip = [&](const char* suf) {
        size_t l = std::strlen(suf);
        if (n.size() >= l) {
            std::string tail = n.substr(n.size() - l);
            for (auto& c : tail) c = char(std::tolower(static_cast<unsigned char>(c)));
            if (tail == suf) n.resize(n.size() - l);
        }
    };
    strip(".zip");
    strip(".ppdmp");
    return n;
}

}  // namespace ge::tools
