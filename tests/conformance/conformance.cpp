// SPDX-License-Identifier: MIT
#include "tests/conformance/conformance.h"

#include <cstring>
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

void commandsInitDisplay(ListBuilder& b, const FrameSetup& f) {
    sdkFrameSetup(b, f);
    b.shadeModel(true);
    b.enable(GE_CMD_TME, false);
    setIdentityMatrices(b);
}

void clutInit(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.depthBuffer(0, 512);
    sdkDispBuffer(b);
    b.scissor(0, 0, 480, 272);
}

std::vector<u8> spriteUv16(u16 u, u16 v, u16 x, u16 y) {
    std::vector<u8> out(20, 0);
    writeLE16(&out[10], u), writeLE16(&out[12], v);
    writeLE16(&out[14], x), writeLE16(&out[16], y);
    return out;
}

std::vector<u8> uvColorPosF(const std::vector<std::array<float, 5>>& v, u32 color) {
    std::vector<u8> out(v.size() * 24, 0);
    for (size_t k = 0; k < v.size(); ++k) {
        u8* p = &out[k * 24];
        writeLE32(p, floatBits(v[k][0]));
        writeLE32(p + 4, floatBits(v[k][1]));
        writeLE32(p + 8, color);
        for (int c = 0; c < 3; ++c) writeLE32(p + 12 + c * 4, floatBits(v[k][2 + size_t(c)]));
    }
    return out;
}

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

std::vector<u8> colorPos16(const std::vector<ColorPos>& v, bool through) {
    std::vector<u8> out(v.size() * 12, 0);
    for (size_t i = 0; i < v.size(); ++i) {
        u8* p = &out[i * 12];
        const int x = through ? v[i].x : v[i].x * 65536 / 480 - 32768;
        const int y = through ? v[i].y : 32768 - v[i].y * 65536 / 272;
        writeLE32(p, v[i].color);
        writeLE16(p + 4, u16(x));
        writeLE16(p + 6, u16(y));
        writeLE16(p + 8, v[i].z);
    }
    return out;
}

void filteringInitDisplay(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.depthBuffer(0, 512);
    sdkDispBuffer(b);
    b.depthBuffer(512 * 272 * 4, 512);
    b.cmd(GE_CMD_OFFSETX, (2048 - 480 / 2) << 4);
    b.cmd(GE_CMD_OFFSETY, (2048 - 272 / 2) << 4);
    b.viewport(2048, 2048, 480, 272);
    b.depthRange(65535, 0);
    b.depthMask(false);
    b.scissor(0, 0, 480, 272);
    b.cullMode(false);
    b.shadeModel(true);
    b.enable(GE_CMD_TME, true);
    b.enable(GE_CMD_ABE, false);
    setIdentityMatrices(b);
    b.texMode(GE_TFMT_8888, 0, false);
    b.texFunc(3 /*REPLACE*/, true);
}

