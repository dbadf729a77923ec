// SPDX-License-Identifier: MIT
// What a backend may offer besides drawing (hle/renderer.h): optional interfaces a host asks for
// through the Backend the factory returns (backend/factory.h), in the manner of Dolphin's video
// backends, so that callers never need to know which backend class they hold. The software
// model offers none of them; the GL translator all (translator/gl_renderer.h).
//
// Each interface is a view of the object the Backend's Renderer owns: it is never deleted through
// (protected destructor) and lives exactly as long as that Renderer.
#pragma once
#include <string>
#include <vector>

#include "hle/ge_state.h"  // GeBufferFormat
#include "hle/types.h"

namespace ge::backend {

// Frames handed to the host's graphics API (plugin API ge2gl_frame_texture).
class FramePresenter {
public:
    // Name of a texture (RGBA8, row 0 = top line, outW x outH) holding the w x h frame at addr
    // (VRAM or RAM), for the host to draw with. Valid until the next call; 0 and err on error.
    virtual unsigned presentFrame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, int outW, int outH,
                                  std::string& err) = 0;

protected:
    ~FramePresenter() = default;
};

// Drawing at a render scale N above the PSP's pixels (the GL hardware mode).
class ScaledRendering {
public:
    virtual int renderScale() const = 0;
    // The frame at vramAddr (stride pixels, format fmt) at render scale N: (w·N)×(h·N) RGBA8888
    // with alpha 255 (R in bits 0–7), row 0 = top line, read from what the backend drew at that
    // scale where it holds it and from VRAM (each pixel repeated N×N) elsewhere. Returns N.
    virtual int readScaledFrame(u32 vramAddr, u32 stride, GeBufferFormat fmt, int w, int h, std::vector<u32>& rgba) = 0;

protected:
    ~ScaledRendering() = default;
};

// A backend that works in a graphics context it shares with the host's thread (a headless
// context it makes current, or the host's own one): calls that reach it are bracketed by
// hostEnter/hostLeave. Nested pairs count. The backend is created entered: the first
// hostLeave() hands the thread (or the host's state) back.
class HostContextUser {
public:
    virtual bool hostEnter(std::string& err) = 0;
    virtual void hostLeave() = 0;

protected:
    ~HostContextUser() = default;
};

// The backend's own counters, one line per counter (`ge2gl render --stats`, bench).
class StatsSource {
public:
    virtual std::string statsText() const = 0;

protected:
    ~StatsSource() = default;
};

}  // namespace ge::backend
