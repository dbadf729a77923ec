// SPDX-License-Identifier: MIT
// Presenting a frame on the GPU (present.h).
#include "translator/present.h"

#include "hle/pixel_format.h"
#include "translator/gl_util.h"

namespace ge::gl {

namespace {

const char* const kPresentVs =
    "#version 330 core\n"
    "void main() {\n"
    "  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
    "  gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";
// Output pixel centre → source texel space (source row 0 = output row 0 = the top line), then a
// bilinear mix of the four nearest texels, clamped at the edges. (x + 0.5) * src / out − 0.5 is
// exact in float when src == out, so an equal-size copy reads each texel alone.
const char* const kPresentFs =
    "#version 330 core\n"
    "uniform usampler2D u_src;\n"
    "uniform vec2 u_srcSize;\n"
    "uniform vec2 u_outSize;\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "  vec2 p = gl_FragCoord.xy * u_srcSize / u_outSize - 0.5;\n"
    "  vec2 b = floor(p);\n"
    "  vec2 f = p - b;\n"
    "  ivec2 hi = ivec2(u_srcSize) - 1;\n"
    "  ivec2 i0 = clamp(ivec2(b), ivec2(0), hi), i1 = clamp(ivec2(b) + 1, ivec2(0), hi);\n"
    "  vec4 c00 = vec4(texelFetch(u_src, i0, 0)), c10 = vec4(texelFetch(u_src, ivec2(i1.x, i0.y), 0));\n"
    "  vec4 c01 = vec4(texelFetch(u_src, ivec2(i0.x, i1.y), 0)), c11 = vec4(texelFetch(u_src, i1, 0));\n"
    "  vec4 c = mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);\n"
    "  o_color = vec4(c.rgb / 255.0, 1.0);\n"
    "}\n";

}  // namespace

Presenter::~Presenter() {
    const GlFuncs& gl = ctx_.f();
    if (prog_) gl.DeleteProgram(prog_);
    if (vao_) gl.DeleteVertexArrays(1, &vao_);
    if (fbo_) gl.DeleteFramebuffers(1, &fbo_);
    for (GLuint t : {out_, stage_})
        if (t) gl.DeleteTextures(1, &t);
}

GLuint Presenter::frame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, int outW, int outH, std::string& err) {
    const GlFuncs& gl = ctx_.f();
    if (!prog_) {
        prog_ = linkProgram(gl, kPresentVs, kPresentFs);
        if (!prog_) {
            err = "the presenting shader did not compile";
            return 0;
        }
        srcSizeLoc_ = gl.GetUniformLocation(prog_, "u_srcSize");
        outSizeLoc_ = gl.GetUniformLocation(prog_, "u_outSize");
        gl.UseProgram(prog_);
        gl.Uniform1i(gl.GetUniformLocation(prog_, "u_src"), 0);
        gl.GenVertexArrays(1, &vao_);
        gl.GenFramebuffers(1, &fbo_);
    }
    // The source: the target in place, or the frame staged from guest memory at 1x.
    GLuint src = 0;
    int scale = 1;
    const Target* t = Memory::isVram(addr) ? fb_.findColor(addr, stride, fmt) : nullptr;
    if (t && t->rowsValid >= h && int(t->width()) >= w) {
        src = t->tex;
        scale = fb_.scale();
        lastFromTarget_ = true;
    } else {
        lastFromTarget_ = false;
        const u32 bpp = bytesPerPixel(fmt);
        fb_.syncRange(addr, ((u32(h) - 1) * stride + u32(w)) * bpp);
        pixels_.assign(size_t(w) * size_t(h), 0xFF000000u);
        for (int y = 0; y < h; ++y) {
            const u32 row = addr + u32(y) * stride * bpp;
            const u32 avail = std::min<u32>(mem_.validSize(row, u32(w) * bpp) / bpp, u32(w));
            if (const u8* p = avail ? mem_.ptr(row, avail * bpp) : nullptr)
                convertToRGBA8888(p, fmt, avail, 1, stride, &pixels_[size_t(y) * size_t(w)]);
        }
        if (!stage_ || stageW_ != w || stageH_ != h) {
            if (!stage_) gl.GenTextures(1, &stage_);
            nearestTexture(gl, stage_);
            gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, w, h, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, nullptr);
            stageW_ = w, stageH_ = h;
        }
        gl.BindTexture(GL_TEXTURE_2D, stage_);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pixels_.data());
        src = stage_;
    }
    if (!out_ || outW_ != outW || outH_ != outH) {
        if (!out_) gl.GenTextures(1, &out_);
        gl.BindTexture(GL_TEXTURE_2D, out_);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, outW, outH, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        outW_ = outW, outH_ = outH;
    }
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, out_, 0);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
    gl.Disable(GL_SCISSOR_TEST);
    gl.Disable(GL_DEPTH_TEST);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.Viewport(0, 0, outW, outH);
    gl.UseProgram(prog_);
    gl.Uniform2f(srcSizeLoc_, float(w * scale), float(h * scale));
    gl.Uniform2f(outSizeLoc_, float(outW), float(outH));
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, src);
    gl.BindVertexArray(vao_);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    return out_;
}

}  // namespace ge::gl
