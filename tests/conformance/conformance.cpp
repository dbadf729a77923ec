#include "tests/conformance/conformance.h"

#include <map>
#include <utility>

namespace ge::conformance {

void sdkFrameSetup(ListBuilder& b, const FrameSetup& f) {
    b.drawBuffer(f.format, 0, 512);
    b.depthBuffer(0, 512);
    sdkDispBuffer(b);
    b.depthBuffer(512 * 272 * 4, 512);
    b.offset(2048 - f.viewW / 2, 2048 - f.viewH / 2);
    b.viewport(2048, 2048, float(f.viewW), float(f.viewH));
    b.depthRange(65535, 0);
    b.depthMask(false);
    b.scissor(0, 0, f.scissorW, f.scissorH);
    b.cullMode(false);
}

void sdkDispBuffer(ListBuilder& b, u32 w, u32 h) { b.region(0, 0, w, h); }

void setIdentityMatrices(ListBuilder& b) {
    static constexpr float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    b.setMatrix(GeMatrix::World, kIdentity);
    b.setMatrix(GeMatrix::View, kIdentity);
    b.setMatrix(GeMatrix::Proj, kIdentity);
}

void drawOnePixel(ListBuilder& b, u32 abgr) {
    BuildVertex v[2];
    v[0].color = v[1].color = abgr;
    v[0].x = v[0].y = -1;
    v[1].x = v[1].y = 1;
    const u32 vtype = vt::COL_8888 | vt::POS_F | vt::THROUGH;
    const std::vector<u8> data = packVertices(vtype, v, 2);
    b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
}

// Checkpoints each backend passes at least. They only rise: a change that passes more raises its
// floor in the same commit; docs/conformance.md has the table.
int floorOf(const std::string& test, const std::string& backend) {
    static const std::map<std::pair<std::string, std::string>, int> kFloors = {
        {{"commands/blend", "soft"}, 65},
        {{"commands/blend", "gl"}, 65},
        {{"commands/blend565", "soft"}, 71},
        {{"commands/blend565", "gl"}, 71},
        {{"clut/address", "soft"}, 23},
        {{"clut/address", "gl"}, 23},
        {{"commands/light", "soft"}, 163},  // of 201: attenuation/exponent precision (docs/conformance.md)
        {{"commands/light", "gl"}, 163},
        {{"depth/precision", "soft"}, 99},  // of 117: transform-mode Z rounding (docs/conformance.md)
        {{"depth/precision", "gl"}, 99},
        {{"texfunc/add", "soft"}, 274},      {{"texfunc/add", "gl"}, 274},
        {{"texfunc/blend", "soft"}, 785},    {{"texfunc/blend", "gl"}, 785},
        {{"texfunc/decal", "soft"}, 272},    {{"texfunc/decal", "gl"}, 272},
        {{"texfunc/modulate", "soft"}, 271}, {{"texfunc/modulate", "gl"}, 271},
        {{"texfunc/replace", "soft"}, 271},  {{"texfunc/replace", "gl"}, 271},
    };
    auto it = kFloors.find({test, backend});
    return it == kFloors.end() ? 0 : it->second;
}

INSTANTIATE_TEST_SUITE_P(Backends, Conformance, ::testing::Values(std::string("soft"), std::string("gl")), backendName);

}  // namespace ge::conformance
