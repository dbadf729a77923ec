// SPDX-License-Identifier: MIT
// GL hardware mode: PRIM draws whose vertex work runs in the generated vertex shader
// (shadergen/hw_vertex.h) — the guest's vertex bytes go to the GPU as they are, with the GE's
// indices rebased to them; transform, skinning, morphing, lighting, texture mapping, fog, the
// viewport, the 1/16-pixel snap, near clipping and the discard rules happen there.
//
// Bezier/spline patches drawn as triangles take the path too: tessellated on the CPU (the
// geometry the CPU path draws), transformed and lit in the vertex shader.
//
// What stays on the CPU (VertexPipeline, shared geometry/ code), each counted by reason in
// --stats because whole-primitive knowledge or the CPU's own assembly is needed:
//  - rectangles, lines and points: expanded or rasterised by the GE's own rules on the CPU;
//  - strips of an even number of vertices and fans of four, without culling: the reference
//    renderer draws those of their quads that form an axis-aligned rectangle as rectangles
//    (geometry/assembly.h), which needs the transformed positions;
//  - PRIM type 7 continuations: the open vertices of the previous PRIM live in VertexPipeline
//    (a GPU-drawn PRIM leaves them there too: VertexPipeline::keepOpenVertices);
//  - draws where the reference's skipped alpha test (geometry/reference_rules.h) depends on the
//    vertex colours that reach the fragments;
//  - destination reads through a texture (no framebuffer fetch): primitives of one draw that
//    overlap must be ordered by barriers, which needs their bounds;
//  - vertex or index bytes the guest memory cannot supply whole (the CPU path draws the readable
//    part and reports the error);
//  - draws that read a UV or normal their format lacks: the vertex unit's latched value
//    (GeState::latchUV / latchNormal) is the CPU decoder's.
#pragma once
#include <string>
#include <vector>

#include "geometry/accuracy_profile.h"
#include "geometry/spline.h"
#include "geometry/transform.h"
#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/renderer.h"
#include "shadergen/hw_vertex.h"
#include "translator/gl_context.h"
#include "translator/shader_cache.h"

namespace ge::gl {

// One draw, prepared on the CPU before any GL call, or several joined (GpuVertexPath::join):
// a GL_TRIANGLES list in the geometry shader's form (shadergen::hwTriangleList).
struct GpuDraw {
    shadergen::HwVsKey key;
    shadergen::HwVsUniforms uniforms;
    std::vector<u8> bytes;     // vertex bytes, vertex i at i * stride
    std::vector<u32> indices;  // 3 per triangle, into `bytes`
    std::vector<u8> ringIds;   // strips and fans: per triangle, its number in its PRIM mod 6
    u32 draws = 0;             // GE draws joined in it
};

// Why a draw stays on the CPU (indices into GpuVertexStats::cpu).
enum class CpuReason : u8 { PrimKind, Quad, Continuation, AlphaRule, DstTexture, Memory, Latched, Count };
const char* cpuReasonName(CpuReason r);

struct GpuVertexStats {
    u64 gpu = 0;
    u64 cpu[size_t(CpuReason::Count)] = {};
};

class GpuVertexPath {
public:
    // `acc`: whether the reference's skipped alpha test can apply (it keeps such draws on the CPU).
    GpuVertexPath(const GlContext& ctx, const geo::AccuracyProfile& acc);
    ~GpuVertexPath();
    GpuVertexPath(const GpuVertexPath&) = delete;
    GpuVertexPath& operator=(const GpuVertexPath&) = delete;

    // Prepares `out` for the GPU path; false (reason counted) when the draw stays on the CPU.
    // `dstTexture`: the fragment shader reads the destination through a texture.
    // `cull`: culling on (the draw's culling itself is in the uniforms).
    bool prepare(const Memory& mem, const GeState& st, const PrimPacket& p, bool texture, bool fog, bool cull,
                 bool dstTexture, GpuDraw& out);
    // Bezier/spline patches, as PPSSPP's GL backend draws them with its CPU tessellation: the
    // vertices geo::tessellatePatch generates (model space) go through the vertex shader as float
    // vertices — position, UV (read or generated), the normal when the control points have one
    // or lighting made one, the colour (8888) when the control points have one.
    // acceptPatch: whether the patch can take this path (false, reason counted: drawn as lines or
    // points, through mode, the alpha rule, destination reads through a texture — as for PRIMs);
    // asked before tessellating. preparePatch then fills `out` from the tessellation;
    // `hasColor`/`hasNormal` as the CPU path reads the patch (geo::DrawFrontEnd::patch).
    bool acceptPatch(const GeState& st, const PatchPacket& p, bool texture, bool dstTexture);
    bool preparePatch(const GeState& st, const geo::TessOutput& tess, bool hasColor, bool hasNormal, bool texture,
                      bool fog, GpuDraw& out);
    // Whether `next` can be drawn in the same GL draw as `batch` (the caller has checked that
    // their fragment state and targets are equal): the same key and uniforms, and the joined
    // vertex bytes and ring ids each within the 65536 texels GL guarantees a buffer texture
    // (shadergen/hw_vertex.h). Then `join` appends it
    // (its indices rebased past batch's vertices). GL draws a draw call's primitives in order, so
    // the joined draw writes what the separate ones did (as PPSSPP's DrawEngine joins draws).
    static bool joinable(const GpuDraw& batch, const GpuDraw& next);
    static void join(GpuDraw& batch, const GpuDraw& next);
    // Uploads the vertex bytes, indices, ring ids and uniforms and draws with `prog` (already
    // bound, with the fragment state applied); false when there is no triangle to draw. Leaves
    // GL_CLIP_DISTANCE0 and face culling as it found them (off). The geometry shader culls and
    // clips (hw_geometry.cpp).
    bool draw(const GpuDraw& d, const Program& prog);
    const GpuVertexStats& stats() const { return stats_; }

private:
    // What both kinds of draw reject before their vertices are looked at.
    bool passesCommonChecks(const GeState& st, bool texture, bool dstTexture);
    bool reject(CpuReason r) {
        ++stats_.cpu[size_t(r)];
        return false;
    }

    const GlContext& ctx_;
    geo::AccuracyProfile acc_;
    GLuint vtxBuf_ = 0, vtxTex_ = 0, idxBuf_ = 0, ringBuf_ = 0, ringTex_ = 0;
    std::vector<u32> seq_;  // 0..count-1 for a draw without indices
    GpuVertexStats stats_;
    std::vector<u32> rawIndices_;
    geo::MatrixFold fold_;  // world·view·proj while the matrices stay the same
};

}  // namespace ge::gl
