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

namespace {

// A byte buffer (R8UI buffer texture `tex` over `buf`) bound on `unit`.
void makeByteBufferTexture(const GlFuncs& gl, int unit, GLuint& buf, GLuint& tex) {
    gl.GenBuffers(1, &buf);
    gl.BindBuffer(GL_TEXTURE_BUFFER, buf);
    gl.BufferData(GL_TEXTURE_BUFFER, 16, nullptr, GL_STREAM_DRAW);
    gl.GenTextures(1, &tex);
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
    gl.BindTexture(GL_TEXTURE_BUFFER, tex);
    gl.TexBuffer(GL_TEXTURE_BUFFER, GL_R8UI, buf);
    gl.ActiveTexture(GL_TEXTURE0);
}

}  // namespace

GpuVertexPath::GpuVertexPath(const GlContext& ctx, const geo::AccuracyProfile& acc) : ctx_(ctx), acc_(acc) {
    const GlFuncs& gl = ctx_.f();
    makeByteBufferTexture(gl, shadergen::kUnitVertexBytes, vtxBuf_, vtxTex_);
    makeByteBufferTexture(gl, shadergen::kUnitRingIds, ringBuf_, ringTex_);
    gl.GenBuffers(1, &idxBuf_);
}

GpuVertexPath::~GpuVertexPath() {
    const GlFuncs& gl = ctx_.f();
    gl.DeleteTextures(1, &vtxTex_);
    gl.DeleteTextures(1, &ringTex_);
    gl.DeleteBuffers(1, &vtxBuf_);
    gl.DeleteBuffers(1, &ringBuf_);
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
                            bool cull, bool dstTexture, GpuDraw& out) {
    // HwVsKey::primKind: the geometry shader does what needs the whole primitive (the discard
    // rules, near clipping in the reference's vertex order, which depends on the kind, culling).
    u8 primKind;
    switch (p.prim) {
        case GE_PRIM_TRIANGLES: primKind = 0; break;
        case GE_PRIM_TRIANGLE_STRIP: primKind = 1; break;
        case GE_PRIM_TRIANGLE_FAN: primKind = 2; break;
        default: return reject(CpuReason::PrimKind);
    }
    if (p.continuation) return reject(CpuReason::Continuation);
    // The reference draws rectangle-shaped quads at the start of an even strip (and a 4-vertex
    // fan) as rectangles when culling is off (geometry/assembly.h): that needs the transformed
    // positions, so such draws stay on the CPU.
    if (!cull && ((primKind == 1 && p.count >= 4 && p.count % 2 == 0) || (primKind == 2 && p.count == 4)))
        return reject(CpuReason::Quad);
    if (!passesCommonChecks(st, texture, dstTexture)) return false;

    VertexReader reader(mem, st, p.vtype);
    if (latchedAttributeUsed(st, reader, texture)) return reject(CpuReason::Latched);
    if (!reader.readIndices(p.indexAddr, p.count, rawIndices_)) return reject(CpuReason::Memory);
    out.key = shadergen::hwVsKeyFromState(st, texture, fog);
    out.key.primKind = primKind;
    out.key.sampleCentre = acc_.pspTriangleSampleCentre ? 1 : 0;
    const u32 stride = shadergen::hwVsStride(out.key);
    if (stride == 0) return reject(CpuReason::Memory);
    // The bytes of the vertices the draw uses: the index range when it is dense, else each used
    // vertex gathered. Vertex i of the buffer starts at i·stride; rawIndices_ (0..count-1 without
    // indices) become the draw's vertex numbers in that buffer.
    u32 lo = ~0u, hi = 0;
    for (u32 i : rawIndices_) lo = std::min(lo, i), hi = std::max(hi, i);
    const u64 span = u64(hi - lo) + 1;
    if (span <= u64(p.count) * 2 + 64) {
        const u64 first = u64(p.vertexAddr) + u64(lo) * stride, bytes = span * stride;
        if (first + bytes > 0x100000000ull) return reject(CpuReason::Memory);
        const u8* src = mem.ptr(u32(first), u32(bytes));
        if (!src) return reject(CpuReason::Memory);
        out.bytes.assign(src, src + bytes);
        for (u32& i : rawIndices_) i -= lo;
    } else {
        out.bytes.clear();
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
            rawIndices_[order[k].second] = next - 1;
        }
    }
    out.indices.clear();
    out.ringIds.clear();
    shadergen::hwTriangleList(out.key.primKind, rawIndices_.data(), u32(rawIndices_.size()), 0, out.indices,
                              out.ringIds);
    out.draws = 1;
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
                                 bool texture, bool fog, GpuDraw& out) {
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
    out.indices.assign(tess.indices.begin(), tess.indices.end() - std::ptrdiff_t(tess.indices.size() % 3));
    out.ringIds.clear();
    out.draws = 1;
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

bool GpuVertexPath::joinable(const GpuDraw& batch, const GpuDraw& next) {
    return batch.bytes.size() + next.bytes.size() <= 65536 && batch.ringIds.size() + next.ringIds.size() <= 65536 &&
           std::memcmp(&batch.key, &next.key, sizeof batch.key) == 0 &&
           std::memcmp(&batch.uniforms, &next.uniforms, sizeof batch.uniforms) == 0;
}

void GpuVertexPath::join(GpuDraw& batch, const GpuDraw& next) {
    const u32 base = u32(batch.bytes.size() / shadergen::hwVsStride(batch.key));
    batch.bytes.insert(batch.bytes.end(), next.bytes.begin(), next.bytes.end());
    const size_t at = batch.indices.size();
    batch.indices.insert(batch.indices.end(), next.indices.begin(), next.indices.end());
    for (size_t k = at; k < batch.indices.size(); ++k) batch.indices[k] += base;
    batch.ringIds.insert(batch.ringIds.end(), next.ringIds.begin(), next.ringIds.end());
    batch.draws += next.draws;
}

bool GpuVertexPath::draw(const GpuDraw& d, const Program& prog) {
    if (d.indices.empty()) return false;
    const GlFuncs& gl = ctx_.f();
    gl.BindBuffer(GL_TEXTURE_BUFFER, vtxBuf_);
    gl.BufferData(GL_TEXTURE_BUFFER, GLsizeiptr(std::max<size_t>(d.bytes.size(), 4)), nullptr, GL_STREAM_DRAW);
    gl.BufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(d.bytes.size()), d.bytes.data());
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + shadergen::kUnitVertexBytes));
    gl.BindTexture(GL_TEXTURE_BUFFER, vtxTex_);
    if (d.key.primKind != 0) {
        gl.BindBuffer(GL_TEXTURE_BUFFER, ringBuf_);
        gl.BufferData(GL_TEXTURE_BUFFER, GLsizeiptr(d.ringIds.size()), d.ringIds.data(), GL_STREAM_DRAW);
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + shadergen::kUnitRingIds));
        gl.BindTexture(GL_TEXTURE_BUFFER, ringTex_);
    }
    gl.ActiveTexture(GL_TEXTURE0);
    if (prog.hwBlock >= 0)
        gl.Uniform4uiv(prog.hwBlock, shadergen::kHwVsUniformVec4, reinterpret_cast<const GLuint*>(&d.uniforms));
    // Culling, near clipping and the discard rules happen in the geometry shader (hw_geometry.cpp):
    // no GL face culling (clipped pieces can be wound against their primitive, as on the CPU)
    // and no clip distances.
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, idxBuf_);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(d.indices.size() * sizeof(u32)), d.indices.data(),
                  GL_STREAM_DRAW);
    gl.DrawElements(GL_TRIANGLES, GLsizei(d.indices.size()), GL_UNSIGNED_INT, nullptr);
    return true;
}

}  // namespace ge::gl
