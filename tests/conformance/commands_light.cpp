// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/commands/light, re-created (gu_sim.h, conformance.h). One
// light (light 0) of each type (directional, point, spot) and each component mode (ambient +
// diffuse, + specular, powered diffuse) lights a 2x2 transform-mode quad with a 16-bit normal of
// raw (0, 0, ±1) — the test writes 1.0f through (s16)(int), so the normal is 1/32768 long — at the
// next free 2x2 box; the light sits at the box's own screen position plus an offset per group
// (diffuse angles, attenuation, spot direction / exponent / cutoff including NaN and infinities,
// powered diffuse, specular). After each group the frame ends and every box's top-left pixel is
// read. Light colours: ambient red, diffuse green, specular blue; material ambient/diffuse/
// specular white, emissive black. ge2gl once trailed PPSSPP on this test (docs/conformance.md,
// "Spot light direction").
#include "tests/conformance/conformance.h"

#include <cmath>
#include <cstdlib>
#include <limits>

namespace ge::conformance {
namespace {

// Read back on a PSP: the 201 boxes in drawing order.
constexpr u32 kHardware[] = {
    0xffff00, 0xffffff, 0xffff00, 0xffff00, 0xffffff, 0xffff00, 0xffff00, 0xffffff,
    0xffff00, 0xff0000, 0xff00b5, 0xff0000, 0xff0000, 0xff00b5, 0xff0000, 0x000000,
    0x000000, 0x000000, 0xff8000, 0xff80dd, 0xff8000, 0xff7f00, 0xff7fdd, 0xff7f00,
    0x7f3f00, 0x7f3f6e, 0x7f3f00, 0xff0000, 0xff0000, 0xff0000, 0xff0000, 0xff0000,
    0xff0000, 0x000000, 0x000000, 0x000000, 0xffff00, 0xffffff, 0xffff00, 0x808000,
    0x808080, 0x808000, 0x808000, 0x808080, 0x808000, 0xffff00, 0xffffff, 0xffff00,
    0x3f3f00, 0x3f3f3f, 0x3f3f00, 0x3f3f00, 0x3f3f3f, 0x3f3f00, 0xffff00, 0xffffff,
    0xffff00, 0xff2b00, 0xff2bc3, 0xff2b00, 0xc52400, 0xc52497, 0xc52400, 0xffff00,
    0xffffff, 0xffff00, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0xffff00, 0xffffff, 0xffff00, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x949400, 0x949494, 0x949400, 0x000000, 0x000000, 0x000000, 0xff9300,
    0xff93e3, 0xff9300, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0xff9300, 0xff93e3, 0xff9300, 0x000000, 0x000000, 0x000000, 0xff9300, 0xff93e3,
    0xff9300, 0x000000, 0x000000, 0x000000, 0x545400, 0x545454, 0x545400, 0xcaca00,
    0xcacaca, 0xcaca00, 0xffff00, 0xffffff, 0xffff00, 0xffff00, 0xffffff, 0xffff00,
    0x000000, 0x000000, 0x000000, 0xffff00, 0xffffff, 0xffff00, 0x000000, 0x000000,
    0x000000, 0xffff00, 0xffffff, 0xffff00, 0xffff00, 0xffffff, 0xffff00, 0x000000,
    0x000000, 0x000000, 0xbfbf00, 0xbfbfbf, 0xbfbf00, 0x000000, 0x000000, 0x000000,
    0xffff00, 0xffffff, 0xffff00, 0xffff00, 0xffffff, 0xffff00, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0xffff00, 0xffff00, 0xffff00, 0xffff00,
    0xffff00, 0xffff00, 0xffff00, 0xffff00, 0xffff00, 0xff0000, 0xff0000, 0xff0000,
    0xff4000, 0xff3f00, 0x7f1f00, 0xffc000, 0xffbf00, 0x7f5f00, 0xffff00, 0xffff00,
    0x7f7f00, 0xff00ff, 0xff00ff, 0xff00ff, 0xff0000, 0xff0000, 0xff0000, 0xff80ee,
    0xff7fee, 0xff7fee, 0xff80bb, 0xff7fbb, 0xff7fbb, 0xff80ff, 0xff7fff, 0xff7fff,
    0xff80ff, 0xff7fff, 0xff7fff, 0xff8000, 0xff7f00, 0xff7f00, 0xff8000, 0xff7f00,
    0xff7f00,
};

enum Kind : int {
    kDirec = 1, kPoint = 2, kSpot = 4, kTypeAll = 7,
    kOnlyDiffuse = 0x10, kBoth = 0x20, kPowDiffuse = 0x40, kModeAll = 0x70,
    kAll = 0x77,
};

struct V3 {
    float x, y, z;
};

class LightTest {
public:
    explicit LightTest(GuSim& gu) : gu_(gu) {}

