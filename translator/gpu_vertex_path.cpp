// SPDX-License-Identifier: MIT
// GL hardware mode's GPU vertex path (see gpu_vertex_path.h).
#include "translator/gpu_vertex_path.h"

#include <algorithm>
#include <cstring>

#include "geometry/reference_rules.h"
#include "hle/vertex_decoder.h"

namespace ge::gl {

const char* cpuReasonName(CpuReason r) {
    switch (r) {
        case CpuReason::PrimKind: return "rect/line/point";
        case CpuReason::Quad: return "even strip / 4-fan";
        case CpuReason::Continuation: return "continuation";
        case CpuReason::AlphaRule: return "alpha rule";
        case CpuReason::DstTexture: return "dst texture";
        case CpuReason::Memory: return "memory";
        case CpuReason::Latched: return "latched uv/normal";
        default: return "?";
    }
}

GpuVertexPath::GpuVertexPath(const GlContext& ctx, const geo::AccuracyProfile& acc) : ctx_(ctx), acc_(acc) {
    const GlFuncs& gl = ctx_.f();
    gl.GenBuffers(1, &vtxBuf_);
    gl.BindBuffer(GL_TEXTURE_BUFFER, vtxBuf_);
    gl.BufferData(GL_TEXTURE_BUFFER, 16, nullptr, GL_STREAM_DRAW);
    gl.GenTextures(1, &vtxTex_);
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + shadergen::kUnitVertexBytes));
    gl.BindTexture(GL_TEXTURE_BUFFER, vtxTex_);
    gl.TexBuffer(GL_TEXTURE_BUFFER, GL_R8UI, vtxBuf_);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.GenBuffers(1, &idxBuf_);
}

GpuVertexPath::~GpuVertexPath() {
    const GlFuncs& gl = ctx_.f();
    gl.DeleteTextures(1, &vtxTex_);
    gl.DeleteBuffers(1, &vtxBuf_);
    gl.DeleteBuffers(1, &idxBuf_);
}

namespace {

// A format without UV or normal takes the vertex unit's latched ones (GeState::latchUV,
// latchNormal), which the vertex shader does not have: such draws stay on the CPU when they read
// the missing attribute. UV: texture mapping from UVs (modes 0 and 3, or the texture matrix from
// UVs). Normal:
// lighting or shade mapping with a latched normal (a zero one normalises to (0, 0, 1), as the
// shader's default), and the texture matrix from the normal (where zero and (0, 0, 1) differ).
bool latchedAttributeUsed(const GeState& st, const VertexReader& reader, bool texture) {
    const u32 texMap = st.TMAP_mode();
    const bool fromNormal = texMap == 1 && st.TMAP_proj() >= 2;
    if (!reader.hasUV() && texture && (texMap == 0 || texMap == 3 || (texMap == 1 && st.TMAP_proj() == 1))) return true;
    if (reader.hasNormal()) return false;
    const bool zero = st.latchNormal[0] == 0.0f && st.latchNormal[1] == 0.0f && st.latchNormal[2] == 0.0f;
    return fromNormal || (!zero && (st.LTE_on() || texMap == 2));
}

}  // namespace

