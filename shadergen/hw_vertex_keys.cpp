// SPDX-License-Identifier: MIT
// GL hardware mode vertex shaders: the key (canonical form, description, from GeState) and the
// uniform block (from GeState). See hw_vertex.h; the generator is hw_vertex.cpp.
#include <cstring>

#include "geometry/transform.h"
#include "shadergen/hw_vertex.h"

namespace ge::shadergen {

namespace {

u32 vtypeOf(const HwVsKey& k) {
    const u32 wc = k.weights ? u32(k.weightCount ? k.weightCount : 1) : 1;
    const u32 mc = k.morphCount ? k.morphCount : 1;
    return u32(k.tc & 3) | u32(k.col & 7) << 2 | u32(k.nrm & 3) << 5 | u32(k.pos & 3) << 7 | u32(k.weights & 3) << 9 |
           (wc - 1) << 14 | (mc - 1) << 18;
}

}  // namespace

void hwTriangleList(u8 primKind, const u32* seq, u32 count, u32 base, std::vector<u32>& indices,
                    std::vector<u8>& ringIds) {
    if (primKind == 0) {
        for (u32 i = 0; i + 3 <= count; i += 3)
            indices.insert(indices.end(), {seq[i] + base, seq[i + 1] + base, seq[i + 2] + base});
        return;
    }
    for (u32 i = 0; i + 3 <= count; ++i) {
        const u32 a = primKind == 2 ? seq[0] : seq[i + (i & 1)], b = primKind == 2 ? seq[i + 1] : seq[i + 1 - (i & 1)];
        indices.insert(indices.end(), {a + base, b + base, seq[i + 2] + base});
        ringIds.push_back(u8(i % 6));
    }
}

u32 hwVsStride(const HwVsKey& k) {
    return u32(VertexLayout::fromVtype(vtypeOf(k)).size) * u32(k.morphCount ? k.morphCount : 1);
}

void canonicalize(HwVsKey& k) {
    auto b = [](u8& v) { v = v ? 1 : 0; };
    k.tc &= 3;
    k.col &= 7;
    if (k.col < 4) k.col = 0;  // CT 1–3: no bytes and no colour (docs/ge-rules.md §5.1)
    k.nrm &= 3;
    k.pos &= 3;
    k.weights &= 3;
    k.weightCount = k.weights ? u8(k.weightCount < 1 ? 1 : (k.weightCount > 8 ? 8 : k.weightCount)) : 0;
    k.morphCount = u8(k.morphCount < 1 ? 1 : (k.morphCount > 8 ? 8 : k.morphCount));
    std::memset(k.reserved, 0, sizeof k.reserved);
    // The primitive kind only changes the geometry shader (its ring order, hw_geometry.cpp).
    if (k.primKind > 2) k.primKind = 0;
    k.sampleCentre = k.sampleCentre ? 1 : 0;
    if (k.pos == 0) {
        // No position: every vertex is dropped (ge-rules.md §8.11); only the layout remains meaningful (and
        // which outputs the vertex shader has).
        HwVsKey c;
        c.tc = k.tc, c.col = k.col, c.nrm = k.nrm, c.weights = k.weights, c.weightCount = k.weightCount;
        c.morphCount = k.morphCount;
        k = c;
        return;
    }
    b(k.lighting);
    b(k.ambientFromVertex);
    b(k.diffuseFromVertex);
    b(k.specularFromVertex);
    b(k.separateSpecular);
    b(k.texture);
    b(k.fog);
    b(k.normalReverse);
    b(k.clipEnable);
    b(k.flatShade);
    b(k.through);
    if (k.through) {
        // Through mode: no transform, lighting, texture mapping, fog or clipping (transformVertex's
        // through branch), so none of their settings changes the shaders; the layout fields stay.
        k.lighting = 0;
        for (int n = 0; n < 4; ++n) k.lightType[n] = 0, k.lightComp[n] = 0;
        k.ambientFromVertex = k.diffuseFromVertex = k.specularFromVertex = k.separateSpecular = 0;
        k.texMap = 0;
        k.projSource = 0;
        k.fog = 0;
        k.normalReverse = 0;
        k.clipEnable = 0;
        return;
    }
    bool anyLight = false, anySpecular = false;
    for (int n = 0; n < 4; ++n) {
        if (!k.lighting || k.lightType[n] == 0) {
            k.lightType[n] = 0, k.lightComp[n] = 0;
            continue;
        }
        if (k.lightType[n] > 3) k.lightType[n] = 3;
        if (k.lightComp[n] > 2) k.lightComp[n] = 0;  // LTYPE comp 3 behaves as 0 (ge-rules.md §3.6)
        anyLight = true;
        anySpecular |= k.lightComp[n] == 1;
    }
    // Material update flags act only with a vertex colour (ge-rules.md §3.6); diffuse and specular only when
    // a light uses them. Without lighting none of them, nor LMODE, matters.
    if (!k.lighting || k.col == 0) k.ambientFromVertex = k.diffuseFromVertex = k.specularFromVertex = 0;
    if (!anyLight) k.diffuseFromVertex = 0;
    if (!anySpecular) k.specularFromVertex = 0, k.separateSpecular = 0;
    if (!k.texture) k.texMap = 0;
    if (k.texMap > 2) k.texMap = 0;  // TMAP mode 3 behaves as UV (ge-rules.md §3.8)
    k.projSource = k.texMap == 1 ? u8(k.projSource & 3) : 0;
    // NREV flips a normal read from the vertex; it matters where that normal is used.
    const bool normalUsed = k.lighting || k.texMap == 2 || (k.texMap == 1 && k.projSource >= 2);
    if (k.nrm == 0 || !normalUsed) k.normalReverse = 0;
}

std::string describe(const HwVsKey& k) {
    static const char* const kFmt[4] = {"-", "8", "16", "f"};
    static const char* const kCol[8] = {"-", "-", "-", "-", "5650", "5551", "4444", "8888"};
    static const char* const kType[4] = {"-", "dir", "point", "spot"};
    static const char* const kComp[3] = {"ad", "ads", "pd"};
    static const char* const kSrc[4] = {"pos", "uv", "nnrm", "nrm"};
    std::string s = "HWVS";
    if (k.through) s += " through";
    s += " tc=";
    s += kFmt[k.tc & 3];
    s += " col=";
    s += kCol[k.col & 7];
    s += " nrm=";
    s += kFmt[k.nrm & 3];
    s += " pos=";
    s += kFmt[k.pos & 3];
    if (k.weights) {
        s += " w=";
        s += kFmt[k.weights & 3];
        s += 'x';
        s += std::to_string(k.weightCount);
    }
    if (k.morphCount > 1) {
        s += " morph=";
        s += std::to_string(k.morphCount);
    }
    if (k.lighting) {
        s += " light=";
        for (int n = 0; n < 4; ++n) {
            if (n) s += ',';
            s += kType[k.lightType[n] & 3];
            if (k.lightType[n]) {
                s += ':';
                s += kComp[k.lightComp[n] > 2 ? 0 : k.lightComp[n]];
            }
        }
        if (k.ambientFromVertex || k.diffuseFromVertex || k.specularFromVertex) {
            s += " matv=";
            if (k.ambientFromVertex) s += 'a';
            if (k.diffuseFromVertex) s += 'd';
            if (k.specularFromVertex) s += 's';
        }
        if (k.separateSpecular) s += " lmode=sep";
    }
    if (k.texture) {
        s += " tex=";
        if (k.texMap == 1) {
            s += "proj:";
            s += kSrc[k.projSource & 3];
        } else {
            s += k.texMap == 2 ? "shade" : "uv";
        }
    }
    if (k.fog) s += " fog";
    if (k.normalReverse) s += " nrev";
    if (k.clipEnable) s += " cle";
    s += k.flatShade ? " flat" : " gouraud";
    static const char* const kPrim[3] = {"list", "strip", "fan"};
    s += " gs=";
    s += kPrim[k.primKind > 2 ? 0 : k.primKind];
    if (k.sampleCentre) s += " centre";
    return s;
}

HwVsKey hwVsKeyFromState(const GeState& st, bool texture, bool fog) {
    return hwVsKeyFromState(st, st.op(GE_CMD_VTYPE), texture, fog);
}

HwVsKey hwVsKeyFromState(const GeState& st, u32 vtype, bool texture, bool fog) {
    HwVsKey k;
    // CMD_VTYPE's fields (ge-rules.md §5.1).
    k.tc = u8(vtype & 3);
    k.col = u8((vtype >> 2) & 7);
    k.nrm = u8((vtype >> 5) & 3);
    k.pos = u8((vtype >> 7) & 3);
    k.weights = u8((vtype >> 9) & 3);
    k.weightCount = u8(((vtype >> 14) & 7) + 1);
    k.morphCount = u8(((vtype >> 18) & 7) + 1);
    k.lighting = st.LTE_on();
    for (int n = 0; n < 4; ++n) {
        if (!st.LE_on(n)) continue;
        const u32 type = st.LTYPE_type(n);  // 0 directional, 1 point, 2 and 3 spot (ge-rules.md §3.6)
        k.lightType[n] = u8(type == 0 ? 1 : (type == 1 ? 2 : 3));
        k.lightComp[n] = u8(st.LTYPE_comp(n));
    }
    k.ambientFromVertex = st.MATERIAL_ambient();
    k.diffuseFromVertex = st.MATERIAL_diffuse();
    k.specularFromVertex = st.MATERIAL_specular();
    k.separateSpecular = st.LMODE_separate();
    k.texture = texture;
    k.texMap = u8(st.TMAP_mode());
    k.projSource = u8(st.TMAP_proj());
    k.fog = fog;
    k.normalReverse = st.NREV_on();
    k.clipEnable = st.CLE_on();
    // Flat in clear mode too, as geo::rasterParamsFor (the fragment key must agree).
    k.flatShade = !(st.SHADE_gouraud() && !st.isClearMode());
    k.through = (vtype >> 23) & 1;
    canonicalize(k);
    return k;
}

void hwVsUniformsFromState(const GeState& st, HwVsUniforms& u, const geo::AccuracyProfile& acc) {
    hwVsUniformsFromState(st, st.op(GE_CMD_VTYPE), u, acc, nullptr);
}

void hwVsUniformsFromState(const GeState& st, u32 vtypeIn, HwVsUniforms& u, const geo::AccuracyProfile& acc,
                           geo::MatrixFold* fold) {
    std::memset(static_cast<void*>(&u), 0, sizeof u);
    // The transform-mode state of this VTYPE, computed by the code the CPU path runs.
    const u32 vtype = vtypeIn & ~(1u << 23);
    const bool hasColor = ((vtype >> 2) & 7) >= 4, hasNormal = ((vtype >> 5) & 3) != 0;
    geo::AccuracyProfile lightingOnly;  // the GPU normalises exactly (see hw_vertex.h)
    lightingOnly.spotDirectionDivide = acc.spotDirectionDivide;
    const geo::TransformState ts = geo::makeTransformState(st, vtype, hasColor, hasNormal, fold, lightingOnly);
    std::memcpy(u.worldViewProj, ts.worldViewProj, sizeof u.worldViewProj);
    std::memcpy(u.viewProj, ts.viewProj, sizeof u.viewProj);
    std::memcpy(u.world, ts.world, sizeof u.world);
    std::memcpy(u.view, ts.view, sizeof u.view);
    std::memcpy(u.tgen, ts.tgen, sizeof u.tgen);
    std::memcpy(u.bones, st.bone, sizeof u.bones);
    for (int i = 0; i < 8; ++i) u.morph[i] = st.WEIGHT_value(i);
    u.viewport[0] = ts.sx, u.viewport[1] = ts.sy, u.viewport[2] = ts.sz;
    u.viewport[3] = ts.tx, u.viewport[4] = ts.ty, u.viewport[5] = ts.tz;
    u.offset16[0] = ts.offX16, u.offset16[1] = ts.offY16;
    u.uvScale[0] = ts.su, u.uvScale[1] = ts.sv, u.uvScale[2] = ts.tu, u.uvScale[3] = ts.tv;
    u.fog[0] = ts.fogEnd, u.fog[1] = ts.fogSlope;
    u.fogFixed[0] = ts.fog ? ts.fogFixed : -1;
    u.matColor[0] = (st.MAC_rgb() & 0xFFFFFF) | (st.MAA_alpha() & 0xFF) << 24;
    // GE culling as geometry/draw_front_end.cpp (none in clear mode).
    u.cull[0] = st.BCE_on() && !st.isClearMode() ? 1 : 0;
    u.cull[1] = st.CULL_ccw() ? 1 : 0;
    // Through mode's texel scaling (makeTransformState computes it in either mode).
    u.texScale[0] = ts.invTexW0, u.texScale[1] = ts.invTexH0;
    for (int k = 0; k < 2; ++k)
        for (int i = 0; i < 3; ++i) u.shadeLight[4 * k + i] = ts.shadeLight[k][i];
    if (!ts.lighting) return;
    const geo::LightingState& ls = ts.light;
    for (int i = 0; i < 3; ++i) {
        u.emissive[i] = ls.emissive[i];
        u.matDiffuse[i] = ls.matDiffuse[i];
        u.matSpecular[i] = ls.matSpecular[i];
    }
    for (int i = 0; i < 4; ++i) u.globalAmbient[i] = ls.globalAmbient[i], u.matAmbient[i] = ls.matAmbient[i];
    u.specularExp[0] = ls.specularExp;
    for (int n = 0; n < 4; ++n) {
        const geo::LightSource& L = ls.lights[n];
        for (int i = 0; i < 3; ++i) {
            u.lightPos[4 * n + i] = L.pos[i];
            u.lightAtt[4 * n + i] = L.att[i];
            u.lightSpotDir[4 * n + i] = L.spotDir[i];
            u.lightAmbient[4 * n + i] = L.ambient[i];
            u.lightDiffuse[4 * n + i] = L.diffuse[i];
            u.lightSpecular[4 * n + i] = L.specularColor[i];
        }
        u.lightSpot[4 * n] = L.spotExp;
        u.lightSpot[4 * n + 1] = L.spotCutoff;
        u.lightSpot[4 * n + 2] = L.spotForced;
    }
}

}  // namespace ge::shadergen
