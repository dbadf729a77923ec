// SPDX-License-Identifier: MIT
// Shared helpers for the GL translator tests: a headless renderer (skipped cleanly when no GL
// context can be created), a 64×64 scene built with ListBuilder, run through GeEngine, and exact
// VRAM reads after flushToMemory().
#pragma once
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "authoring/list_builder.h"
#include "hle/ge_engine.h"
#include "hle/memory.h"
#include "translator/gl_renderer.h"

namespace ge::gltest {

constexpr u32 kFbOffset = 0x000000;   // frame buffer at VRAM start
constexpr u32 kZOffset = 0x100000;    // depth buffer
constexpr u32 kStride = 64;           // pixels
constexpr int kSize = 64;

// Runs `build` (FINISH appended) through a GeEngine with renderer `r` on `mem` and returns the
// whole of VRAM after flushToMemory() (the differential GL ↔ software-model tests).
inline std::vector<u8> runListVram(Memory& mem, Renderer& r, const std::function<void(ListBuilder&)>& build) {
    GeEngine eng(mem, &r);
    ListBuilder b(&mem);
    build(b);
    b.finish();
    eng.startList(b.placeList(), 0);
    eng.run();
    r.flushToMemory();
    return std::vector<u8>(mem.vram(), mem.vram() + Memory::kVramSize);
}

// Destination-read path under test.
enum class GlPath { FbFetch, Barrier, Baseline };

class GlScene : public ::testing::TestWithParam<GlPath> {
public:
    void SetUp() override {
        mem = std::make_unique<Memory>();
        gl::GlOptions opt;
        opt.baseline = GetParam() == GlPath::Baseline;
        opt.disableFramebufferFetch = GetParam() == GlPath::Barrier;
        std::string err;
        renderer = gl::createGlRenderer(*mem, opt, err);
        if (!renderer) GTEST_SKIP() << "no GL context: " << err;
        engine = std::make_unique<GeEngine>(*mem, renderer.get());
        b = std::make_unique<ListBuilder>(mem.get());
    }

    // Frame buffer, scissor/region 64×64, no depth; SDK-like defaults.
    void setupFrame(u32 fmt = GE_FORMAT_8888) {
        b->drawBuffer(fmt, kFbOffset, kStride);
        b->depthBuffer(kZOffset, kStride);
        b->scissor(0, 0, kSize, kSize);
        b->region(0, 0, kSize, kSize);
        b->offset(2048 - kSize / 2, 2048 - kSize / 2);
        b->viewport(2048, 2048, float(kSize), float(kSize));
        b->depthRange(65535, 0);
    }

    // Executes the list and writes everything back to VRAM.
    void run() {
        b->finish();
        const u32 list = b->placeList();
        ASSERT_NE(list, 0u);
        engine->startList(list, 0);
        engine->run();
        renderer->flushToMemory();
        b = std::make_unique<ListBuilder>(mem.get(), b->arenaNext());
    }

    u32 px32(int x, int y, u32 offset = kFbOffset, u32 stride = kStride) const {
        return mem->read32(0x04000000 + offset + u32(y * int(stride) + x) * 4);
    }
    u16 px16(int x, int y, u32 offset = kFbOffset, u32 stride = kStride) const {
        return mem->read16(0x04000000 + offset + u32(y * int(stride) + x) * 2);
    }
    u16 depth(int x, int y) const { return mem->read16(0x04000000 + kZOffset + u32(y * int(kStride) + x) * 2); }

    // Through-mode rectangle (x1,y1)-(x2,y2), colour ABGR, optional texel UVs.
    void rect(float x1, float y1, float x2, float y2, u32 color, float u1 = 0, float v1 = 0, float u2 = 0, float v2 = 0,
              u16 z = 0) {
        BuildVertex v[2];
        v[0].x = x1, v[0].y = y1, v[0].z = z, v[0].color = color, v[0].u = u1, v[0].v = v1;
        v[1].x = x2, v[1].y = y2, v[1].z = z, v[1].color = color, v[1].u = u2, v[1].v = v2;
        const u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        const std::vector<u8> data = packVertices(vtype, v, 2);
        b->drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
    }

    std::unique_ptr<Memory> mem;
    std::unique_ptr<gl::GlRenderer> renderer;
    std::unique_ptr<GeEngine> engine;
    std::unique_ptr<ListBuilder> b;
};

inline std::string pathName(const ::testing::TestParamInfo<GlPath>& info) {
    switch (info.param) {
        case GlPath::FbFetch: return "FbFetch";
        case GlPath::Barrier: return "Barrier";
        default: return "Baseline";
    }
}
#define GE2GL_GL_PATHS ::testing::Values(GlPath::FbFetch, GlPath::Barrier, GlPath::Baseline), pathName

}  // namespace ge::gltest
