// SPDX-License-Identifier: MIT
// The GL renderer's class (translator-internal; the public face is gl_renderer.h). Its member
// functions are defined by concern:
//   gl_renderer.cpp      construction, the Renderer entry points (draws join the batch), stats;
//   gl_batch.cpp         a draw's setup, batching and the batch's GL draw (flush), GPU-vertex draws;
//   gl_rtt_transfer.cpp  block transfers and render-to-texture (on the GPU in hardware mode);
//   gl_present_host.cpp  host calls: entering/leaving the host's context, presenting and reading
//                        frames, forgetting guest memory.
#pragma once
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "shadergen/keys_from_state.h"
#include "shadergen/shader_gen.h"
#include "translator/framebuffer_manager.h"
#include "translator/gl_context.h"
#include "translator/gl_host_state.h"
#include "translator/gl_renderer.h"
#include "translator/gl_state_cache.h"
#include "translator/gpu_vertex_path.h"
#include "translator/present.h"
#include "translator/shader_cache.h"
#include "translator/texture_cache.h"
#include "translator/vertex_pipeline.h"

namespace ge::gl {

class GlRendererImpl final : public GlRenderer {
public:
    // `hostState`: what the host's context held before creation (Current contexts), restored by
    // the first hostLeave().
    GlRendererImpl(Memory& mem, const GlOptions& opt, std::unique_ptr<GlContext> ctx, const HostGlState& hostState);
    ~GlRendererImpl() override;

    // ---- Host calls (gl_present_host.cpp) ----
    bool hostEnter(std::string& err) override;
    void hostLeave() override;
    unsigned presentFrame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, int outW, int outH,
                          std::string& err) override;
    int renderScale() const override { return scale_; }
    int readScaledFrame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, std::vector<u32>& rgba) override;
    void forgetGuestMemory() override;
    void hostMayHaveWritten(bool frameBuffers) override;
    bool holdsNewerThanMemory(u32 addr, u32 size) const override;
    void takeDirtyRanges(std::vector<std::pair<u32, u32>>& out) override;
    GlStats stats() const override;
    std::string statsText() const override { return glStatsText(stats()); }

    // ---- Renderer (gl_renderer.cpp; blockTransfer in gl_rtt_transfer.cpp) ----
    u64 pixelWork() const override { return pipeline_.pixelWork(); }
    void setPixelBudget(u64 pixels) override { pipeline_.setPixelBudget(pixels); }
    void drawPrim(const PrimPacket& p) override;
    void drawPatch(const PatchPacket& p) override;
    void drawImmediate(const ImmPacket& p) override;
    void blockTransfer(const TransferPacket& t, Memory& mem) override;
    void clutLoaded(const GeState&) override { ++generation_; }
    void textureFlush() override { ++generation_; }
    void textureSync() override { flush(); }
    void finish() override { flush(); }
    void syncMemoryForRead(u32 addr, u32 size) override;
    void memoryWritten(u32 addr, u32 size) override;
    void flushToMemory() override;

