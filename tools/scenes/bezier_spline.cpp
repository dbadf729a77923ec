// SPDX-License-Identifier: MIT
// make_scenes Scene 3: bezier_spline (docs/scenes.md).
#include "tools/scenes/scene_kit.h"
#include "tools/scenes/scenes.h"

namespace ge::scenes {

void sceneBezierSpline(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(16, 16, 24), 0);

    const Mat4 proj = sceneProjection();
    const Mat4 view = lookAt({0.f, 2.6f, 3.9f}, {0.f, 0.1f, 0.2f}, {0.f, 1.f, 0.f});
    b.setMatrix(GeMatrix::Proj, proj.m);
    b.setMatrix(GeMatrix::View, view.m);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);

    b.enable(GE_CMD_LTE, true);
    b.ambient(rgba(50, 50, 60));
    b.materialAmbient(rgba(255, 255, 255));
    b.materialDiffuse(rgba(255, 255, 255));
    b.materialSpecular(rgba(255, 255, 255));
    b.specularPower(12.f);
    b.lightMode(false);
    const float dirPos[3] = {0.3f, 1.f, 0.6f};
    b.light(0, 0, 1, dirPos);
    b.lightColor(0, LIGHT_AMBIENT, 0);
    b.lightColor(0, LIGHT_DIFFUSE, rgba(220, 215, 200));
    b.lightColor(0, LIGHT_SPECULAR, rgba(120, 120, 120));
    const float pointPos[3] = {0.f, 1.2f, 1.8f};
    b.light(1, 1, 0, pointPos);
    b.lightColor(1, LIGHT_AMBIENT, 0);
    b.lightColor(1, LIGHT_DIFFUSE, rgba(80, 120, 255));
    b.lightAtt(1, 0.5f, 0.4f, 0.f);
    b.enable(GE_CMD_LE0, true);
    b.enable(GE_CMD_LE0 + 1, true);
    b.enable(GE_CMD_LE0 + 2, false);
    b.enable(GE_CMD_LE0 + 3, false);

    b.enable(GE_CMD_TME, true);
    b.texFunc(0, false);
    b.texMode(GE_TFMT_8888, 0, false);
    placeTexture(b, 0, bytes32(checker(32, 32, 4, rgba(250, 250, 250), rgba(200, 70, 50))), 32, 32, 32);
    b.texFilter(1, 1);
    b.texWrap(false, false);
    b.texLevelMode(1, 0.f);
    b.patchPrim(0);
    b.patchFace(false);

    // ---- Bezier: 7×4 control points = 2×1 patches, UV in the vertices, no normals (generated) ----
    {
        std::vector<BuildVertex> cp;
        for (u32 j = 0; j < 4; ++j)
            for (u32 i = 0; i < 7; ++i) {
                BuildVertex p;
                p.x = -2.6f + 2.2f * float(i) / 6.f;
                p.z = -1.2f + 2.4f * float(j) / 3.f;
                p.y = 0.6f * std::sin(float(i) * 1.3f) * std::cos(float(j) * 1.1f) + 0.2f;
                p.u = 2.f * float(i) / 6.f;
                p.v = float(j) / 3.f;
                cp.push_back(p);
            }
        const u32 vtype = vt::TC_F | vt::POS_F;
        auto data = packVertices(vtype, cp.data(), u32(cp.size()));
        const u32 addr = b.place(data.data(), u32(data.size()), 4);
        b.patchDivide(10, 8);
        b.setMatrix(GeMatrix::World, identity().m);
        b.patchFace(true);  // generated normals towards +Y (the light) for this control-point order
        b.drawBezier(vtype, 7, 4, 0, addr);
        b.patchFace(false);
    }

    // ---- Spline A: 6×5 control points, knots OPEN/OPEN in U, CLOSE/CLOSE in V, vertex colours
    //      and normals, 8-bit indices, generated texture coordinates scaled by SU/SV ----
    {
        std::vector<BuildVertex> cp;
        for (u32 j = 0; j < 5; ++j)
            for (u32 i = 0; i < 6; ++i) {
                BuildVertex p;
                p.x = 0.3f + 2.4f * float(i) / 5.f;
                p.z = -1.4f + 2.8f * float(j) / 4.f;
                p.y = 0.5f * std::cos(float(i) * 1.7f + float(j));
                p.nx = -0.3f * std::sin(float(i));
                p.ny = 1.f;
                p.nz = 0.2f;
                p.color = hue(i + j * 2, 10);
                cp.push_back(p);
            }
        // Indices walk the control points in reverse row order, to make the index path matter.
        std::vector<u8> idx;
        for (u32 j = 0; j < 5; ++j)
            for (u32 i = 0; i < 6; ++i) idx.push_back(u8((4 - j) * 6 + i));
        const u32 vtype = vt::COL_8888 | vt::NRM_F | vt::POS_F | vt::IDX_8;
        auto data = packVertices(vtype, cp.data(), u32(cp.size()));
        const u32 vaddr = b.place(data.data(), u32(data.size()), 4);
        const u32 iaddr = b.place(idx.data(), u32(idx.size()), 4);
        b.colorMaterial(3);
        b.texScale(0.5f, 0.5f);
        b.patchDivide(6, 12);
        b.drawSpline(vtype, 6, 5, 3, 0, iaddr, vaddr);
        b.colorMaterial(0);
        b.texScale(1, 1);
    }

    // ---- Spline B: 5×4 control points, knots OPEN/CLOSE (1) in U and CLOSE/OPEN (2) in V,
    //      drawn as lines, untextured, reversed face ----
    {
        std::vector<BuildVertex> cp;
        for (u32 j = 0; j < 4; ++j)
            for (u32 i = 0; i < 5; ++i) {
                BuildVertex p;
                p.x = -1.2f + 2.4f * float(i) / 4.f;
                p.z = 1.6f + 0.8f * float(j) / 3.f;
                p.y = 0.9f + 0.3f * std::sin(float(i + j));
                cp.push_back(p);
            }
        const u32 vtype = vt::POS_F;
        auto data = packVertices(vtype, cp.data(), u32(cp.size()));
        const u32 addr = b.place(data.data(), u32(data.size()), 4);
        b.enable(GE_CMD_TME, false);
        b.patchPrim(1);
        b.patchFace(true);
        b.patchDivide(8, 4);
        b.materialAmbient(rgba(255, 240, 120));
        b.drawSpline(vtype, 5, 4, 1, 2, 0, addr);
        b.patchPrim(0);
        b.patchFace(false);
    }

    b.enable(GE_CMD_LTE, false);
    b.finish();
}

}  // namespace ge::scenes
