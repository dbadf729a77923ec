// SPDX-License-Identifier: MIT
// Render targets as caches of emulated VRAM: VRAM is the source of truth.
//
// A colour target is (VRAM address, stride, format) ↔ an RGBA8UI texture whose row y is drawing
// row y; it holds stored pixels (16-bit formats bit-replicated, i.e. what a GE read expands to).
// A depth target is (address, stride) ↔ a D32F texture holding z/65536.
//
// Render scale N (GL hardware mode): every PSP pixel is N×N texels of the target; the texture is
// (512 or 1024)·N wide (stride ≤ 512 or larger) and 512·N or 1024·N high (grown, contents kept,
// when a draw needs rows past 512). VRAM stays in PSP pixels: an upload stretches each pixel over
// its N×N texels (nearest); a write-back averages them (box filter, rounded) before the exact
// format conversion. At N = 1 both are plain copies.
//
// Invalidation / write-back contract:
//  - rows [0, rowsValid) of a target mirror VRAM or are newer; rows are uploaded from VRAM the
//    first time a draw needs them;
//  - `dirty` bounds the pixels drawn since the last write-back; writeBack() converts them
//    exactly (truncation to the format, u16 depth) into VRAM;
//  - a target claims the bytes of its valid rows; claiming bytes another target holds writes that
//    target back first and then drops or shortens it (so two targets never alias);
//  - memoryWritten() re-uploads only the written byte span, so pixels drawn elsewhere survive;
//  - syncRange() writes back every dirty target overlapping a byte range (texture reads,
//    transfers, host reads);
//  - unreported CPU writes (plugin API): flushAll() leaves every target clean and records a hash
//    of each of its rows as VRAM then holds it; markSuspect() (the host may have written guest
//    memory: a list was queued or continued) makes the next lookup compare clean targets' rows
//    with VRAM and re-upload the rows that changed, so the GE draws over what the CPU wrote
//    (PPSSPP does the same check before it reuses a frame buffer). Dirty targets are newer than
//    VRAM and are not checked.
#pragma once
#include <algorithm>
#include <memory>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "translator/gl_context.h"

namespace ge::gl {

constexpr int kTargetSize = 1024;

struct Rect {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive; empty when x1 < x0
    bool empty() const { return x1 < x0 || y1 < y0; }
    void add(const Rect& r) {
        if (r.empty()) return;
        if (empty()) {
            *this = r;
            return;
        }
        x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0), x1 = std::max(x1, r.x1), y1 = std::max(y1, r.y1);
    }
};

struct Target {
    bool depth = false;
    u32 addr = 0;    // normalised linear VRAM address (0x04000000 + offset)
    u32 stride = 0;  // pixels
    GeBufferFormat fmt = GE_FORMAT_8888;  // colour only
    GLuint tex = 0;
    int rowsValid = 0;
    int allocRows = 0;  // rows (PSP pixels) the texture has room for: 512 or 1024
    Rect dirty;
    Rect announced;              // rows of `dirty` takeNewlyDirty() reported since the last write-back
    std::vector<u64> rowHashes;  // VRAM hash per row when last clean (empty: none recorded)
    u32 bpp() const { return depth ? 2 : (fmt == GE_FORMAT_8888 ? 4 : 2); }
    u32 width() const { return std::min<u32>(stride, kTargetSize); }
    int texCols() const { return stride <= 512 ? 512 : kTargetSize; }  // texture width, PSP pixels
    u32 end() const { return addr + u32(rowsValid) * stride * bpp(); }
};

class FramebufferManager {
public:
    // `scale`: render scale N, 1–8 (texels per PSP pixel along each axis).
    FramebufferManager(const GlContext& ctx, Memory& mem, int scale = 1);
    ~FramebufferManager();

    // Targets for the current draw; rows [0, rows) valid. Null when the buffer is unusable
    // (stride 0). The returned pointers stay valid until the next call that creates targets.
    Target* colorTarget(u32 addr, u32 stride, GeBufferFormat fmt, int rows);
    Target* depthTarget(u32 addr, u32 stride, int rows);
    // Binds the draw FBO with these attachments (depth may be null).
    void bindDraw(Target* color, Target* depth);
    GLuint drawFbo() const { return drawFbo_; }

