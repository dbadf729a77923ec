// SPDX-License-Identifier: MIT
// A GL dispatch table whose calls do nothing ("null GL"): `ge2gl bench --null-gl` replays with it
// so that the translator's own CPU cost per draw (vertex work, setup, batching, state tracking,
// uniform and buffer calls) is measured apart from the driver's.
#pragma once
#include "translator/gl_funcs.h"

namespace ge::gl {

// Fills every entry of f. Object names come from one counter, so caches that compare names still
// see distinct objects; statuses report success (compile, link, framebuffer complete); queries
// return zeros; reads leave the caller's buffers as they are.
void loadNullGl(GlFuncs& f);

}  // namespace ge::gl