    TestRun run() {
        TestRun out{"commands/light", gu_.backend(), {}};
        run_ = &out;
        gu_.init();
        commandsInitDisplay(gu_.start());
        gu_.finishSync();
        // draw()
        startFrame();
        l().enable(GE_CMD_STE, false);  // sceGuDisable(GU_TEXTURE): GU_TEXTURE is 3, GU_STENCIL_TEST's number
        l().enable(GE_CMD_ABE, false);
        l().clear(CLEAR_COLOR | CLEAR_STENCIL, 0x003F3F3F, 0, 0);
        l().enable(GE_CMD_LTE, true);
        l().enable(GE_CMD_LE0, true);
        testDiffuse();
        testAttenuation();
        testSpots();
        testPoweredDiffuse();
        testSpecular();
        logBoxes();
        gu_.finishSync();
        EXPECT_EQ(out.checkpoints.size(), std::size(kHardware));
        return out;
    }

private:
    ListBuilder& l() { return gu_.list(); }

    void startFrame() {
        gu_.start();
        l().clear(CLEAR_COLOR, 0, 0, 0);  // sceGuClearColor(0); sceGuClear(GU_COLOR_BUFFER_BIT)
    }

    static float norm32x(int x) { return 2.0f * float(x) / 480.0f - 1.0f; }
    static s16 norm16x(int x) { return s16(x * 65536 / 480 - 32768); }
    static s16 norm16y(int y) { return s16(32768 - y * 65536 / 272); }

    void drawBox(const std::string& title) {
        const int x = nextX_, y = nextY_;
        // Vertices(GU_COLOR_8888 | GU_NORMAL_16BIT | GU_VERTEX_16BIT | GU_TRANSFORM_3D), four CNP:
        // colour, normal (s16)(int)boxNormZ, position norm16x/norm16y, z 0; 16 bytes each.
        const int px[4] = {x, x + 2, x + 2, x}, py[4] = {y, y, y + 2, y + 2};
        std::vector<u8> v(16 * 4, 0);
        for (int i = 0; i < 4; ++i) {
            u8* p = &v[size_t(i) * 16];
            writeLE32(p, 0xFFFFFFFF);
            writeLE16(p + 4, 0);
            writeLE16(p + 6, 0);
            writeLE16(p + 8, u16(s16(int(normZ_))));
            writeLE16(p + 10, u16(norm16x(px[i])));
            writeLE16(p + 12, u16(norm16y(py[i])));
            writeLE16(p + 14, 0);
        }
        l().drawArrayData(GE_PRIM_TRIANGLE_FAN, vt::COL_8888 | vt::NRM_16 | vt::POS_16, 4, nullptr, v.data());
        boxes_.push_back({x, y, title});
        nextX_ += 2;
        if (nextX_ >= 480) nextX_ = 0, nextY_ += 2;
    }

    void logBoxes() {
        gu_.finishSync();  // endFrame
        if (std::getenv("GE2GL_CONF_DEBUG")) {
            int n = 0;
            for (u32 i = 0; i < 512 * 272; ++i) if (gu_.readVram32(i * 4)) { if (n++ < 5) std::printf("nonzero at %u,%u: %08x\n", i % 512, i / 512, gu_.readVram32(i * 4)); }
            std::printf("nonzero pixels: %d\n", n);
        }
        for (const Box& b : boxes_) {
            const size_t k = run_->checkpoints.size();
            const u32 hw = k < std::size(kHardware) ? kHardware[k] : 0xDEADBEEF;
            run_->checkpoints.push_back({b.title, hw, gu_.readVram32(u32(b.y * 512 + b.x) * 4)});
        }
        boxes_.clear();
        startFrame();
    }

