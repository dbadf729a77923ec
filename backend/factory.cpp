// SPDX-License-Identifier: MIT
#include "backend/factory.h"

#include "softmodel/soft_renderer.h"
#ifdef GE2GL_HAVE_GL
#include "translator/gl_renderer.h"
#endif

namespace ge::backend {

namespace {

#ifdef GE2GL_HAVE_GL
gl::GlOptions glOptions(const BackendOptions& opt) {
    gl::GlOptions go;
    switch (opt.glContext) {
    case GlContext::OSMesa: go.context = gl::ContextKind::OSMesa; break;
    case GlContext::EGL: go.context = gl::ContextKind::EGL; break;
    case GlContext::Current: go.context = gl::ContextKind::Current; break;
    case GlContext::Null: go.context = gl::ContextKind::Null; break;
    }
    go.mode = opt.glMode == GlMode::Hw ? gl::GlMode::Hw : gl::GlMode::Exact;
    go.scale = opt.scale;
    switch (opt.glVertices) {
    case GlVertices::Auto: go.vertices = gl::GlOptions::Vertices::Auto; break;
    case GlVertices::Gpu: go.vertices = gl::GlOptions::Vertices::Gpu; break;
    case GlVertices::Cpu: go.vertices = gl::GlOptions::Vertices::Cpu; break;
    }
    go.baseline = opt.glBaseline;
    go.loader = opt.glLoader;
    go.shaderDumpDir = opt.shaderDumpDir;
    go.programCacheDir = opt.programCacheDir;
    go.accuracy = opt.accuracy;
    return go;
}

Backend createGl(Memory& mem, const BackendOptions& opt, std::string& err) {
    Backend b;
    std::unique_ptr<gl::GlRenderer> r = gl::createGlRenderer(mem, glOptions(opt), err);
    if (!r) return b;
    b.presenter = r.get();
    b.scaled = r.get();
    b.host = r.get();
    b.stats = r.get();
    b.renderer = std::move(r);
    return b;
}
#endif

}  // namespace

bool backendBuilt(BackendKind kind) {
#ifdef GE2GL_HAVE_GL
    (void)kind;
    return true;
#else
    return kind != BackendKind::Gl;
#endif
}

void preloadBackend(const BackendOptions& opt) {
#ifdef GE2GL_HAVE_GL
    if (opt.kind == BackendKind::Gl) gl::preloadContextLibrary(glOptions(opt).context);
#else
    (void)opt;
#endif
}

Backend createBackend(Memory& mem, const BackendOptions& opt, std::string& err) {
    Backend b;
    switch (opt.kind) {
    case BackendKind::Null: b.renderer = std::make_unique<NullRenderer>(); break;
    case BackendKind::Soft: {
        soft::SoftOptions so;
        so.threads = opt.threads;
        so.accuracy = opt.accuracy;
        b.renderer = soft::createSoftRenderer(mem, so);
        break;
    }
    case BackendKind::Gl:
#ifdef GE2GL_HAVE_GL
        b = createGl(mem, opt, err);
#else
        err = "the GL backend is not built into this version of ge2gl (GE2GL_BUILD_GL=OFF)";
#endif
        break;
    }
    return b;
}

}  // namespace ge::backend
