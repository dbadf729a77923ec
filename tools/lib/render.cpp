// SPDX-License-Identifier: MIT
#include "tools/lib/render.h"

#include <chrono>
#include <filesystem>
#include <optional>

#include "softmodel/soft_renderer.h"
#include "tools/lib/draw_hook.h"
#ifdef GE2GL_HAVE_GL
#include "translator/gl_renderer.h"
#endif

namespace ge::tools {

std::unique_ptr<Renderer> createBackend(const RenderOptions& opt, Memory& mem, std::string& err) {
    if (opt.backend == "null") return std::make_unique<NullRenderer>();
    if (opt.backend == "soft") {
        soft::SoftOptions so;
        so.threads = opt.threads;
        return soft::createSoftRenderer(mem, so);
    }
    if (opt.backend == "gl") {
#ifdef GE2GL_HAVE_GL
        gl::GlOptions go;
        if (opt.glContext == "egl") go.context = gl::ContextKind::EGL;
        else if (opt.glContext == "null") go.context = gl::ContextKind::Null;
        else if (opt.glContext != "osmesa") {
            err = "unknown GL context '" + opt.glContext + "' (use osmesa, egl or null)";
            return nullptr;
        }
        go.baseline = opt.glBaseline;
        if (opt.glMode == "hw") go.mode = gl::GlMode::Hw;
        else if (opt.glMode != "exact") {
            err = "unknown GL mode '" + opt.glMode + "' (use exact or hw)";
            return nullptr;
        }
        go.scale = opt.scale;
        if (opt.glVertices == "gpu") go.vertices = gl::GlOptions::Vertices::Gpu;
        else if (opt.glVertices == "cpu") go.vertices = gl::GlOptions::Vertices::Cpu;
        else if (opt.glVertices != "auto") {
            err = "unknown vertex path '" + opt.glVertices + "' (use auto, gpu or cpu)";
            return nullptr;
        }
        go.shaderDumpDir = opt.shaderDumpDir;
        go.programCacheDir = opt.programCacheDir;
        auto r = gl::createGlRenderer(mem, go, err);
        if (!r && err.empty()) err = "could not create the GL backend";
        return r;
#else
        err = "backend 'gl' is not built in this version of ge2gl";
        return nullptr;
#endif
    }
    err = "unknown backend '" + opt.backend + "' (use soft, gl or null)";
    return nullptr;
}

std::string backendStats(const std::string& backend, const Renderer& r) {
#ifdef GE2GL_HAVE_GL
    if (backend == "gl") return gl::glStatsText(gl::glStats(r));
#endif
    (void)backend;
    (void)r;
    return {};
}

bool renderDump(const dump::Dump& d, const RenderOptions& opt, RenderOutput& out, std::string& err,
                std::vector<u8>* vramOut, std::vector<u16>* depthOut, Memory* reuse, std::unique_ptr<Renderer>* backend) {
    auto t0 = std::chrono::steady_clock::now();
    std::optional<Memory> fresh;
    if (reuse) reuse->clear();
    Memory& mem = reuse ? *reuse : fresh.emplace();
    std::unique_ptr<Renderer> own;
    const bool held = backend && reuse;
    std::unique_ptr<Renderer>& r = held ? *backend : own;
    const bool reused = r != nullptr;
    if (!r) {
        r = createBackend(opt, mem, err);
        if (!r) return false;
    }
#ifdef GE2GL_HAVE_GL
    // A GL renderer is created with its context current (entered). One held between replays
    // leaves it and enters again for each replay: another GL renderer created or destroyed on
    // this thread in between (the fuzzer's fresh re-checks, blame) changes the current context,
    // and a held renderer that stayed "entered" sent its GL calls to no context (black frames).
    struct HostScope {
        Renderer* r = nullptr;
        ~HostScope() {
            if (r) gl::glHostLeave(*r);
        }
    } hostScope;
    if (held && opt.backend == "gl") {
        if (!reused) gl::glHostLeave(*r);
        if (!gl::glHostEnter(*r, err)) return false;
        hostScope.r = r.get();
    }
#endif
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
    GeEngine eng(mem, hook ? static_cast<Renderer*>(&*hook) : r.get());
    dump::ReplayOptions ro;
    ro.replayEnd = opt.replayEnd;
    ro.timing = opt.replayTiming;
    ro.maxGeMs = opt.maxGeMs;
    if (!dump::replayDump(d, eng, ro, out.replay, err)) return false;
    dump::displayedFramebuffer(out.replay, eng.state(), out.displayAddr, out.displayStride, out.displayFormat);
    out.frame = readFrame(mem, out.displayAddr, out.displayStride, out.displayFormat);
#ifdef GE2GL_HAVE_GL
    if (opt.backend == "gl" && opt.scale > 1) {
        // The displayed frame at render scale, from the scaled render target.
        Image& hi = out.frameScaled;
        hi.width = 480 * opt.scale, hi.height = 272 * opt.scale;
        gl::glReadScaledFrame(*r, out.displayAddr, out.displayStride, GeBufferFormat(out.displayFormat & 3), 480, 272,
                              hi.rgba);
        out.frame = boxDownsample(hi, opt.scale);
    }
#endif
    out.engineStats = eng.stats();
    out.backendStats = backendStats(opt.backend, *r);
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

bool renderDumpFile(const std::string& path, const RenderOptions& opt, RenderOutput& out, std::string& err,
                    std::vector<u8>* vramOut, std::vector<u16>* depthOut) {
    auto t0 = std::chrono::steady_clock::now();
    dump::Dump d;
    if (!dump::loadDump(path, d, err)) return false;
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