    void resetLightState() {
        l().lightAtt(0, 1.0f, 0.0f, 0.0f);
        l().lightMode(false);
        l().lightColor(0, LIGHT_AMBIENT, 0xFF0000);
        l().lightColor(0, LIGHT_DIFFUSE, 0x00FF00);
        l().lightColor(0, LIGHT_SPECULAR, 0x0000FF);
        spot({0, 0, 1}, 1.0f, 0.0f);
        l().specularPower(1.0f);
        // sceGuModelColor(0, 0xFFFFFF, 0xFFFFFF, 0xFFFFFF): emissive, diffuse, ambient, specular.
        l().cmd(GE_CMD_MEC, 0x000000);
        l().cmd(GE_CMD_MDC, 0xFFFFFF);
        l().cmd(GE_CMD_MAC, 0xFFFFFF);
        l().cmd(GE_CMD_MSC, 0xFFFFFF);
        l().colorMaterial(0);
        normZ_ = 1.0f;
    }

    void spot(V3 dir, float exponent, float cutoff) {
        const float d[3] = {dir.x, dir.y, dir.z};
        l().lightSpot(0, d, exponent, cutoff);
    }

    // sceGuLight(0, type, components, pos + add); components: 0 A+D, 1 D+S, 2 powered D.
    void drawLight(const std::string& title, const char* sub, u32 type, u32 comps, const V3* pos, V3 add) {
        V3 p = pos ? *pos : V3{norm32x(nextX_ + 1), -norm32x(nextY_ + 1), 0.0f};
        const float q[3] = {p.x + add.x, p.y + add.y, p.z + add.z};
        l().light(0, type, comps, q);
        drawBox(title + " - " + sub);
    }

    static bool match(int kinds, int m) { return (kinds & m) == m; }

    void types(const std::string& title, V3 add, int kinds) {
        const V3 zero{0, 0, 0};
        if (match(kinds, kDirec | kOnlyDiffuse)) drawLight(title, "Direc A + D", 0, 0, &zero, add);
        if (match(kinds, kDirec | kBoth)) drawLight(title, "Direc A + D + pow(S)", 0, 1, &zero, add);
        if (match(kinds, kDirec | kPowDiffuse)) drawLight(title, "Direc A + pow(D)", 0, 2, &zero, add);
        if (match(kinds, kPoint | kOnlyDiffuse)) drawLight(title, "Point A + D", 1, 0, nullptr, add);
        if (match(kinds, kPoint | kBoth)) drawLight(title, "Point A + D + pow(S)", 1, 1, nullptr, add);
        if (match(kinds, kPoint | kPowDiffuse)) drawLight(title, "Point A + pow(D)", 1, 2, nullptr, add);
        if (match(kinds, kSpot | kOnlyDiffuse)) drawLight(title, "Spot A + D", 2, 0, nullptr, add);
        if (match(kinds, kSpot | kBoth)) drawLight(title, "Spot A + D + pow(S)", 2, 1, nullptr, add);
        if (match(kinds, kSpot | kPowDiffuse)) drawLight(title, "Spot A + pow(D)", 2, 2, nullptr, add);
        logBoxes();
    }

    void testDiffuse() {
        resetLightState();
        types("Diffuse 1.0", {0, 0, 1}, kAll);
        types("Diffuse 0.0", {0.5f, 0.5f, 0}, kAll);
        types("Diffuse 0.5", {1, 1, 0.817f}, kAll);
        types("Diffuse -0.5", {1, 1, -0.817f}, kAll);
    }

    void testAttenuation() {
        resetLightState();
        l().lightAtt(0, 0, 1, 0);
        types("Attenuation 0.5", {0, 0, 2}, kAll);
        l().lightAtt(0, 0, 0, 1);
        types("Attenuation pow(0.5)", {0, 0, 2}, kAll);
        l().lightAtt(0, 0, 1, 0);
        spot({1, 1, 1}, 1.0f, 0.0f);
        types("Attenuation large", {0, 0, 0.001f}, kAll);
        l().lightAtt(0, 0, 1, 0);
        spot({0, 0, 1}, 1.0f, 0.0f);
        types("Attenuation tiny", {0, 0, 1000.0f}, kAll);
        l().lightAtt(0, -1, 0, 0);
        types("Attenuation -1.0", {0, 0, 1}, kAll);
    }

