// SPDX-License-Identifier: MIT
// make_scenes Scene 5: render_to_texture (docs/scenes.md).
#include "tools/scenes/scene_kit.h"
#include "tools/scenes/scenes.h"

namespace ge::scenes {

void sceneRenderToTexture(ListBuilder& b) {
    standardSetup(b);

    // ---- pass 1: a lit, vertex-coloured cube into an 8888 off-screen buffer (128×128) ----
    b.drawBuffer(GE_FORMAT_8888, kOff0, 128);
    b.depthBuffer(kZb, 128);
    b.offset(2048 - 64, 2048 - 64);
    b.viewport(2048, 2048, 128, 128);
    b.scissor(0, 0, 128, 128);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, rgba(20, 40, 70), 0);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);
    b.setMatrix(GeMatrix::Proj, perspective(50.f, 1.f, 0.5f, 20.f).m);
    b.setMatrix(GeMatrix::View, lookAt({2.2f, 1.8f, 2.6f}, {0, 0, 0}, {0, 1, 0}).m);
    b.setMatrix(GeMatrix::World, rotY(0.3f).m);
    b.enable(GE_CMD_LTE, true);
    b.ambient(rgba(60, 60, 60));
    b.colorMaterial(3);
    b.materialSpecular(0);
    const float lp[3] = {0.5f, 1.f, 0.8f};
    b.light(0, 0, 0, lp);
    b.lightColor(0, LIGHT_AMBIENT | LIGHT_SPECULAR, 0);
    b.lightColor(0, LIGHT_DIFFUSE, rgba(230, 230, 230));
    b.enable(GE_CMD_LE0, true);
    for (u32 n = 1; n < 4; ++n) b.enable(u8(GE_CMD_LE0 + n), false);
    {
        // 24 vertices (4 per face), 16-bit colour 5650 per face, 8-bit normals, 16-bit positions.
        const Vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        std::vector<BuildVertex> v;
        std::vector<u16> idx;
        for (int f = 0; f < 6; ++f) {
            Vec3 nrm = normals[f];
            Vec3 t1 = std::fabs(nrm.y) > 0.5f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            Vec3 t2 = cross(nrm, t1);
            u16 base = u16(v.size());
            for (int k = 0; k < 4; ++k) {
                float s = (k & 1) ? 1.f : -1.f, t = (k & 2) ? 1.f : -1.f;
                BuildVertex p;
                p.x = 0.7f * (nrm.x + s * t1.x + t * t2.x);
                p.y = 0.7f * (nrm.y + s * t1.y + t * t2.y);
                p.z = 0.7f * (nrm.z + s * t1.z + t * t2.z);
                p.nx = nrm.x;
                p.ny = nrm.y;
                p.nz = nrm.z;
                p.color = hue(u32(f * 2 + (k == 3)), 12);
                v.push_back(p);
            }
            idx.insert(idx.end(), {base, u16(base + 1), u16(base + 2), u16(base + 1), u16(base + 3), u16(base + 2)});
        }
        const u32 vtype = vt::COL_5650 | vt::NRM_8 | vt::POS_16 | vt::IDX_16;
        auto data = packVertices(vtype, v.data(), u32(v.size()));
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
    }
    b.enable(GE_CMD_LTE, false);
    b.enable(GE_CMD_ZTE, false);

    // ---- pass 2: a 5650 off-screen buffer (64×64, stride 64) with a pattern whose raw 16-bit
    //      values are later used as CLUT16 indices ----
    b.drawBuffer(GE_FORMAT_565, kOff1, 64);
    b.scissor(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, rgba(0, 0, 0), 0);
    for (int i = 0; i < 8; ++i) rect(b, i * 8, 0, 8, 64, rgba(u32(i) * 36, 0, 0));  // R 5 bits: index low bits
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 10, 10, rgba(255, 255, 255), rgba(255, 255, 255));  // additive
    for (int j = 0; j < 8; ++j) rect(b, 0, j * 8, 64, 8, rgba(0, u32(j) * 36, 0));    // G adds upper bits
    b.enable(GE_CMD_ABE, false);

    // ---- main pass ----
    b.drawBuffer(GE_FORMAT_8888, kFb, 512);
    b.depthBuffer(kZb, 512);
    b.offset(2048 - 240, 2048 - 136);
    b.viewport(2048, 2048, 480, 272);
    b.scissor(0, 0, 480, 272);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, rgba(40, 40, 40), 0);
    b.texSync();
    b.texFlush();

    // A perspective quad textured with the rendered 8888 buffer (bilinear).
    b.setMatrix(GeMatrix::Proj, sceneProjection().m);
    b.setMatrix(GeMatrix::View, lookAt({0, 0, 4.f}, {0, 0, 0}, {0, 1, 0}).m);
    b.setMatrix(GeMatrix::World, mul(translate(-1.3f, 0.2f, 0), rotY(0.5f)).m);
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, 0x04000000 + kOff0, 128, 128, 128);
    b.texFunc(3, false);
    b.texFilter(1, 1);
    b.texWrap(true, true);
    b.texLevelMode(1, 0.f);
    {
        BuildVertex v[4];
        const float xs[4] = {-1, 1, -1, 1}, ys[4] = {1, 1, -1, -1};
        for (int i = 0; i < 4; ++i) {
            v[i].x = xs[i];
            v[i].y = ys[i];
            v[i].z = 0;
            v[i].u = (xs[i] + 1) / 2;
            v[i].v = (1 - ys[i]) / 2;
        }
        const u32 vtype = vt::TC_F | vt::POS_F;
        auto data = packVertices(vtype, v, 4);
        b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 4, nullptr, data.data());
    }

    // The 5650 buffer read as CLUT16: index = (pixel >> 0) & 0xFF with an 8888 rainbow palette.
    {
        std::vector<u32> pal(256);
        for (u32 i = 0; i < 256; ++i) pal[i] = hue(i * 7, 256);
        const auto palBytes = bytes32(pal);
        const u32 palAddr = b.place(palBytes.data(), 1024, 16);
        b.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
        b.clutLoad(palAddr, 32);
        b.texMode(GE_TFMT_CLUT16, 0, false);
        b.setTexture(0, 0x04000000 + kOff1, 64, 64, 64);
        b.texFilter(0, 0);
        texRect(b, 300, 20, 128, 128, 0, 0, 64, 64);
        // And the same bytes as a plain 5650 texture.
        b.texMode(GE_TFMT_5650, 0, false);
        b.setTexture(0, 0x04000000 + kOff1, 64, 64, 64);
        texRect(b, 300, 156, 64, 64, 0, 0, 64, 64);
    }
    b.enable(GE_CMD_TME, false);

    // Block transfers: a procedural 8888 image from RAM into the frame buffer, and a VRAM→VRAM
    // copy of part of the rendered cube (the source is GE-drawn, so the dump keeps the VRAM
    // source address instead of a TRANSFERSRC copy).
    {
        std::vector<u32> img = rings(64, 64, 0);
        const auto bytes = bytes32(img);
        const u32 src = b.place(bytes.data(), u32(bytes.size()), 16);
        b.copyImage(GE_FORMAT_8888, 8, 4, 48, 40, 64, src, 400, 220, 512, 0x04000000 + kFb);
        b.copyImage(GE_FORMAT_8888, 32, 32, 64, 64, 128, 0x04000000 + kOff0, 20, 190, 512, 0x04000000 + kFb);
    }

    b.finish();
}

}  // namespace ge::scenes