bool GpuVertexPath::prepare(const Memory& mem, const GeState& st, const PrimPacket& p, bool texture, bool fog,
                            bool cull, bool cullCcw, bool dstTexture, GpuDraw& out) {
    GLenum mode;
    switch (p.prim) {
        case GE_PRIM_TRIANGLES: mode = GL_TRIANGLES; break;
        case GE_PRIM_TRIANGLE_STRIP: mode = GL_TRIANGLE_STRIP; break;
        case GE_PRIM_TRIANGLE_FAN: mode = GL_TRIANGLE_FAN; break;
        default: return reject(CpuReason::PrimKind);
    }
    if (p.continuation) return reject(CpuReason::Continuation);
    // The reference draws rectangle-shaped quads at the start of an even strip (and a 4-vertex
    // fan) as rectangles when culling is off (geometry/assembly.h): that needs the transformed
    // positions, so such draws stay on the CPU.
    if (!cull && ((mode == GL_TRIANGLE_STRIP && p.count >= 4 && p.count % 2 == 0) ||
                  (mode == GL_TRIANGLE_FAN && p.count == 4)))
        return reject(CpuReason::Quad);
    if (!passesCommonChecks(st, texture, dstTexture)) return false;

    VertexReader reader(mem, st, p.vtype);
    if (latchedAttributeUsed(st, reader, texture)) return reject(CpuReason::Latched);
    if (!reader.readIndices(p.indexAddr, p.count, rawIndices_)) return reject(CpuReason::Memory);
    out.key = shadergen::hwVsKeyFromState(st, texture, fog);
    // The geometry shader does what needs the whole primitive: the discard rules, near clipping
    // in the reference's vertex order (which needs the primitive kind), culling.
    out.key.primKind = mode == GL_TRIANGLE_STRIP ? 1 : (mode == GL_TRIANGLE_FAN ? 2 : 0);
    out.key.sampleCentre = acc_.pspTriangleSampleCentre ? 1 : 0;
    const u32 stride = shadergen::hwVsStride(out.key);
    if (stride == 0) return reject(CpuReason::Memory);
    out.mode = mode;
    out.count = p.count;
    out.cull = cull;
    out.cullCcw = cullCcw;
    out.indexed = reader.indexSize() != 0;
    out.indices.clear();
    // The bytes of the vertices the draw uses: the index range when it is dense, else each used
    // vertex gathered (indices remapped). Vertex i of the buffer starts at i·stride.
    u32 lo = ~0u, hi = 0;
    for (u32 i : rawIndices_) lo = std::min(lo, i), hi = std::max(hi, i);
    const u64 span = u64(hi - lo) + 1;
    if (span <= u64(p.count) * 2 + 64) {
        const u64 first = u64(p.vertexAddr) + u64(lo) * stride, bytes = span * stride;
        if (first + bytes > 0x100000000ull) return reject(CpuReason::Memory);
        const u8* src = mem.ptr(u32(first), u32(bytes));
        if (!src) return reject(CpuReason::Memory);
        out.bytes.assign(src, src + bytes);
        if (out.indexed) {
            out.indices.resize(rawIndices_.size());
            for (size_t k = 0; k < rawIndices_.size(); ++k) out.indices[k] = rawIndices_[k] - lo;
        }
    } else {
        out.bytes.clear();
        out.indices.resize(rawIndices_.size());
        std::vector<std::pair<u32, u32>> order;  // (guest index, position in the draw)
        order.reserve(rawIndices_.size());
        for (u32 k = 0; k < rawIndices_.size(); ++k) order.emplace_back(rawIndices_[k], k);
        std::sort(order.begin(), order.end());
        u32 next = 0;
        for (size_t k = 0; k < order.size(); ++k) {
            if (k == 0 || order[k].first != order[k - 1].first) {
                const u64 a = u64(p.vertexAddr) + u64(order[k].first) * stride;
                const u8* src = a + stride <= 0x100000000ull ? mem.ptr(u32(a), stride) : nullptr;
                if (!src) return reject(CpuReason::Memory);
                out.bytes.insert(out.bytes.end(), src, src + stride);
                ++next;
            }
            out.indices[order[k].second] = next - 1;
        }
        out.indexed = true;
    }
    shadergen::hwVsUniformsFromState(st, st.op(GE_CMD_VTYPE), out.uniforms, acc_, &fold_);
    ++stats_.gpu;
    return true;
}

bool GpuVertexPath::passesCommonChecks(const GeState& st, bool texture, bool dstTexture) {
    // Whether the alpha test runs can hang on the colours that reach the fragments; when it
    // cannot (the rule is off even with every alpha 255), the vertex shader's colours suffice.
    if (acc_.clutSkipsAlphaTest && geo::referenceSkipsAlphaTest(st, texture, true)) return reject(CpuReason::AlphaRule);
    if (dstTexture) return reject(CpuReason::DstTexture);
    if (!ctx_.f().Uniform4uiv || !ctx_.f().DrawElements) return reject(CpuReason::PrimKind);
    return true;
}

