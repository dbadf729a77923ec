// SPDX-License-Identifier: MIT
// PNG encoding for the tools' output images, with the deflate work split across threads.
#pragma once
#include <vector>

#include "hle/types.h"

namespace ge::tools {

// The PNG file (PNG 1.2 / ISO 15948) of a width x height image given as RGBA8888 pixels (R in
// bits 7..0), rows top first. Stored as 8-bit RGB when every alpha is 255, else RGBA; no row
// filters; one zlib stream at level 1 whose row ranges are deflated on up to `threads` threads.
// Empty when zlib fails (out of memory).
std::vector<u8> encodePng(const u32* rgba, int width, int height, int threads);

}  // namespace ge::tools
