// SPDX-License-Identifier: MIT
// `ge2gl step` (tools/lib/step.h, the GE debugger's CLI): the frame buffer right after
// draw N is the frame `render --replay-end N` gives, for every draw of the five scenes; the
// read-outs at a break hold what the scene put there; the command line prints the state and writes
// the buffers.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "hle/dump/player.h"
#include "tests/tools_cli_run.h"
#include "tools/lib/render.h"
#include "tools/lib/step.h"

using namespace ge;
using namespace clitest;
namespace fs = std::filesystem;

namespace {

std::string scenePath(const char* name) { return std::string(GE2GL_SOURCE_DIR) + "/dumps/" + name + ".ppdmp"; }

size_t differing(const tools::Image& a, const tools::Image& b) {
    if (a.rgba.size() != b.rgba.size()) return ~size_t(0);
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) n += (a.rgba[i] & 0xFFFFFF) != (b.rgba[i] & 0xFFFFFF);
    return n;
}

TEST(Step, BreakOnDrawNGivesTheFrameOfReplayEndN) {
    int checked = 0;
    for (const char* name : {"lit_textured_skinned", "blend_stencil_logic", "clut_dxt_sprites", "render_to_texture", "bezier_spline"}) {
        dump::Dump d;
        std::string err;
        ASSERT_TRUE(dump::loadDump(scenePath(name), d, err)) << err;
        const u64 draws = dump::summarize(d).draws;
        ASSERT_GT(draws, 2u) << name;
        for (u64 n = 1; n <= draws; ++n) {
            SCOPED_TRACE(std::string(name) + " draw " + std::to_string(n));
            tools::StepOptions so;
            so.breakAt = "draw:" + std::to_string(n);
            so.render.threads = 1;
            tools::StepResult step;
            ASSERT_TRUE(tools::stepDump(scenePath(name), so, step, err)) << err;
            ASSERT_TRUE(step.hit);
            tools::RenderOptions ro;
            ro.threads = 1;
            ro.replayEnd = n;
            tools::RenderOutput want;
            std::vector<u8> vram;
            ASSERT_TRUE(tools::renderDump(d, ro, want, err, &vram)) << err;
            // The buffer draw N went into (a render-to-texture scene draws into another first), as
            // the replay that stopped after draw N left it in VRAM.
            Memory m;
            ASSERT_TRUE(m.write(Memory::kVramBase, vram.data(), u32(vram.size())));
            const tools::Image wantFrame = tools::readFrame(m, step.fbAddr, step.fbStride, step.fbFormat);
            ASSERT_EQ(step.color.rgba.size(), wantFrame.rgba.size());
            EXPECT_EQ(differing(step.color, wantFrame), 0u);
            ++checked;
        }
    }
    EXPECT_GT(checked, 20);
}

TEST(Step, ReadOutsHoldWhatTheSceneSent) {
    // clut_dxt_sprites: its third draw is a 52x52 sprite from (4, 10) with a swizzled 32x32 CLUT4
    // texture and a 4444 palette (the scene's source: tools/scenes/clut_dxt_sprites.cpp).
    tools::StepOptions so;
    so.breakAt = "draw:3";
    so.outDir = (fs::temp_directory_path() / ("ge2gl_step_" + std::to_string(::getpid()))).string();
    tools::StepResult r;
    std::string err;
    ASSERT_TRUE(tools::stepDump(scenePath("clut_dxt_sprites"), so, r, err)) << err;
    ASSERT_TRUE(r.hit);
    EXPECT_NE(r.report.find("> 0x"), std::string::npos);  // the disassembly marks the pc
    EXPECT_NE(r.report.find("PRIM count=2 type=6"), std::string::npos) << r.report;
    EXPECT_NE(r.report.find("    4.000   10.000"), std::string::npos) << r.report;  // screen position of vertex 0
    EXPECT_NE(r.report.find("   56.000   62.000"), std::string::npos) << r.report;
    EXPECT_NE(r.report.find("level 0 32x32"), std::string::npos) << r.report;
    EXPECT_NE(r.report.find("0xc5 CLUT"), std::string::npos) << r.report;  // every register is listed
    for (const char* f : {"color.png", "depth.png", "stencil.png", "texture-L0.png", "clut.png"})
        EXPECT_TRUE(fs::exists(fs::path(so.outDir) / f)) << f;
    fs::remove_all(so.outDir);

    // Bad specs and a break the frame never reaches.
    tools::StepResult none;
    so.outDir.clear();
    for (const char* bad : {"draw:0", "draw:x", "op:NOPE", "addr:0x3", "frame:1", "draw"}) {
        so.breakAt = bad;
        EXPECT_FALSE(tools::stepDump(scenePath("clut_dxt_sprites"), so, none, err)) << bad;
    }
    so.breakAt = "draw:100000";
    ASSERT_TRUE(tools::stepDump(scenePath("clut_dxt_sprites"), so, none, err)) << err;
    EXPECT_FALSE(none.hit);
    so.breakAt = "op:CLOAD:2";
    ASSERT_TRUE(tools::stepDump(scenePath("clut_dxt_sprites"), so, none, err)) << err;
    EXPECT_TRUE(none.hit);
    EXPECT_NE(none.report.find("CLOAD"), std::string::npos);
}

TEST(Step, CommandLinePrintsTheStateAndFailsWhenTheBreakIsNeverReached) {
    CliRun r = runCommand(quote(cliPath()) + " step " + quote(scenePath("lit_textured_skinned")) + " --break prim:2");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("== vertices"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("== registers and matrices =="), std::string::npos);
    EXPECT_NE(r.out.find("world (upload index"), std::string::npos);
    r = runCommand(quote(cliPath()) + " step " + quote(scenePath("lit_textured_skinned")) + " --break draw:9999");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("the frame ended before --break draw:9999"), std::string::npos) << r.out;
    r = runCommand(quote(cliPath()) + " step " + quote(scenePath("lit_textured_skinned")) + " --break bogus:1");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("bad --break"), std::string::npos) << r.out;
}

}  // namespace
