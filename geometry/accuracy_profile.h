// SPDX-License-Identifier: MIT
// The accuracy profile: one named switch per known divergence between what a PSP's GE does and
// what PPSSPP's software renderer (GPU/Software, c09e6bddaa, x86-64 build) does. Two profiles:
//   psp()    — every hardware-measured rule taken, PPSSPP's optimisation artefacts off;
//   ppsspp() — bit-compatible with PPSSPP's software renderer, artefacts included (the shared
//              frametests are its renders).
// Everything both profiles share is not here: a switch exists only where the two disagree.
// The profile enters each backend at creation (backend/factory.h BackendOptions::accuracy) and
// the code that applies a rule reads the switch it needs; nothing compares profiles. Which
// frametests and conformance checkpoints each switch moves: docs/accuracy.md "Accuracy profiles".
#pragma once
#include <cstring>

namespace ge::geo {

struct AccuracyProfile {
    // PPSSPP's implicit "alpha != 0" test: a source-alpha blend (A = As, B = 1 − As) with no
    // depth write, no effective stencil test and an off or always-true alpha test drops alpha-0
    // fragments (Rasterizer.cpp DetectStateOptimizations, OPTIMIZED_ALPHATEST_ON;
    // geometry/reference_rules.h referenceDropsZeroAlpha). The GE runs no such test (manual §8:
    // the alpha test is the ATE register's): with dithering the dither value still moves the
    // pixel. Moves Monster Hunter 3rd's HUD gradient.
    bool implicitAlphaNonZeroTest = false;
    // PPSSPP's skipped alpha test for CLUT textures whose palette is opaque (or ANDs to non-zero
    // for reference 0) and all vertex alphas full (DetectStateOptimizations,
    // OPTIMIZED_ALPHATEST_OFF_NE/GT; referenceSkipsAlphaTest). The GE tests every fragment.
    // Moves Hokuto no Ken (1.769 → 1.693 with it).
    bool clutSkipsAlphaTest = false;
    // PPSSPP's knot setup for a single spline patch open at both ends (SplineCommon.cpp
    // CalcKnots overwrites the open start's reciprocal 1 with the open end's 1/2): non-Bernstein
    // weights. The manual's knot vector (§5.2.1) gives Bezier weights (geometry/spline.cpp
    // splineSpans). Moves GachiTora's text patches (0.1875 → 0.0161 with it).
    bool splineOpenKnotQuirk = false;
    // Zero-area triangles are rasterised: PPSSPP submits each triangle in both orders and keeps
    // samples exactly on the line (TransformUnit::SendTriangle, BinManager::AddTriangle;
    // geometry/raster.cpp rasterZeroAreaTriangle). The plain reading of the GE (docs/ge-rules.md
    // §8.11) draws nothing for them. Moves Valkyria Chronicles' strip joins (0.26 → 0.057 with
    // it), Locoroco, Virtua Tennis.
    bool zeroAreaTriangles = false;
    // PPSSPP normalises the spot direction LD as v / |v| with a float length (Lighting.cpp
    // ComputeState, Vec3<float>::Normalize in Math3D.cpp): on x86 a zero or infinite LD divides
    // to the default NaN, whose sign bit is set, so the spot cosine takes 0 and the light is dark;
    // a NaN component leaves the NaN of the first NaN component. A PSP lights an LD of +∞ fully
    // (pspautotests commands/light "Spot INFINITY": 3 checkpoints; zero, −∞ and NaN agree with
    // it; geometry/lighting.cpp makeLightingState). No frametest moves.
    bool spotDirectionDivide = false;
    // Lighting's vectors normalised as PPSSPP's x86 build does (Lighting.cpp, Math3D.cpp):
    // lengths as float sums x² + (y² + z²) (Vec3<float>::Length in NormalizeOr001: the light
    // vectors, the world normal) and the half vector H multiplied by the approximate reciprocal
    // square root of (x² + y²) + z² (NormalizedOr001 with SSE4: rsqrtps after dpps). ge2gl's own
    // (the PSP's precision is not known; it passes the two light checkpoints this moves): lengths
    // summed in double, one division per component. With spotDirectionDivide it takes
    // commands/light 163 → 158 of 201, PPSSPP's count. Moves Need for Speed Carbon (0.0696 →
    // 0.0325 against its reference) and Pursuit Force UCUS98703 (0.0001 → 0.0005). PPSSPP's
    // source also normalises shade-mapping light directions and the projection-mapping normal
    // with the approximation; taking those too moved Need for Speed Carbon to 0.0952, away from
    // its reference, so they are not part of the switch (docs/accuracy.md).
    bool sseVectorArithmetic = false;
    // Transform-mode RECTANGLES reach the screen by the PSP's sprite rule: float24 viewport
    // arithmetic and the screen position rounded up to the next 1/16 pixel before OFFSETX/Y is
    // taken off (geometry/transform.cpp projectToScreen; docs/conformance.md "Sprites":
    // pspautotests filtering/nearest and linear, precision*3d, textures/size, depth/precision).
    // PPSSPP rounds sprites as any vertex (TransformUnit.cpp ClipToScreen, truncation after the
    // float offset subtraction). Moves Beam 'em up (0 → 2.43 with it), Valkyria Chronicles,
    // Frontier Gate, Need for Speed Carbon.
    bool pspSpritePosition = false;
    // RECTANGLES draws leave out the pixel whose centre lies on the far edge, odd or not
    // (pspautotests filtering/precision*2d and *3d: a 2x2 sprite from −8/16 to 1.5 draws pixel 0
    // only; geometry/raster.cpp rectangleSetup). PPSSPP's 2×2 rectangle walk draws it when it is
    // the odd pixel of a pair (Rasterizer.cpp DrawRectangle), as it still does for the strip and
    // fan quads it draws as rectangles in both profiles. No frametest moved.
    bool spriteFarEdgeExcluded = false;
    // Bilinear filtering takes the texel position (8 fraction bits) truncated toward zero, as
    // nearest filtering does (pspautotests filtering/precisionlinear2d and 3d; docs/conformance.md
    // "What fails"). PPSSPP's x86 sampler JIT rounds it to nearest, ties to even (SamplerX86.cpp
    // Jit_GetTexelCoordsQuad, CVTPS2DQ; softmodel/sampler.cpp texelFixedRound).
    bool pspBilinearTruncation = false;
    // Triangles sample pixel (x, y) at its centre (16·x + 8, 16·y + 8 in 1/16 pixel), so a centre
    // exactly on an edge goes by the top-left rule alone (pspautotests primitives/continue and
    // immediate, texmtx/uvs; docs/conformance.md "primitives"). PPSSPP's software renderer
    // samples 1/16 pixel up-left of it (Rasterizer.cpp TriangleEdge::Start, centerOff =
    // SCREEN_SCALE_FACTOR / 2 - 1; geometry/raster.h triangleSampleOffset).
    bool pspTriangleSampleCentre = false;
    // Gouraud colours (primary and secondary) are stepped from the triangle's top vertex (least
    // y, then least x) with per-pixel gradients held to 8 fraction bits, rounded toward −∞, and
    // the value at the sample point rounded down (geometry/raster.h ColourPlane): a colour that
    // falls from one vertex to the next comes out a step lower wherever the exact value is a
    // whole number, one that rises does not (pspautotests primitives/immediate: the Gouraud fan
    // from green 255 to 127 over 40 rows reads 253, 250, 246, 243 … where the exact values are
    // 253.4, 250.2, 247.0, 243.8; 248 → 272 of 272; commands/light 163 → 170; spline 183 → 190
    // with it alone). PPSSPP interpolates in float and rounds to nearest (Rasterizer.cpp
    // Interpolate, DrawTriangleSlice's prim_color/sec_color; geometry/raster.cpp
    // interpolateColor).
    bool pspColourGradients = false;
    // Colours of vertices generated by Bezier and spline patches are rounded up from the
    // evaluated sum, not to nearest (pspautotests primitives/bezier and spline: every Gouraud
    // patch row reads a step higher than the nearest-rounded vertices give; bezier 212 → 237,
    // spline 190 → 222 together with pspColourGradients). PPSSPP rounds to nearest
    // (SplineCommon.cpp: the tessellated colour converted by Vec4<float>::ToRGBA, Math3D.h,
    // cvtps2dq; geometry/spline.cpp).
    bool pspPatchColourRoundUp = false;
    // Lines are sampled at pixel centres along their longer axis: the pixels whose centres lie in
    // [start, end) are drawn, the other coordinate taken at that centre, and each pixel's Gouraud
    // colour is the colour at the centre's place along the line, rounded down (geometry/raster.cpp
    // rasterLineAtCentres). pspautotests primitives/lines and linestrip: a line from x 9.375 to
    // 11.25 draws pixels 9 and 10 (centres 9.5, 10.5); bezier and spline, the line patches: a
    // vertical line from y 10 to 22.42, green 0 → 148, reads 5, 29, 41, 53, 65 on rows 10, 12–15,
    // ⌊148·(row + 0.5 − 10) / 12.42⌋. PPSSPP walks ⌊max(|dx|, |dy|) / 16⌋ whole steps from the
    // start vertex and steps the colour once per step, (c0·(n − i) + c1·i) / n (Rasterizer.cpp
    // DrawLine): pixel 9 only, and 0, 24, 37, 49, 61.
    bool pspLineCentres = false;

