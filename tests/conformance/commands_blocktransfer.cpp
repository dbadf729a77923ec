// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/commands/blocktransfer, re-created (gu_sim.h, conformance.h).
// A block transfer from a buffer of 0xAA bytes to one of 0xBB bytes (2 MiB each, in RAM), 16- or
// 32-bit pixels, with source and destination strides 0 to 0xFC00 and sizes 1x1 to 1024x512; the
// test counts the bytes from the destination's start that equal the source's. The values show the
// stride the GE uses (bits 3-10 of the field: 0x407 acts as 0x400, 0xFC00 as 0x400, 0x7FF as
// 0x7F8) and rows overlapping where the stride is below the width.
#include "tests/conformance/conformance.h"

namespace ge::conformance {
namespace {

constexpr u32 kMem1 = 0x08400000, kMem2 = 0x08600000, kMemSize = 16384 * 32 * 4;

struct Case {
    const char* name;
    u32 stride, w, h, bpp;
    u32 hardware;  // sameCount(mem1, mem2) on a PSP
};
constexpr Case kCases[] = {
    {"16 bit, 0 stride", 0, 1024, 4, 16, 2048},           {"16 bit, 0x100 stride", 0x100, 1024, 4, 16, 3584},
    {"16 bit, 0x3F8 stride", 0x3F8, 1024, 4, 16, 8144},   {"16 bit, 0x400 stride", 0x400, 1024, 4, 16, 8192},
    {"16 bit, 0x407 stride", 0x407, 1024, 4, 16, 8192},   {"16 bit, 0x408 stride", 0x408, 1024, 4, 16, 2048},
    {"16 bit, 0x7FF stride", 0x7FF, 1024, 4, 16, 2048},   {"16 bit, 0xFC00 stride", 0xFC00, 1024, 4, 16, 8192},
    {"32 bit, 0 stride", 0, 1024, 4, 32, 4096},           {"32 bit, 0x100 stride", 0x100, 1024, 4, 32, 7168},
    {"32 bit, 0x3F8 stride", 0x3F8, 1024, 4, 32, 16288},  {"32 bit, 0x400 stride", 0x400, 1024, 4, 32, 16384},
    {"32 bit, 0x407 stride", 0x407, 1024, 4, 32, 16384},  {"32 bit, 0x408 stride", 0x408, 1024, 4, 32, 4096},
    {"32 bit, 0x7FF stride", 0x7FF, 1024, 4, 32, 4096},   {"32 bit, 0xFC00 stride", 0xFC00, 1024, 4, 32, 16384},
    {"1024x512", 0x200, 1024, 512, 16, 525312},           {"1024x256", 0x200, 1024, 256, 16, 263168},
    {"1024x128", 0x200, 1024, 128, 16, 132096},           {"1024x64", 0x200, 1024, 64, 16, 66560},
    {"1024x4", 0x200, 1024, 4, 16, 5120},                 {"1024x1", 0x200, 1024, 1, 16, 2048},
    {"1x1", 0x200, 1, 1, 16, 2},
};

TestRun runBlockTransfer(GuSim& gu) {
    TestRun run{"commands/blocktransfer", gu.backend(), {}};
    gu.init();
    const std::vector<u8> aa(kMemSize, 0xAA), bb(kMemSize, 0xBB);
    for (const Case& c : kCases) {
        gu.cpuWrite(kMem1, aa.data(), kMemSize);
        gu.cpuWrite(kMem2, bb.data(), kMemSize);
        // dlist1: the transfer registers written as raw words, then TRANSFERSTART, FINISH, END.
        ListBuilder& l = gu.start();
        l.cmd(GE_CMD_XBP1, kMem1 & 0xFFFFFF);
        l.cmd(GE_CMD_XBW1, ((kMem1 & 0xFF000000) >> 8) | (c.stride & 0xFFFF));
        l.cmd(GE_CMD_XPOS1, 0);
        l.cmd(GE_CMD_XBP2, kMem2 & 0xFFFFFF);
        l.cmd(GE_CMD_XBW2, ((kMem2 & 0xFF000000) >> 8) | (c.stride & 0xFFFF));
        l.cmd(GE_CMD_XPOS2, 0);
        l.cmd(GE_CMD_XSIZE, (((c.h - 1) << 10) & 0x000FFC00) | ((c.w - 1) & 0x3FF));
        l.cmd(GE_CMD_XSTART, c.bpp == 32 ? 1 : 0);
        gu.finishSync();
        const u8* a = gu.readBytes(kMem1, kMemSize);
        const u8* b = gu.readBytes(kMem2, kMemSize);
        u32 same = 0;
        while (same < kMemSize && a[same] == b[same]) ++same;
        run.checkpoints.push_back({c.name, c.hardware, same});
    }
    return run;
}

CONFORMANCE_TEST(CommandsBlockTransfer, runBlockTransfer)

}  // namespace
}  // namespace ge::conformance
