// SPDX-License-Identifier: MIT
// Small GL helpers the translator's utility passes share (write-back, upload, presenting).
#pragma once
#include "translator/gl_funcs.h"

namespace ge::gl {

// Compiles and links a vertex + fragment shader pair; 0 when either fails.
GLuint linkProgram(const GlFuncs& gl, const char* vs, const char* fs);
// Binds tex to GL_TEXTURE_2D with nearest filtering and a single level.
void nearestTexture(const GlFuncs& gl, GLuint tex);

}  // namespace ge::gl
