// SPDX-License-Identifier: MIT
// make_scenes Scene 1: lit_textured_skinned (docs/scenes.md).
#include "tools/scenes/scene_kit.h"
#include "tools/scenes/scenes.h"

namespace ge::scenes {

namespace {

// Floor: 16×16 grid, y = 0, float UV/normal/position, 16-bit indices.
void drawFloor(ListBuilder& b) {
    std::vector<u32> l0 = checker(64, 64, 8, rgba(235, 225, 200), rgba(90, 110, 140));
    for (u32 y = 0; y < 64; ++y)  // a thin diagonal accent so the mip levels differ visibly
        for (u32 x = 0; x < 64; ++x)
            if (((x + y) & 31) < 2) l0[y * 64 + x] = rgba(200, 60, 40);
    std::vector<u32> l1 = halve(l0, 64, 64), l2 = halve(l1, 32, 32);
    b.texMode(GE_TFMT_8888, 2, false);
    placeTexture(b, 0, bytes32(l0), 64, 64, 64);
    placeTexture(b, 1, bytes32(l1), 32, 32, 32);
    placeTexture(b, 2, bytes32(l2), 16, 16, 16);
    b.texFilter(7, 1);  // LINEAR_MIPMAP_LINEAR / LINEAR
    b.texLevelMode(0, 0.f);

    const u32 n = 16;
    std::vector<BuildVertex> v;
    for (u32 j = 0; j <= n; ++j)
        for (u32 i = 0; i <= n; ++i) {
            BuildVertex p;
            p.x = -3.5f + 7.f * float(i) / n;
            p.z = -4.f + 7.f * float(j) / n;
            p.y = 0.f;
            p.nx = 0;
            p.ny = 1;
            p.nz = 0;
            p.u = 4.f * float(i) / n;
            p.v = 4.f * float(j) / n;
            v.push_back(p);
        }
    const u32 vtype = vt::TC_F | vt::NRM_F | vt::POS_F | vt::IDX_16;
    auto data = packVertices(vtype, v.data(), u32(v.size()));
    auto idx = gridIndices(n, n);
    b.setMatrix(GeMatrix::World, identity().m);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
}

// Skinned arm: a cylinder on two bones, u8 weights, 16-bit UV and normal.
void drawSkinnedArm(ListBuilder& b) {
    // Texture: swizzled 5650 stripes, single level, bilinear.
    std::vector<u16> tex(32 * 32);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) {
            u32 c = ((y / 4) & 1) ? rgba(250, 200, 60) : rgba(60, 120, 230);
            if ((x / 8) & 1) c = rgba(((c & 255) * 3) / 4, (((c >> 8) & 255) * 3) / 4, (((c >> 16) & 255) * 3) / 4);
            tex[y * 32 + x] = to5650(c);
        }
    b.texMode(GE_TFMT_5650, 0, true);
    placeTexture(b, 0, swizzle(bytes16(tex), 64, 32), 32, 32, 32);
    b.texFilter(1, 1);

    // Bone 0 holds the lower half, bone 1 bends the upper half around the joint at y = 1.
    const Mat4 bone0 = identity();
    const Mat4 bone1 = mul(translate(0, 1.f, 0), mul(rotZ(0.75f), translate(0, -1.f, 0)));
    float m[12];
    to3x4(bone0, m);
    b.setBoneMatrix(0, m);
    to3x4(bone1, m);
    b.setBoneMatrix(1, m);

    const u32 seg = 12, rings = 10;
    std::vector<BuildVertex> v;
    for (u32 r = 0; r <= rings; ++r)
        for (u32 s = 0; s <= seg; ++s) {
            float a = 2.f * kPi * float(s) / seg, y = 2.f * float(r) / rings;
            BuildVertex p;
            p.x = 0.28f * std::cos(a);
            p.z = 0.28f * std::sin(a);
            p.y = y;
            p.nx = std::cos(a);
            p.ny = 0;
            p.nz = std::sin(a);
            p.u = float(s) / seg;
            p.v = float(r) / rings * 1.5f;
            float w1 = std::clamp((y - 0.7f) / 0.6f, 0.f, 1.f);
            p.w[0] = 1.f - w1;
            p.w[1] = w1;
            v.push_back(p);
        }
    const u32 vtype = vt::W_8 | vt::weights(2) | vt::TC_16 | vt::NRM_16 | vt::POS_F | vt::IDX_16;
    auto data = packVertices(vtype, v.data(), u32(v.size()));
    auto idx = gridIndices(seg, rings);
    // World: stand the arm slightly left of centre, turned towards the camera.
    b.setMatrix(GeMatrix::World, mul(translate(-0.6f, 0.f, 0.3f), rotY(0.4f)).m);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
}

// A second skinned object with float weights: a bent box on the right, vertex colours.
void drawBentBox(ListBuilder& b) {
    b.enable(GE_CMD_TME, false);
    b.colorMaterial(3);  // ambient + diffuse from the vertex colour
    const Mat4 bone0 = identity();
    const Mat4 bone1 = mul(translate(0, 0.6f, 0), mul(rotX(-0.6f), translate(0, -0.6f, 0)));
    float m[12];
    to3x4(bone0, m);
    b.setBoneMatrix(0, m);
    to3x4(bone1, m);
    b.setBoneMatrix(1, m);

    // Box from y 0..1.2 as 6 faces × 2×2 quads, flat normals per face.
    std::vector<BuildVertex> v;
    std::vector<u16> idx;
    const Vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const u32 faceCol[6] = {rgba(240, 80, 80), rgba(80, 240, 80), rgba(240, 240, 90),
                            rgba(90, 90, 240), rgba(240, 140, 40), rgba(200, 90, 220)};
    for (int f = 0; f < 6; ++f) {
        Vec3 nrm = normals[f];
        Vec3 t1 = std::fabs(nrm.y) > 0.5f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        Vec3 t2 = cross(nrm, t1);
        u16 base = u16(v.size());
        for (int j = 0; j <= 2; ++j)
            for (int i = 0; i <= 2; ++i) {
                float s = float(i) - 1.f, t = float(j) - 1.f;
                BuildVertex p;
                p.x = 0.3f * (nrm.x + s * t1.x + t * t2.x);
                p.y = 0.6f + 0.6f * (nrm.y + s * t1.y + t * t2.y);
                p.z = 0.3f * (nrm.z + s * t1.z + t * t2.z);
                p.nx = nrm.x;
                p.ny = nrm.y;
                p.nz = nrm.z;
                p.color = faceCol[f];
                float w1 = std::clamp(p.y / 1.2f, 0.f, 1.f);
                p.w[0] = 1.f - w1;
                p.w[1] = w1;
                v.push_back(p);
            }
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                u16 a = u16(base + j * 3 + i);
                idx.insert(idx.end(), {a, u16(a + 3), u16(a + 1), u16(a + 1), u16(a + 3), u16(a + 4)});
            }
    }
    const u32 vtype = vt::W_F | vt::weights(2) | vt::COL_8888 | vt::NRM_F | vt::POS_F | vt::IDX_16;
    auto data = packVertices(vtype, v.data(), u32(v.size()));
    b.setMatrix(GeMatrix::World, mul(translate(1.1f, 0.f, 0.4f), rotY(-0.5f)).m);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
}

}  // namespace

