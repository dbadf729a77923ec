// SPDX-License-Identifier: MIT
// What the GL translator builds on the CPU per draw is bounded like the software model's work
// (docs/timing.md, docs/fuzzing.md): a batch holds at most kGlBatchTriangles GL triangles, one
// huge draw is drawn in parts, the arrays are trimmed after a flush, and while a GE-time limit
// is set (dump replays) every GL triangle built is charged to it
// (VertexPipeline::kHostPixelsPerGlTriangle), so a replay of line fragments, each a one-pixel
// quad, stops at the budget.
#include <gtest/gtest.h>

#include "hle/dump/dump_writer.h"
#include "hle/dump/player.h"
#include "hle/ge_time.h"
#include "softmodel/soft_renderer.h"
#include "tests/gl_fixture.h"
#include "tests/hostile_dumps.h"
#include "translator/vertex_pipeline.h"

namespace ge::gltest {
namespace {

std::unique_ptr<gl::GlRenderer> makeGl(Memory& mem, gl::GlMode mode) {
    gl::GlOptions opt;
    opt.mode = mode;
    opt.vertices = gl::GlOptions::Vertices::Cpu;
    std::string err;
    return gl::createGlRenderer(mem, opt, err);
}

// A 64×64 frame and `lines` one-pixel-apart horizontal lines of 60 pixels, one LINES draw:
// 60 fragments each, 120 GL triangles each.
void drawLines(ListBuilder& b, u32 lines) {
    b.drawBuffer(GE_FORMAT_8888, kFbOffset, kStride);
    b.scissor(0, 0, kSize, kSize);
    b.region(0, 0, kSize, kSize);
    std::vector<BuildVertex> v(2 * size_t(lines));
    for (u32 i = 0; i < lines; ++i) {
        v[2 * i].x = 2, v[2 * i + 1].x = 62;
        v[2 * i].y = v[2 * i + 1].y = float(i % 64);
        v[2 * i].color = v[2 * i + 1].color = 0xFF000000u | (i * 0x010203u);
    }
    const u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    const std::vector<u8> data = packVertices(vtype, v.data(), u32(v.size()));
    b.drawArrayData(GE_PRIM_LINES, vtype, u32(v.size()), nullptr, data.data());
}

class GlWorkBounds : public ::testing::TestWithParam<gl::GlMode> {};

// One draw of 1,200 lines is 144,000 GL triangles, more than two batches: it is drawn in parts,
// no batch holds more than kGlBatchTriangles, and the parts draw what the software model draws.
TEST_P(GlWorkBounds, HugeDrawIsDrawnInBoundedParts) {
    Memory mem;
    auto gl = makeGl(mem, GetParam());
    if (!gl) GTEST_SKIP() << "no GL context";
    const std::vector<u8> glVram = runListVram(mem, *gl, [](ListBuilder& b) { drawLines(b, 1200); });
    const gl::GlStats s = gl->stats();
    EXPECT_EQ(s.cpuTriangles, 1200u * 60 * 2);
    EXPECT_LE(s.batchPeak, gl::kGlBatchTriangles);
    EXPECT_GE(s.glDrawCalls, 3u);
    // Flushed and trimmed: the arrays do not keep a batch's peak.
    EXPECT_LE(s.cpuGeometryBytes, 2 * gl::Geometry::kTrimFloor * (3 * sizeof(gl::GlVertex) + sizeof(gl::PrimBounds) +
                                                                   sizeof(gl::TriRecord)));
    Memory softMem;
    soft::SoftOptions so;
    so.threads = 1;
    auto soft = soft::createSoftRenderer(softMem, so);
    const std::vector<u8> softVram = runListVram(softMem, *soft, [](ListBuilder& b) { drawLines(b, 1200); });
    if (GetParam() == gl::GlMode::Exact) {
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const size_t at = size_t(y * int(kStride) + x) * 4;
                ASSERT_EQ(std::memcmp(&glVram[at], &softVram[at], 4), 0) << x << "," << y;
            }
    }
}

// After a batch far larger than the next ones, a flush gives the memory back.
TEST_P(GlWorkBounds, ArraysAreTrimmedAfterALargeBatch) {
    Memory mem;
    auto gl = makeGl(mem, GetParam());
    if (!gl) GTEST_SKIP() << "no GL context";
    runListVram(mem, *gl, [](ListBuilder& b) { drawLines(b, 500); });  // 60,000 GL triangles
    runListVram(mem, *gl, [](ListBuilder& b) { drawLines(b, 2); });
    EXPECT_LE(gl->stats().cpuGeometryBytes, 64u << 20);
    EXPECT_LE(gl->stats().cpuGeometryBytes,
              4 * gl::Geometry::kTrimFloor * (3 * sizeof(gl::GlVertex) + sizeof(gl::PrimBounds) + sizeof(gl::TriRecord)));
}

// A replay of screen-wide line strips: the software model shades the fragments at the GE's fill
// rate, the GL translator makes each a quad of two triangles on the CPU. Under a GE-time limit
// the quads are charged, and the replay stops at the budget with the usual warning instead of
// building and drawing millions of them.
TEST_P(GlWorkBounds, LineFragmentsAreChargedToTheGeTimeBudget) {
    dump::DumpWriter w = hostile::start();
    w.registers(hostile::frameState());
    std::vector<BuildVertex> v(1000);
    for (size_t i = 0; i < v.size(); ++i) v[i].x = (i & 1) ? 479 : 0, v[i].y = (i & 2) ? 271 : 0, v[i].color = 0xFF00FF00;
    const auto bytes = packVertices(hostile::kThroughColor, v.data(), u32(v.size()));
    w.vertices(bytes.data(), u32(bytes.size()));
    w.registers({hostile::word(GE_CMD_PRIM, (GE_PRIM_LINE_STRIP << 16) | u32(v.size()))});
    const dump::Dump d = hostile::repeatLast(w, 2, 1000);
    constexpr double kMs = 2.0;
    Memory mem;
    auto gl = makeGl(mem, GetParam());
    if (!gl) GTEST_SKIP() << "no GL context";
    GeEngine eng(mem, gl.get());
    dump::ReplayOptions opt;
    opt.maxGeMs = kMs;
    dump::ReplayResult res;
    std::string err;
    ASSERT_TRUE(dump::replayDump(d, eng, opt, res, err)) << err;
    EXPECT_TRUE(res.timeLimitHit);
    EXPECT_NE(res.warning.find("GE time budget"), std::string::npos) << res.warning;
    const gl::GlStats s = gl->stats();
    const u64 budget = getime::cyclesFromMs(kMs);
    // The quads alone may cost the budget, give or take one line's (480 fragments).
    EXPECT_GT(s.cpuTriangles, 0u);
    EXPECT_LE(s.cpuTriangleCycles, budget);
    EXPECT_LE(s.cpuTriangles, budget * 3 / gl::VertexPipeline::kHostPixelsPerGlTriangle + 2 * 480);
    EXPECT_EQ(s.cpuTriangleCycles * 3, s.cpuTriangles * gl::VertexPipeline::kHostPixelsPerGlTriangle);
    EXPECT_LE(s.batchPeak, gl::kGlBatchTriangles);
}

// Without a GE-time limit (a host running its own GE) nothing is charged: emulated time does not
// depend on the backend.
TEST_P(GlWorkBounds, NothingIsChargedWithoutATimeLimit) {
    auto run = [](Memory& mem, Renderer& r) {
        GeEngine eng(mem, &r);
        ListBuilder b(&mem);
        drawLines(b, 10);
        b.finish();
        eng.startList(b.placeList(), 0);
        EXPECT_EQ(eng.run(), RunStatus::Completed);
        return eng.stats();
    };
    Memory mem;
    auto gl = makeGl(mem, GetParam());
    if (!gl) GTEST_SKIP() << "no GL context";
    const GeStats glStats = run(mem, *gl);
    EXPECT_EQ(gl->stats().cpuTriangles, 10u * 60 * 2);
    EXPECT_EQ(gl->stats().cpuTriangleCycles, 0u);
    Memory softMem;
    soft::SoftOptions so;
    so.threads = 1;
    auto soft = soft::createSoftRenderer(softMem, so);
    const GeStats softStats = run(softMem, *soft);
    EXPECT_EQ(glStats.cyclesPixels, softStats.cyclesPixels);
    EXPECT_EQ(glStats.cycles, softStats.cycles);
}

INSTANTIATE_TEST_SUITE_P(Modes, GlWorkBounds, ::testing::Values(gl::GlMode::Exact, gl::GlMode::Hw),
                         [](const ::testing::TestParamInfo<gl::GlMode>& i) {
                             return std::string(i.param == gl::GlMode::Exact ? "Exact" : "Hw");
                         });

}  // namespace
}  // namespace ge::gltest
