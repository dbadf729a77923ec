// SPDX-License-Identifier: MIT
// The GL state contract with a host that lends its context (plugin API, GE2GL_BACKEND_GL_CURRENT;
// docs/plugin-api.md "GL state").
//
// A host's renderer caches its own bindings, so anything ge2gl changes and leaves changed breaks
// the host's next frame; anything the host set (blending, culling, a sampler object on a unit, a
// pixel-unpack buffer) silently changes what ge2gl's draws and uploads do. So, around every call
// that touches GL:
//  - HostGlState::save() records every binding and setting the translator changes (framebuffers,
//    program, VAO, buffers, texture and sampler bindings of the units it uses, active unit,
//    viewport, scissor, masks, depth, pixel store, the enables below), restore() puts them back;
//  - establishTranslatorState() sets every piece of state the translator's code assumes and
//    never sets per draw (no blending, culling, stencil, sRGB, logic op, rasterizer discard,
//    polygon offset, primitive restart or multisample coverage; fill mode; last-vertex
//    convention; depth range 0..1; depth clamp; no pixel buffers; plain pixel store; no samplers).
// The renderer forgets its own state cache at the same time (GlRenderer::hostEnter).
#pragma once
#include "translator/gl_funcs.h"

namespace ge::gl {

// Texture units the translator binds: 0..7 (shader_gen.h kUnit*, hw_vertex.h kUnitVertexBytes
// and kUnitRingIds).
constexpr int kHostUnits = 8;

struct HostGlState {
    GLint drawFbo = 0, readFbo = 0, program = 0, vao = 0, arrayBuffer = 0, textureBuffer = 0, packBuffer = 0,
          unpackBuffer = 0, activeTexture = 0;
    GLint tex2d[kHostUnits] = {}, texBuffer[kHostUnits] = {}, sampler[kHostUnits] = {};
    GLint viewport[4] = {}, scissor[4] = {};
    GLboolean colorMask[4] = {}, depthMask = 0;
    GLint depthFunc = 0, provoking = 0, polygonMode[2] = {};
    GLfloat depthRange[2] = {};
    // Pixel store, pack then unpack (order of kPixelStore in the .cpp).
    GLint pixelStore[16] = {};
    // glIsEnabled of kEnables in the .cpp.
    GLboolean enabled[16] = {};

    void save(const GlFuncs& gl);
    void restore(const GlFuncs& gl) const;
};

void establishTranslatorState(const GlFuncs& gl);

}  // namespace ge::gl