void sceneLitTexturedSkinned(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(24, 32, 48), 0);

    const Mat4 proj = sceneProjection();
    const Mat4 view = lookAt({0.f, 2.2f, 5.5f}, {0.f, 0.7f, 0.f}, {0.f, 1.f, 0.f});
    b.setMatrix(GeMatrix::Proj, proj.m);
    b.setMatrix(GeMatrix::View, view.m);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);  // GEQUAL: depthRange(65535, 0) puts near objects at high Z
    b.depthMask(false);

    // Lighting: global ambient, a directional light with specular, a red point light with
    // attenuation, and a cyan spot light aimed at the floor.
    b.enable(GE_CMD_LTE, true);
    b.ambient(rgba(40, 40, 48));
    b.materialAmbient(rgba(255, 255, 255));
    b.materialDiffuse(rgba(230, 230, 230));
    b.materialSpecular(rgba(255, 255, 255));
    b.materialEmissive(0);
    b.colorMaterial(0);
    b.specularPower(20.f);
    b.lightMode(true);  // separate specular: goes to the secondary colour, added after texturing

    const float dirPos[3] = {-0.4f, 1.f, 0.7f};
    b.light(0, 0, 1, dirPos);
    b.lightColor(0, LIGHT_AMBIENT, rgba(0, 0, 0));
    b.lightColor(0, LIGHT_DIFFUSE, rgba(150, 150, 140));
    b.lightColor(0, LIGHT_SPECULAR, rgba(255, 255, 255));

    const float pointPos[3] = {1.6f, 0.9f, 1.2f};
    b.light(1, 1, 1, pointPos);
    b.lightColor(1, LIGHT_AMBIENT, rgba(20, 0, 0));
    b.lightColor(1, LIGHT_DIFFUSE, rgba(255, 60, 40));
    b.lightColor(1, LIGHT_SPECULAR, rgba(255, 160, 120));
    b.lightAtt(1, 0.6f, 0.3f, 0.15f);

    // LD points from the lit floor back toward the light (a PSP's sign, pspautotests
    // gpu/commands/light: cos = LD·(light − vertex); the manual's 9-4 reads the other way).
    const float spotPos[3] = {-1.6f, 3.f, 0.6f};
    const float spotDir[3] = {-0.35f, 1.f, 0.15f};
    b.light(2, 2, 0, spotPos);
    b.lightColor(2, LIGHT_AMBIENT, rgba(0, 0, 0));
    b.lightColor(2, LIGHT_DIFFUSE, rgba(40, 220, 255));
    b.lightColor(2, LIGHT_SPECULAR, rgba(0, 0, 0));
    b.lightAtt(2, 1.f, 0.f, 0.f);
    b.lightSpot(2, spotDir, 6.f, 0.82f);
    for (u32 n = 0; n < 3; ++n) b.enable(u8(GE_CMD_LE0 + n), true);
    b.enable(GE_CMD_LE0 + 3, false);

    // Texturing: modulate, trilinear mip-mapped floor texture (3 levels).
    b.enable(GE_CMD_TME, true);
    b.texFunc(0, false);
    b.texWrap(false, false);

    drawFloor(b);  // floor: 16×16 grid, y = 0, float UV/normal/position, 16-bit indices

    drawSkinnedArm(b);  // skinned arm: a cylinder on two bones, u8 weights, 16-bit UV and normal

    drawBentBox(b);  // a second skinned object with float weights: a bent box on the right, vertex colours

    b.enable(GE_CMD_LTE, false);
    b.finish();
}

}  // namespace ge::scenes