    void testSpots() {
        const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
        const V3 v000{0, 0, 0}, v001{0, 0, 1}, v00N{0, 0, -1}, v100{1, 0, 0}, v111{1, 1, 1};
        const int k = kSpot | kModeAll;
        resetLightState();
        spot(v111, 1, 0);
        types("Spot z=1", v001, k);
        types("Spot z=-1", v00N, k);
        types("Spot xyz=1", v111, k);
        spot(v001, 1, 0);
        types("Spot z=0", v100, k);
        spot(v000, 1, 0);
        types("Spot zero vector", v111, k);
        spot({nan, nan, nan}, 1, 0);
        types("Spot NAN", v111, k);
        spot({-nan, -nan, -nan}, 1, 0);
        types("Spot -NAN", v111, k);
        spot({inf, inf, inf}, 1, 0);
        types("Spot INFINITY", v111, k);
        spot({-inf, -inf, -inf}, 1, 0);
        types("Spot -INFINITY", v111, k);

        spot(v111, 2, 0);
        types("Spot e=2", v001, k);
        spot(v111, 0.5f, 0);
        types("Spot e=0.5", v001, k);
        spot(v111, 0, 0);
        types("Spot e=0.0", v001, k);
        spot(v000, 0, 0);
        types("Spot zero vector e=0.0", v001, k);
        spot(v111, nan, 0);
        types("Spot e=NAN", v001, k);
        spot(v111, -nan, 0);
        types("Spot e=-NAN", v001, k);
        spot(v111, inf, 0);
        types("Spot e=INF", v001, k);
        spot(v111, -inf, 0);
        types("Spot e=-INF", v001, k);

        spot(v00N, 0, -100);
        types("Spot negative cutoff + e=0.0", v001, k);
        spot(v00N, 2, -100);
        types("Spot negative cutoff + e=2.0", v001, k);
        spot(v001, 0, 1);
        types("Spot 1.0 cutoff=1.0", v001, k);
        spot(v001, 0, 2);
        types("Spot 1.0 cutoff=2.0", v001, k);
        spot(v001, 0, -nan);
        types("Spot 1.0 cutoff=-NAN", v001, k);
        spot(v001, 0, -inf);
        types("Spot 1.0 cutoff=-INF", v001, k);
        spot(v001, 0, nan);
        types("Spot 1.0 cutoff=NAN", v001, k);
        spot(v001, 0, inf);
        types("Spot 1.0 cutoff=INF", v001, k);
    }

    void testPoweredDiffuse() {
        const V3 v001{0, 0, 1}, v00N{0, 0, -1}, v111{1, 1, 1}, d05{1, 1, 0.817f};
        const int k = kTypeAll | kPowDiffuse;
        resetLightState();
        types("Diffuse 1.0 pow e=1.0", v001, k);
        l().specularPower(0.0f);
        types("Diffuse 1.0 pow e=0.0", v001, k);
        l().specularPower(0.0f);
        spot(v111, 0, -100);
        types("Diffuse -1.0 pow e=0.0", v00N, k);
        l().specularPower(2.0f);
        types("Diffuse -1.0 pow e=2.0", v00N, k);
        spot(v001, 1, 0);
        l().specularPower(2.0f);
        types("Diffuse 0.5 pow e=2.0", d05, k);
        l().specularPower(0.5f);
        types("Diffuse 0.5 pow e=0.5", d05, k);
        l().specularPower(-1.0f);
        types("Diffuse 0.5 pow e=-1.0", d05, k);
    }

    void testSpecular() {
        const V3 v111{1, 1, 1}, d0{0.5f, 0.5f, 0}, d05{1, 1, 0.817f}, dN{1, 1, -0.817f};
        const int k = kTypeAll | kBoth;
        resetLightState();
        spot(v111, 0, -100);
        l().specularPower(0.0f);
        types("Diffuse 0.0 spec e=0.0", d0, k);
        types("Diffuse -0.5 spec e=0.0", dN, k);
        l().specularPower(0.5f);
        types("Diffuse 0.5 spec e=0.5", d05, k);
        l().specularPower(2.0f);
        types("Diffuse 0.5 spec e=2.0", d05, k);
        l().specularPower(-2.0f);
        types("Diffuse 0.5 spec e=-2.0", d05, k);
        normZ_ = -1.0f;
        l().specularPower(0.0f);
        types("Diffuse 0.5 spec=-0.5 e=0.0", dN, k);
        l().specularPower(1.0f);
        types("Diffuse 0.5 spec=-0.5 e=1.0", dN, k);
        l().specularPower(2.0f);
        types("Diffuse 0.5 spec=-0.5 e=2.0", dN, k);
    }

    struct Box {
        int x, y;
        std::string title;
    };
    GuSim& gu_;
    TestRun* run_ = nullptr;
    std::vector<Box> boxes_;
    int nextX_ = 2, nextY_ = 2;
    float normZ_ = 1.0f;
};

TestRun runLight(GuSim& gu) { return LightTest(gu).run(); }

CONFORMANCE_TEST(CommandsLight, runLight)

}  // namespace
}  // namespace ge::conformance
