// SPDX-License-Identifier: MIT
// The GL renderer's block transfers and render-to-texture (gl_renderer_impl.h): through VRAM,
// or in hardware mode between render targets on the GPU at render scale.
#include "geometry/texture_size.h"
#include "hle/texture_decoder.h"
#include "translator/gl_renderer_impl.h"

namespace ge::gl {

void GlRendererImpl::blockTransfer(const TransferPacket& t, Memory& mem) {
    flush();
    if (hw_ && transferOnGpu(t)) {
        ++stats_.transfersGpu;
        ++generation_;
        return;
    }
    // The source must hold what was drawn; the destination's dirty pixels go to VRAM first so
    // the re-upload after the copy keeps pixels outside the copied rectangle.
    fb_.syncRange(t.srcBegin(), t.srcBytes());
    fb_.syncRange(t.dstBegin(), t.dstBytes());
    performTransfer(mem, t);
    fb_.memoryWritten(t.dstBegin(), t.dstBytes());
    ++generation_;
}

// Hardware mode: a block transfer whose source and destination rectangles both lie inside
// colour render targets of the same format (whole rows of the rectangle within the target's
// width and valid rows) is a GPU copy at render scale; the destination target holds the result
// (dirty) until a write-back, so scaled detail survives. Anything else goes through VRAM.
bool GlRendererImpl::transferOnGpu(const TransferPacket& t) {
    struct Side {
        Target* target;
        int x, y;
    };
    auto locate = [&](u32 base, u32 stride, u32 x, u32 y, Side& out) {
        const u32 begin = Memory::drawingAddress(base + (y * stride + x) * t.bpp);
        Target* tg = fb_.containing(begin);
        if (!tg || tg->stride != stride || tg->bpp() != t.bpp) return false;
        const u32 px = (begin - tg->addr) / t.bpp;
        if ((begin - tg->addr) % t.bpp) return false;
        out = Side{tg, int(px % stride), int(px / stride)};
        return u32(out.x) + t.width <= tg->width() && out.y + int(t.height) <= tg->rowsValid;
    };
    Side src{}, dst{};
    if (!locate(t.src, t.srcStride, t.srcX, t.srcY, src) || !locate(t.dst, t.dstStride, t.dstX, t.dstY, dst))
        return false;
    if (src.target->fmt != dst.target->fmt) return false;  // bytes reinterpreted: through VRAM
    if (src.target == dst.target) {
        const bool overlap = src.x < dst.x + int(t.width) && dst.x < src.x + int(t.width) &&
                             src.y < dst.y + int(t.height) && dst.y < src.y + int(t.height);
        if (overlap) return false;  // the GE's row order matters; a blit's is undefined
    }
    fb_.copyPixels(*src.target, src.x, src.y, *dst.target, dst.x, dst.y, int(t.width), int(t.height));
    state_.invalidate();
    return true;
}

// Hardware mode: when the texture's level 0 lies in a colour render target whose pixels a
// texture of its format reads directly (8888 as 8888, a 16-bit buffer as any 16-bit format),
// the draw samples the target in place at render scale (FsKey::texTarget). CLUT16 over a 16-bit
// buffer and CLUT32 over an 8888 one (one index per pixel: how games read a buffer's channel
// through a palette) look the pixel up in a palette texture. Not for mipmaps, CLUT4/8 (several
// indices per pixel), swizzled textures or the draw's own colour target (a feedback loop):
// those go through VRAM.
bool GlRendererImpl::sampleTarget(const GeState& st, DrawSetup& s) {
    const Target* t = fb_.containing(Memory::drawingAddress(st.textureAddr(0)));
    if (!t) return false;
    const u32 tf = st.TPF_format();
    const bool fb32 = t->fmt == GE_FORMAT_8888;
    // Texels per pixel: CLUT4/CLUT8 read a buffer's nibbles/bytes (the texture's buffer width
    // then counts them), CLUT16 over 16-bit and CLUT32 over 8888 one index per pixel.
    u32 perPixel = 0;
    if (tf == GE_TFMT_CLUT4) perPixel = fb32 ? 8 : 4;
    else if (tf == GE_TFMT_CLUT8) perPixel = fb32 ? 4 : 2;
    else if (fb32 ? (tf == GE_TFMT_CLUT32 || tf == GE_TFMT_8888) : (tf <= GE_TFMT_4444 || tf == GE_TFMT_CLUT16))
        perPixel = 1;
    const bool clut = tf >= GE_TFMT_CLUT4 && tf <= GE_TFMT_CLUT32;
    const u32 off = Memory::drawingAddress(st.textureAddr(0)) - t->addr;
    if (!perPixel || s.fs.texMip || st.TMODE_swizzle() || st.textureBufWidth(0) != t->stride * perPixel ||
        off % t->bpp() ||
        (t->addr == s.colorAddr && t->stride == s.colorStride)) {
        ++stats_.rttVram;
        return false;
    }
    // Pending draws into the source target first (the batch may be drawing into it).
    const u32 lin = Memory::drawingAddress(st.textureAddr(0));
    if (pending() && batchOverlaps(lin, lin + 1)) flush();
    const u32 px = off / t->bpp();
    s.fs.texTarget = u8(1 + t->fmt);
    s.fs.texFormat = u8(tf);
    shadergen::canonicalize(s.fs);
    s.texture = t->tex;
    s.u.texLevels[0][0] = int(px / t->stride) * scale_;
    s.u.texLevels[0][1] = int(geo::texCoordWidth(st, 0));  // unclamped 2^n (geometry/texture_size.h)
    s.u.texLevels[0][2] = int(geo::texCoordHeight(st, 0));
    s.u.texLevels[0][3] = int(px % t->stride) * scale_;
    s.u.texMaxLevel = 0;
    s.u.texScale = scale_;
    if (clut) {
        s.u.clutShift = s32(st.CLUT_shift());
        s.u.clutMask = s32(st.CLUT_mask());
        s.clutTexture = paletteTexture(st);
    }
    state_.textureUnitUsed();
    ++stats_.rttGpu;
    return true;
}

// A 256×1 RGBA8UI texture of the palette per masked index (hle maskedPalette), one per
// distinct palette; the set is dropped (after drawing what uses it) past 64.
GLuint GlRendererImpl::paletteTexture(const GeState& st) {
    u32 pal[256];
    maskedPalette(st, 0, pal);
    const u64 h = shadergen::hashBytes(pal, sizeof pal);
    if (auto it = palettes_.find(h); it != palettes_.end()) return it->second;
    if (palettes_.size() >= 64) {
        flush();
        for (auto& kv : palettes_) gl_.DeleteTextures(1, &kv.second);
        palettes_.clear();
        state_.clutTexturesDeleted();
    }
    GLuint tex = 0;
    gl_.GenTextures(1, &tex);
    gl_.BindTexture(GL_TEXTURE_2D, tex);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl_.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, 256, 1, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pal);
    palettes_.emplace(h, tex);
    state_.textureUnitUsed();  // unit 0 was used for the upload
    return tex;
}

}  // namespace ge::gl