    static constexpr AccuracyProfile psp() {
        AccuracyProfile a;
        a.pspSpritePosition = true;
        a.spriteFarEdgeExcluded = true;
        a.pspBilinearTruncation = true;
        a.pspTriangleSampleCentre = true;
        a.pspColourGradients = true;
        a.pspPatchColourRoundUp = true;
        a.pspLineCentres = true;
        return a;
    }
    static constexpr AccuracyProfile ppsspp() {
        AccuracyProfile a;
        a.implicitAlphaNonZeroTest = true;
        a.clutSkipsAlphaTest = true;
        a.splineOpenKnotQuirk = true;
        a.zeroAreaTriangles = true;
        a.spotDirectionDivide = true;
        a.sseVectorArithmetic = true;
        return a;
    }

    constexpr bool operator==(const AccuracyProfile&) const = default;

    // "psp", "ppsspp", or "custom" for another mix of switches (the tools' --accuracy and
    // compare's JSON carry the names; a custom mix is named by the text that chose it).
    const char* name() const {
        if (*this == psp()) return "psp";
        if (*this == ppsspp()) return "ppsspp";
        return "custom";
    }
    // The profile `name` chooses: "psp" or "ppsspp", optionally followed by switches turned on
    // (+name) or off (-name), e.g. "ppsspp+pspColourGradients" or "psp-pspTriangleSampleCentre"
    // (what one switch moves, measured on its own); false for anything else.
    static bool fromName(const char* name, AccuracyProfile& out);
};

// Every switch by name: the tools' --accuracy BASE±SWITCH, the profile tests and the
// divergence catalogue walk this table.
struct AccuracySwitch {
    const char* name;
    bool AccuracyProfile::*member;
};
inline constexpr AccuracySwitch kAccuracySwitches[] = {
    {"implicitAlphaNonZeroTest", &AccuracyProfile::implicitAlphaNonZeroTest},
    {"clutSkipsAlphaTest", &AccuracyProfile::clutSkipsAlphaTest},
    {"splineOpenKnotQuirk", &AccuracyProfile::splineOpenKnotQuirk},
    {"zeroAreaTriangles", &AccuracyProfile::zeroAreaTriangles},
    {"spotDirectionDivide", &AccuracyProfile::spotDirectionDivide},
    {"sseVectorArithmetic", &AccuracyProfile::sseVectorArithmetic},
    {"pspSpritePosition", &AccuracyProfile::pspSpritePosition},
    {"spriteFarEdgeExcluded", &AccuracyProfile::spriteFarEdgeExcluded},
    {"pspBilinearTruncation", &AccuracyProfile::pspBilinearTruncation},
    {"pspTriangleSampleCentre", &AccuracyProfile::pspTriangleSampleCentre},
    {"pspColourGradients", &AccuracyProfile::pspColourGradients},
    {"pspPatchColourRoundUp", &AccuracyProfile::pspPatchColourRoundUp},
    {"pspLineCentres", &AccuracyProfile::pspLineCentres},
};

// Every member is a switch, and every switch is in the table.
static_assert(sizeof(AccuracyProfile) == sizeof(kAccuracySwitches) / sizeof(kAccuracySwitches[0]));

inline bool AccuracyProfile::fromName(const char* name, AccuracyProfile& out) {
    const char* end = name;
    while (*end && *end != '+' && *end != '-') ++end;
    const size_t baseLen = size_t(end - name);
    AccuracyProfile a;
    if (baseLen == 3 && std::strncmp(name, "psp", 3) == 0) a = psp();
    else if (baseLen == 6 && std::strncmp(name, "ppsspp", 6) == 0) a = ppsspp();
    else return false;
    while (*end) {
        const bool on = *end == '+';
        const char* tok = ++end;
        while (*end && *end != '+' && *end != '-') ++end;
        const size_t len = size_t(end - tok);
        bool found = false;
        for (const AccuracySwitch& sw : kAccuracySwitches)
            if (std::strlen(sw.name) == len && std::strncmp(sw.name, tok, len) == 0) a.*sw.member = on, found = true;
        if (!found) return false;
    }
    out = a;
    return true;
}

}  // namespace ge::geo