bool GpuVertexPath::acceptPatch(const GeState& st, const PatchPacket& p, bool texture, bool dstTexture) {
    if (p.patchPrim != 0 || ((p.vtype >> 23) & 1)) return reject(CpuReason::PrimKind);
    return passesCommonChecks(st, texture, dstTexture);
}

bool GpuVertexPath::preparePatch(const GeState& st, const geo::TessOutput& tess, bool hasColor, bool hasNormal,
                                 bool texture, bool fog, bool cull, bool cullCcw, GpuDraw& out) {
    const size_t n = tess.verts.size();
    for (u32 i : tess.indices)
        if (i >= n) return reject(CpuReason::Memory);
    // VTYPE of the generated vertices (ge-rules.md §5.1): float UV (3), colour 8888 (7) or none,
    // float normal (3) or none, float position (3); no weights (skinning was applied to the
    // control points), no morphing.
    const u32 vtype = 3u | (hasColor ? 7u : 0u) << 2 | (hasNormal ? 3u : 0u) << 5 | 3u << 7;
    out.key = shadergen::hwVsKeyFromState(st, vtype, texture, fog);
    out.key.primKind = 0;
    out.key.sampleCentre = acc_.pspTriangleSampleCentre ? 1 : 0;
    const VertexLayout l = VertexLayout::fromVtype(vtype);
    out.mode = GL_TRIANGLES;
    out.count = u32(tess.indices.size());
    out.cull = cull;
    out.cullCcw = cullCcw;
    out.indexed = true;
    out.indices.assign(tess.indices.begin(), tess.indices.end());
    // The guest's own float vertices are little-endian, as the hosts ge2gl runs on: the shader
    // reads these bytes as it reads the guest's.
    out.bytes.assign(n * l.size, 0);
    u8* b = out.bytes.data();
    for (const DecodedVertex& v : tess.verts) {
        std::memcpy(b + l.tcOff, v.uv, 8);
        if (hasColor) std::memcpy(b + l.colOff, v.color, 4);
        if (hasNormal) std::memcpy(b + l.nrmOff, v.nrm, 12);
        std::memcpy(b + l.posOff, v.pos, 12);
        b += l.size;
    }
    shadergen::hwVsUniformsFromState(st, vtype, out.uniforms, acc_, &fold_);
    ++stats_.gpu;
    return true;
}

void GpuVertexPath::draw(const GpuDraw& d, const Program& prog) {
    const GlFuncs& gl = ctx_.f();
    gl.BindBuffer(GL_TEXTURE_BUFFER, vtxBuf_);
    gl.BufferData(GL_TEXTURE_BUFFER, GLsizeiptr(std::max<size_t>(d.bytes.size(), 4)), nullptr, GL_STREAM_DRAW);
    gl.BufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(d.bytes.size()), d.bytes.data());
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + shadergen::kUnitVertexBytes));
    gl.BindTexture(GL_TEXTURE_BUFFER, vtxTex_);
    gl.ActiveTexture(GL_TEXTURE0);
    if (prog.hwBlock >= 0)
        gl.Uniform4uiv(prog.hwBlock, shadergen::kHwVsUniformVec4, reinterpret_cast<const GLuint*>(&d.uniforms));
    // Culling, near clipping and the discard rules happen in the geometry shader (hw_geometry.cpp):
    // no GL face culling (clipped pieces can be wound against their primitive, as on the CPU)
    // and no clip distances.
    if (d.indexed) {
        gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, idxBuf_);
        gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(d.indices.size() * sizeof(u32)), d.indices.data(),
                      GL_STREAM_DRAW);
        gl.DrawElements(d.mode, GLsizei(d.count), GL_UNSIGNED_INT, nullptr);
    } else {
        gl.DrawArrays(d.mode, 0, GLsizei(d.count));
    }
}

}  // namespace ge::gl