    // Writes the dirty pixels of t that lie in [lo, hi) (linear VRAM addresses) back to guest
    // memory; what is left of the dirty area stays dirty.
    void writeBack(Target& t, u32 lo = 0, u32 hi = ~0u);
    // Writes back dirty targets overlapping [addr, addr+size) (size 0: from addr to VRAM end).
    void syncRange(u32 addr, u32 size);
    // Guest memory changed under the targets: re-upload the overlapping spans.
    void memoryWritten(u32 addr, u32 size);
    void flushAll();
    // Drops every target without writing anything back (guest memory was replaced wholesale):
    // the next draws create targets from VRAM as a fresh manager would. Their textures are kept
    // for reuse by the next targets of the same size (kSpareTextures at most).
    void forgetAll();
    // Any dirty target overlapping [addr, addr+size) (size 0: to the end of VRAM)?
    bool dirtyOverlaps(u32 addr, u32 size) const;
    // The host may have written VRAM: check clean targets against their row hashes on next use.
    void markSuspect() { suspect_ = true; }
    // Byte ranges of targets drawn into since their last write-back that were not reported yet.
    void takeNewlyDirty(std::vector<std::pair<u32, u32>>& out);
    u64 cpuWriteReuploads() const { return cpuWriteReuploads_; }  // rows re-uploaded by the check
    // The renderer's GL state cache must be dropped (the host changed bindings).
    void forgetBindings() {
        boundColor_ = 0, boundDepth_ = ~0u;
        ++clobbers_;
    }
    u64 readbacks() const { return readbacks_; }
    u64 writeBacks() const { return writeBacks_; }  // write-backs that changed VRAM (generation bumps)
    const std::vector<std::unique_ptr<Target>>& targets() const { return targets_; }
    int scale() const { return scale_; }
    // The colour target whose valid rows hold the linear VRAM address, if one does.
    Target* containing(u32 linearAddr);
    // Copies w×h PSP pixels from (sx, sy) of src to (dx, dy) of dst on the GPU at render scale
    // (texel for texel) and marks them dirty in dst. Same format; src and dst not overlapping.
    void copyPixels(const Target& src, int sx, int sy, Target& dst, int dx, int dy, int w, int h);
    // The colour target at (addr, stride, fmt) with valid rows, if one exists (no creation).
    const Target* findColor(u32 addr, u32 stride, GeBufferFormat fmt);
    // Reads rows [0, h) × columns [0, w) of a colour target at render scale (w·N × h·N stored
    // pixels, row 0 first) into out; rows past rowsValid are left as they are in out.
    void readScaled(const Target& t, int w, int h, std::vector<u32>& out);
    // Increments whenever this class changed GL state the renderer caches (program, VAO, depth,
    // masks, scissor, framebuffer binding).
    u64 clobbers() const { return clobbers_; }

private:
    Target* find(bool depth, u32 addr, u32 stride, GeBufferFormat fmt);
    // markSuspect(): compares clean targets' rows with VRAM, re-uploads the changed ones.
    void verifySuspects();
    void hashRows(Target& t);
    Target* create(bool depth, u32 addr, u32 stride, GeBufferFormat fmt);
    void ensureRows(Target& t, int rows);
    // Frees [begin, end) for `owner`: other targets there are written back and shortened/dropped.
    void claim(u32 begin, u32 end, const Target* owner);
    void uploadRows(Target& t, int y0, int y1);
    void uploadSpan(Target& t, u32 begin, u32 end);
    void uploadRect(Target& t, int x0, int y0, int w, int h);
    void destroy(Target* t);
    // Gives t room for `rows` rows (PSP pixels), copying what it holds into a taller texture.
    void grow(Target& t, int rows);
    GLuint allocTexture(bool depth, int w, int h);
    bool buildDepthProgram();
    // Render scale > 1: the N×N box average of a target's texels into a 1× scratch texture.
    bool buildDownsamplePrograms();
    void downsample(const Target& t, const Rect& r);
    void uploadColor(Target& t, int x0, int y0, int w, int h);

    const GlContext& ctx_;
    Memory& mem_;
    const int scale_;
    std::vector<std::unique_ptr<Target>> targets_;
    // Textures of forgotten targets; allocTexture takes one of the same kind and size first.
    // Their texels are stale, as a new texture's are undefined (every row is uploaded before use).
    struct SpareTexture {
        bool depth;
        int w, h;
        GLuint tex;
    };
    static constexpr size_t kSpareTextures = 16;
    std::vector<SpareTexture> spare_;
    GLuint drawFbo_ = 0, readFbo_ = 0, utilFbo_ = 0;
    GLuint boundColor_ = 0, boundDepth_ = ~0u;
    // Depth upload: R16UI staging texture drawn into the depth target by a tiny program.
    GLuint depthProg_ = 0, depthStage_ = 0, emptyVao_ = 0;
    GLint depthScaleLoc_ = -1;
    // Scale > 1: 1× colour staging for uploads; downsampling programs and their 1× scratch targets.
    GLuint colorStage_ = 0;
    GLuint downColorProg_ = 0, downDepthProg_ = 0, downColor_ = 0, downDepth_ = 0;
    std::vector<u32> pixels_;
    std::vector<float> depthPixels_;
    std::vector<u16> depth16_;
    std::vector<float> depthF_;
    u64 readbacks_ = 0, writeBacks_ = 0, clobbers_ = 0, cpuWriteReuploads_ = 0;
    bool suspect_ = false;
};

}  // namespace ge::gl
