// SPDX-License-Identifier: MIT
// Presenting (plugin API ge2gl_frame_texture): the displayed frame as an RGBA8 GL texture at any
// size, made on the GPU.
//
// The source is the render target holding the frame (address, stride and format equal, enough
// rows) at render scale N, read in place: its texels are the stored pixels (16-bit formats
// bit-replicated, framebuffer_manager.h), so value/255 is the displayed colour. A frame no target
// holds (never drawn by the GE, written by the CPU, or in RAM, where sceDisplay may point) is
// converted from guest memory and staged at 1x. A fragment shader resamples either to the size
// asked for, bilinearly between texel centres: at the source's own size every output pixel lands
// on a texel centre, so the copy is exact.
#pragma once
#include <string>
#include <vector>

#include "hle/memory.h"
#include "translator/framebuffer_manager.h"
#include "translator/gl_context.h"

namespace ge::gl {

class Presenter {
public:
    Presenter(const GlContext& ctx, FramebufferManager& fb, Memory& mem) : ctx_(ctx), fb_(fb), mem_(mem) {}
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    // The w x h frame at addr as an outW x outH texture (row 0 = top line, alpha 1); 0 and err
    // on failure. Leaves GL bindings changed (the caller's state cache must be dropped).
    GLuint frame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, int outW, int outH, std::string& err);
    bool lastFromTarget() const { return lastFromTarget_; }

private:
    const GlContext& ctx_;
    FramebufferManager& fb_;
    Memory& mem_;
    GLuint prog_ = 0, vao_ = 0, fbo_ = 0, out_ = 0, stage_ = 0;
    GLint srcSizeLoc_ = -1, outSizeLoc_ = -1;
    int outW_ = 0, outH_ = 0, stageW_ = 0, stageH_ = 0;
    bool lastFromTarget_ = false;
    std::vector<u32> pixels_;
};

}  // namespace ge::gl