u32 floatBits(float f) {
    u32 u;
    std::memcpy(&u, &f, 4);
    return u;
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
        {{"commands/light", "soft"}, 170},  // of 201: attenuation/exponent precision (docs/conformance.md)
        {{"commands/light", "gl"}, 170},
        {{"depth/precision", "soft"}, 113},  // of 117: Z with the viewport centre 32768 (docs/conformance.md)
        {{"depth/precision", "gl"}, 113},
        {{"texfunc/add", "soft"}, 274},      {{"texfunc/add", "gl"}, 274},
        {{"texfunc/blend", "soft"}, 785},    {{"texfunc/blend", "gl"}, 785},
        {{"texfunc/decal", "soft"}, 272},    {{"texfunc/decal", "gl"}, 272},
        {{"texfunc/modulate", "soft"}, 271}, {{"texfunc/modulate", "gl"}, 271},
        {{"texfunc/replace", "soft"}, 271},  {{"texfunc/replace", "gl"}, 271},
        {{"commands/cull", "soft"}, 32},     {{"commands/cull", "gl"}, 32},
        {{"commands/fog", "soft"}, 266},     {{"commands/fog", "gl"}, 266},
        {{"dither", "soft"}, 624},           {{"dither", "gl"}, 624},
        {{"texcolors/rgb565", "soft"}, 4},   {{"texcolors/rgb565", "gl"}, 4},
        {{"texcolors/rgba5551", "soft"}, 4}, {{"texcolors/rgba5551", "gl"}, 4},
        {{"texcolors/rgba4444", "soft"}, 4}, {{"texcolors/rgba4444", "gl"}, 4},
        {{"texcolors/dxt1", "soft"}, 30},    {{"texcolors/dxt1", "gl"}, 30},
        {{"texcolors/dxt3", "soft"}, 34},    {{"texcolors/dxt3", "gl"}, 34},
        {{"texcolors/dxt5", "soft"}, 4368},  {{"texcolors/dxt5", "gl"}, 4368},
        {{"clut/shifts", "soft"}, 88},       {{"clut/shifts", "gl"}, 88},
        {{"clut/masks", "soft"}, 16},        {{"clut/masks", "gl"}, 16},
        {{"clut/offset", "soft"}, 170},      {{"clut/offset", "gl"}, 170},
        {{"textures/mipmap", "soft"}, 308},  {{"textures/mipmap", "gl"}, 308},
        {{"textures/rotate", "soft"}, 96},   {{"textures/rotate", "gl"}, 96},
        {{"filtering/nearest", "soft"}, 541}, {{"filtering/nearest", "gl"}, 541},
        {{"filtering/linear", "soft"}, 541},  {{"filtering/linear", "gl"}, 541},
        // the bilinear position truncated (the psp profile's AccuracyProfile::pspBilinearTruncation)
        {{"filtering/precisionlinear2d", "soft"}, 368},  {{"filtering/precisionlinear2d", "gl"}, 368},
        {{"filtering/precisionlinear3d", "soft"}, 368},  {{"filtering/precisionlinear3d", "gl"}, 368},
        {{"filtering/precisionnearest2d", "soft"}, 368}, {{"filtering/precisionnearest2d", "gl"}, 368},
        {{"filtering/precisionnearest3d", "soft"}, 368}, {{"filtering/precisionnearest3d", "gl"}, 368},
        {{"commands/blocktransfer", "soft"}, 23}, {{"commands/blocktransfer", "gl"}, 23},
        {{"rendertarget/depal", "soft"}, 272},   {{"rendertarget/depal", "gl"}, 272},
        // texmtx: one-step texel precision and attributes a vertex format leaves out (docs/conformance.md)
        {{"texmtx/uvs", "soft"}, 12},     {{"texmtx/uvs", "gl"}, 12},
        {{"texmtx/normals", "soft"}, 24}, {{"texmtx/normals", "gl"}, 24},
        {{"texmtx/prims", "soft"}, 20},   {{"texmtx/prims", "gl"}, 20},
        {{"texmtx/source", "soft"}, 84},  {{"texmtx/source", "gl"}, 84},
        // screenshot tests: one checkpoint per row of the 480x272 frame (screenshot.h)
        {{"vertices/colors", "soft"}, 272},           {{"vertices/colors", "gl"}, 272},
        {{"primitives/triangles", "soft"}, 272},      {{"primitives/triangles", "gl"}, 272},
        {{"primitives/trianglestrip", "soft"}, 272},  {{"primitives/trianglestrip", "gl"}, 272},
        {{"primitives/trianglefan", "soft"}, 272},    {{"primitives/trianglefan", "gl"}, 272},
        {{"primitives/rectangles", "soft"}, 272},     {{"primitives/rectangles", "gl"}, 272},
        {{"primitives/points", "soft"}, 272},         {{"primitives/points", "gl"}, 272},
        {{"primitives/indices", "soft"}, 272},        {{"primitives/indices", "gl"}, 272},
        {{"primitives/invalidprim", "soft"}, 272},    {{"primitives/invalidprim", "gl"}, 272},
        // triangles sample at the pixel centre (AccuracyProfile::pspTriangleSampleCentre)
        {{"primitives/continue", "soft"}, 272},       {{"primitives/continue", "gl"}, 272},
        // lines sampled at pixel centres (AccuracyProfile::pspLineCentres)
        {{"primitives/lines", "soft"}, 272},          {{"primitives/lines", "gl"}, 272},
        {{"primitives/linestrip", "soft"}, 272},      {{"primitives/linestrip", "gl"}, 272},
        // Gouraud colours stepped by gradient planes (AccuracyProfile::pspColourGradients)
        {{"primitives/immediate", "soft"}, 272},      {{"primitives/immediate", "gl"}, 272},
        {{"vertices/morph", "soft"}, 272},            {{"vertices/morph", "gl"}, 272},
        {{"vertices/texcoords", "soft"}, 272},        {{"vertices/texcoords", "gl"}, 272},
        {{"commands/material", "soft"}, 272},         {{"commands/material", "gl"}, 272},
        // of 272: patch colours with pspColourGradients, pspPatchColourRoundUp and pspLineCentres;
        // the point patch and a step off on some rows (docs/conformance.md)
        {{"primitives/bezier", "soft"}, 254},         {{"primitives/bezier", "gl"}, 254},
        {{"primitives/spline", "soft"}, 239},         {{"primitives/spline", "gl"}, 239},
        {{"filtering/mipmaplinear", "soft"}, 530}, {{"filtering/mipmaplinear", "gl"}, 530},
        {{"rendertarget/copy", "soft"}, 2720},     {{"rendertarget/copy", "gl"}, 2720},
        {{"textures/size", "soft"}, 1024}, {{"textures/size", "gl"}, 1024},
    };
    auto it = kFloors.find({test, backend});
    return it == kFloors.end() ? 0 : it->second;
}

INSTANTIATE_TEST_SUITE_P(Backends, Conformance, ::testing::Values(std::string("soft"), std::string("gl")), backendName);

}  // namespace ge::conformance
