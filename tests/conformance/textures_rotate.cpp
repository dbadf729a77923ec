// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/textures/rotate, re-created (gu_sim.h, conformance.h). A 2x2
// 8888 texture (texels 0x0100FF, 0x02FF00 / 0x03FF00, 0x0400FF), nearest, DECAL/RGB, drawn by a
// 2x2 sprite whose two vertices are given in the four corner orders (TL-BR, TR-BL, BL-TR, BR-TL),
// in through mode, in transform mode, with the model, view or projection matrix flipping Y, and
// with a negative viewport height; the 2x2 pixels at (0, 0) are read back. The values show how a
// sprite maps its texture when its corners come in another order.
#include "tests/conformance/conformance.h"

namespace ge::conformance {
namespace {

// On a PSP, per group and corner order, pixels (0,0) (1,0) (0,1) (1,1).
constexpr u32 kHardware[96] = {
    0x0100ff, 0x02ff00, 0x03ff00, 0x0400ff, 0x03ff00, 0x0100ff, 0x0400ff, 0x02ff00,
    0x02ff00, 0x0400ff, 0x0100ff, 0x03ff00, 0x0400ff, 0x03ff00, 0x02ff00, 0x0100ff,
    0x0100ff, 0x02ff00, 0x03ff00, 0x0400ff, 0x03ff00, 0x0100ff, 0x0400ff, 0x02ff00,
    0x02ff00, 0x0400ff, 0x0100ff, 0x03ff00, 0x0400ff, 0x03ff00, 0x02ff00, 0x0100ff,
    0x0100ff, 0x02ff00, 0x03ff00, 0x0400ff, 0x03ff00, 0x0100ff, 0x0400ff, 0x02ff00,
    0x02ff00, 0x0400ff, 0x0100ff, 0x03ff00, 0x0400ff, 0x03ff00, 0x02ff00, 0x0100ff,
    0x0100ff, 0x02ff00, 0x03ff00, 0x0400ff, 0x03ff00, 0x0100ff, 0x0400ff, 0x02ff00,
    0x02ff00, 0x0400ff, 0x0100ff, 0x03ff00, 0x0400ff, 0x03ff00, 0x02ff00, 0x0100ff,
    0x0100ff, 0x02ff00, 0x03ff00, 0x0400ff, 0x03ff00, 0x0100ff, 0x0400ff, 0x02ff00,
    0x02ff00, 0x0400ff, 0x0100ff, 0x03ff00, 0x0400ff, 0x03ff00, 0x02ff00, 0x0100ff,
    0x0100ff, 0x02ff00, 0x03ff00, 0x0400ff, 0x03ff00, 0x0100ff, 0x0400ff, 0x02ff00,
    0x02ff00, 0x0400ff, 0x0100ff, 0x03ff00, 0x0400ff, 0x03ff00, 0x02ff00, 0x0100ff,
};

constexpr u32 kImage = 0x08400000;
constexpr s16 kTransT = 32767, kTransL = -32768, kTransB = 32767 - 482, kTransR = -32768 + 273;
constexpr s16 kFlipT = -32768, kFlipB = -32768 + 482;

struct Corner {
    u16 u, v;
    s16 x, y;
};
using Sprite = Corner[2];
constexpr Sprite kThrough[4] = {{{0, 0, 0, 0}, {2, 2, 2, 2}},
                                {{0, 0, 2, 0}, {2, 2, 0, 2}},
                                {{0, 0, 0, 2}, {2, 2, 2, 0}},
                                {{0, 0, 2, 2}, {2, 2, 0, 0}}};
constexpr Sprite kTransform[4] = {{{0, 0, kTransL, kTransT}, {32768, 32768, kTransR, kTransB}},
                                  {{0, 0, kTransR, kTransT}, {32768, 32768, kTransL, kTransB}},
                                  {{0, 0, kTransL, kTransB}, {32768, 32768, kTransR, kTransT}},
                                  {{0, 0, kTransR, kTransB}, {32768, 32768, kTransL, kTransT}}};
constexpr Sprite kFlipped[4] = {{{0, 0, kTransL, kFlipT}, {32768, 32768, kTransR, kFlipB}},
                                {{0, 0, kTransR, kFlipT}, {32768, 32768, kTransL, kFlipB}},
                                {{0, 0, kTransL, kFlipB}, {32768, 32768, kTransR, kFlipT}},
                                {{0, 0, kTransR, kFlipB}, {32768, 32768, kTransL, kFlipT}}};

class RotateTest {
public:
    explicit RotateTest(GuSim& gu) : gu_(gu), run_{"textures/rotate", gu.backend(), {}} {}