private:
    // gl_present_host.cpp
    bool currentIsOurs(std::string& err) const;
    void forgetGlState();

    // gl_renderer.cpp
    void startDraw(const GeState& st, const shadergen::DrawFlags& flags);
    void addDraw();
    static void drawOutputFull(void* self) { static_cast<GlRendererImpl*>(self)->addDraw(); }
    static constexpr size_t kBatchTriangles = kGlBatchTriangles;
    void noteError(const std::string& e);

    // gl_batch.cpp
    bool beginDraw(const GeState& st, const shadergen::DrawFlags& flags);
    bool makeSetup(const GeState& st, const shadergen::DrawFlags& flags, DrawSetup& s);
    // The keys and fragment uniforms of a draw, made again only when they may differ (setupFor).
    struct KeyCache {
        bool valid = false;
        const GeState* state = nullptr;
        shadergen::DrawFlags flags{};
        shadergen::PipelineKeys keys{};
        shadergen::FsUniforms u{};
        bool clutHashed = false;  // clutHash holds hashBytes of the state's CLUT
        u64 clutHash = 0;
    };
    KeyCache& setupFor(const GeState& st, const shadergen::DrawFlags& flags);
    void noteDirty(u32 groups) {
        setupDirty_ |= groups;
        pipeline_.noteDirty(groups);
    }
    struct GpuDrawState {
        shadergen::DrawFlags flags{};
        bool dstTexture = false, texture = false, fog = false, cull = false;
    };
    GpuDrawState gpuDrawState(const GeState& st);
    bool drawPrimOnGpu(const PrimPacket& p);
    bool drawPatchOnGpu(const PatchPacket& p);
    void submitGpuDraw(const GeState& st, const shadergen::DrawFlags& flags);
    bool batchOverlaps(u32 begin, u32 end) const;
    // Whether draws wait in a batch: the CPU path's triangles (geo_) or the GPU path's joined
    // draws (gpuBatch_); at most one of them at a time, both with batchSetup_.
    bool pending() const { return !geo_.empty() || gpuBatch_.draws != 0; }
    void flush();
    void flushGpu();

    // gl_rtt_transfer.cpp
    bool transferOnGpu(const TransferPacket& t);
    bool sampleTarget(const GeState& st, DrawSetup& s);
    GLuint paletteTexture(const GeState& st);

    HostGlState hostState_;  // Current contexts: the host's state while ge2gl works (hostEnter)
    Memory& mem_;
    GlOptions opt_;
    const bool hw_;  // GlMode::Hw
    bool gpuVertices_ = false;  // hw mode with GlOptions::vertices resolved to Gpu
    std::unique_ptr<GlContext> ctx_;
    // Destroyed after every member below (they delete GL objects in their destructors) and before
    // the context: the destructor enters the context, this leaves it once they are gone, so a
    // headless context's deletes never land in a host's context current on the thread.
    struct LeaveWhenDestroyed {
        GlContext* ctx = nullptr;
        ~LeaveWhenDestroyed() {
            if (ctx) ctx->leave();
        }
    } leaveGuard_;
    const GlFuncs& gl_;
    shadergen::HostCaps caps_;
    bool useBarrier_ = false;
    ProgramCache programs_;
    TextureCache textures_;
    FramebufferManager fb_;
    const int scale_;
    VertexPipeline pipeline_{opt_.accuracy};
    GpuVertexPath gpu_;
    GpuDraw gpuDraw_;   // the draw being prepared
    GpuDraw gpuBatch_;  // GPU draws waiting (draws != 0), joined into one GL draw (flushGpu)
    geo::TessOutput tess_;  // the GPU path's patch tessellation (reused)
    u64 batchGeneration_ = 0;
    Geometry geo_;
    Geometry drawGeo_;  // the current draw's geometry, before it joins the batch
    const GeState* drawState_ = nullptr;  // the current draw's state and flags (startDraw)
    shadergen::DrawFlags drawFlags_{};
    DrawSetup batchSetup_;
    KeyCache keyCache_;
    u32 setupDirty_ = DIRTY_ALL;  // GeDirty groups changed since keyCache_ was made
    GlStateCache state_;  // what GL holds (gl_state_cache.h)
    u64 generation_ = 1;
    GLuint vao_ = 0, vbo_ = 0;
    std::string probeLabel_;  // GL_CURRENT with KHR_debug: vbo_'s label (currentIsOurs)
    GLuint snapColor_ = 0, snapDepth_ = 0, snapFbo_ = 0;
    std::unique_ptr<Presenter> presenter_;
    int hostDepth_ = 1;
    GLuint recordBuf_ = 0, recordTex_ = 0;
    GLuint gradientBuf_ = 0, gradientTex_ = 0;  // the records' gradient planes (tri_setup.h)
    std::unordered_map<u64, GLuint> palettes_;  // paletteTexture
    GlStats stats_;
    std::string lastError_;
    u64 errors_ = 0;
};

}  // namespace ge::gl
