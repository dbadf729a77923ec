// SPDX-License-Identifier: MIT
// Saving and restoring a host's GL state around ge2gl's work (gl_host_state.h).
#include "translator/gl_host_state.h"

#include <iterator>

namespace ge::gl {

namespace {

// Capabilities the translator turns on or off (saved and restored) or needs off (established).
constexpr GLenum kEnables[] = {GL_SCISSOR_TEST,        GL_DEPTH_TEST,         GL_BLEND,
                               GL_CULL_FACE,           GL_STENCIL_TEST,       GL_DEPTH_CLAMP,
                               GL_RASTERIZER_DISCARD,  GL_FRAMEBUFFER_SRGB,   GL_COLOR_LOGIC_OP,
                               GL_PRIMITIVE_RESTART,   GL_POLYGON_OFFSET_FILL, GL_SAMPLE_ALPHA_TO_COVERAGE,
                               GL_SAMPLE_COVERAGE,     GL_MULTISAMPLE,        GL_PROGRAM_POINT_SIZE};
static_assert(std::size(kEnables) <= std::size(HostGlState{}.enabled));

constexpr GLenum kPixelStore[] = {GL_PACK_ALIGNMENT,     GL_PACK_ROW_LENGTH,    GL_PACK_SKIP_ROWS,
                                  GL_PACK_SKIP_PIXELS,   GL_PACK_IMAGE_HEIGHT,  GL_PACK_SKIP_IMAGES,
                                  GL_PACK_SWAP_BYTES,    GL_PACK_LSB_FIRST,     GL_UNPACK_ALIGNMENT,
                                  GL_UNPACK_ROW_LENGTH,  GL_UNPACK_SKIP_ROWS,   GL_UNPACK_SKIP_PIXELS,
                                  GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_IMAGES, GL_UNPACK_SWAP_BYTES,
                                  GL_UNPACK_LSB_FIRST};
static_assert(std::size(kPixelStore) <= std::size(HostGlState{}.pixelStore));

// What the translator assumes: alignment 4 is set where it matters, the rest must be the defaults.
GLint pixelStoreDefault(GLenum e) { return e == GL_PACK_ALIGNMENT || e == GL_UNPACK_ALIGNMENT ? 4 : 0; }

}  // namespace

void HostGlState::save(const GlFuncs& gl) {
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFbo);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFbo);
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &program);
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
    gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &arrayBuffer);
    gl.GetIntegerv(GL_TEXTURE_BUFFER_BINDING, &textureBuffer);
    gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer);
    gl.GetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpackBuffer);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture);
    for (int u = 0; u < kHostUnits; ++u) {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + u));
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &tex2d[u]);
        gl.GetIntegerv(GL_TEXTURE_BINDING_BUFFER, &texBuffer[u]);
        gl.GetIntegerv(GL_SAMPLER_BINDING, &sampler[u]);
    }
    gl.ActiveTexture(GLenum(activeTexture));
    gl.GetIntegerv(GL_VIEWPORT, viewport);
    gl.GetIntegerv(GL_SCISSOR_BOX, scissor);
    gl.GetBooleanv(GL_COLOR_WRITEMASK, colorMask);
    gl.GetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
    gl.GetIntegerv(GL_DEPTH_FUNC, &depthFunc);
    gl.GetIntegerv(GL_PROVOKING_VERTEX, &provoking);
    // Core profiles report one value (front and back are the same); leave room for two.
    polygonMode[0] = polygonMode[1] = GL_FILL;
    gl.GetIntegerv(GL_POLYGON_MODE, polygonMode);
    gl.GetFloatv(GL_DEPTH_RANGE, depthRange);
    for (size_t i = 0; i < std::size(kPixelStore); ++i) gl.GetIntegerv(kPixelStore[i], &pixelStore[i]);
    for (size_t i = 0; i < std::size(kEnables); ++i) enabled[i] = gl.IsEnabled(kEnables[i]);
}

void HostGlState::restore(const GlFuncs& gl) const {
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(drawFbo));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readFbo));
    gl.UseProgram(GLuint(program));
    gl.BindVertexArray(GLuint(vao));
    gl.BindBuffer(GL_ARRAY_BUFFER, GLuint(arrayBuffer));
    gl.BindBuffer(GL_TEXTURE_BUFFER, GLuint(textureBuffer));
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(packBuffer));
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpackBuffer));
    for (int u = 0; u < kHostUnits; ++u) {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + u));
        gl.BindTexture(GL_TEXTURE_2D, GLuint(tex2d[u]));
        gl.BindTexture(GL_TEXTURE_BUFFER, GLuint(texBuffer[u]));
        gl.BindSampler(GLuint(u), GLuint(sampler[u]));
    }
    gl.ActiveTexture(GLenum(activeTexture));
    gl.Viewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    gl.Scissor(scissor[0], scissor[1], scissor[2], scissor[3]);
    gl.ColorMask(colorMask[0], colorMask[1], colorMask[2], colorMask[3]);
    gl.DepthMask(depthMask);
    gl.DepthFunc(GLenum(depthFunc));
    gl.ProvokingVertex(GLenum(provoking));
    gl.PolygonMode(GL_FRONT_AND_BACK, GLenum(polygonMode[0]));
    gl.DepthRange(depthRange[0], depthRange[1]);
    for (size_t i = 0; i < std::size(kPixelStore); ++i) gl.PixelStorei(kPixelStore[i], pixelStore[i]);
    for (size_t i = 0; i < std::size(kEnables); ++i) (enabled[i] ? gl.Enable : gl.Disable)(kEnables[i]);
}

void establishTranslatorState(const GlFuncs& gl) {
    for (GLenum e : kEnables)
        if (e != GL_SCISSOR_TEST && e != GL_DEPTH_TEST) gl.Disable(e);
    gl.Enable(GL_DEPTH_CLAMP);  // positions carry z = 0 or clip-space z; depth comes from the shader
    gl.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    gl.ProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    gl.DepthRange(0.0, 1.0);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    for (GLenum e : kPixelStore) gl.PixelStorei(e, pixelStoreDefault(e));
    for (int u = 0; u < kHostUnits; ++u) gl.BindSampler(GLuint(u), 0);
    gl.ActiveTexture(GL_TEXTURE0);
}

}  // namespace ge::gl