    TestRun run() {
        gu_.init();
        ListBuilder& b = gu_.start();  // init(): no depth range (sceGuInit left the viewport's Z at 0)
        b.drawBuffer(GE_FORMAT_8888, 0, 512);
        b.depthBuffer(0, 512);
        sdkDispBuffer(b);
        b.scissor(0, 0, 480, 272);
        b.offset(2048 - 240, 2048 - 136);
        b.viewport(2048, 2048, 480, 272);
        b.depthMask(true);
        b.cullMode(false);
        b.shadeModel(true);
        setIdentityMatrices(b);
        gu_.finishSync();
        gu_.fillVram32(0, 0, 512 * 272);
        const u32 image[8] = {0x000100FF, 0x0002FF00, 0, 0, 0x0003FF00, 0x000400FF, 0, 0};
        gu_.cpuWrite(kImage, image, sizeof image);
        gu_.start().texFilter(0, 0);
        gu_.finishSync();

        group("Through mode", true, kThrough);
        group("Full transform", false, kTransform);
        flipMatrix(GeMatrix::World);
        group("Full transform (flipped model)", false, kFlipped);
        flipMatrix(GeMatrix::View);
        group("Full transform (flipped view)", false, kFlipped);
        flipMatrix(GeMatrix::Proj);
        group("Full transform (flipped proj)", false, kFlipped);
        {
            ListBuilder& l = gu_.start();  // setFlippedMatrix(-1); setFlippedViewport(true)
            setIdentityMatrices(l);
            gu_.finishSync();
            gu_.start().viewport(2048, 2048, 480, -272);
            gu_.finishSync();
        }
        group("Full transform (flipped viewport)", false, kFlipped);
        return run_;
    }

private:
    void flipMatrix(GeMatrix which) {
        static constexpr float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        static constexpr float kFlipY[16] = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        ListBuilder& l = gu_.start();
        for (GeMatrix m : {GeMatrix::World, GeMatrix::View, GeMatrix::Proj}) l.setMatrix(m, m == which ? kFlipY : kIdentity);
        gu_.finishSync();
    }

    void group(const std::string& title, bool through, const Sprite* sprites) {
        static const char* kOrders[4] = {"TL BR", "TR BL", "BL TR", "BR TL"};
        for (int i = 0; i < 4; ++i) {
            // Vertex {u16 u, v; s16 x, y, z}, z 0.
            std::vector<u8> v(20, 0);
            for (int k = 0; k < 2; ++k) {
                u8* p = &v[size_t(k) * 10];
                writeLE16(p, sprites[i][k].u);
                writeLE16(p + 2, sprites[i][k].v);
                writeLE16(p + 4, u16(sprites[i][k].x));
                writeLE16(p + 6, u16(sprites[i][k].y));
            }
            ListBuilder& l = gu_.start();  // drawTexFlush()
            l.enable(GE_CMD_TME, true);
            l.texMode(GE_TFMT_8888, 0, false);
            l.texFunc(1 /*DECAL*/, false);
            l.setTexture(0, kImage, 2, 2, 4);
            l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | (through ? vt::THROUGH : 0u), 2, nullptr, v.data());
            gu_.finishSync();
            for (u32 y = 0; y < 2; ++y)
                for (u32 x = 0; x < 2; ++x) {
                    const size_t n = run_.checkpoints.size();
                    run_.checkpoints.push_back({title + " " + kOrders[i] + " (" + std::to_string(x) + "," + std::to_string(y) + ")",
                                                kHardware[n], gu_.readVram32((y * 512 + x) * 4), 0x00FFFFFF});
                }
            gu_.fillVram32(0, 0, 512 * 272);
        }
    }

    GuSim& gu_;
    TestRun run_;
};

TestRun runRotate(GuSim& gu) { return RotateTest(gu).run(); }

CONFORMANCE_TEST(TexturesRotate, runRotate)

}  // namespace
}  // namespace ge::conformance
