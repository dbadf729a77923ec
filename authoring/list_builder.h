// SPDX-License-Identifier: MIT
// Display-list authoring: a small sceGu-like builder that emits GE command words, places the data
// they point at (vertices, indices, textures, CLUTs) into guest memory, and can record the same
// command stream as a `.ppdmp` frame dump.
//
// Word encodings follow docs/ge-rules.md §3 and the SDK conventions noted there (ge-rules.md §3.5 viewport,
// offset and depth range; ge-rules.md §3.10 sceGuClear; §3.11 sceGuCopyImage; §5.1 vertex types). Every word
// the builder emits is listed in the comment of the call that emits it, in order, so tests can
// check them word for word.
//
// Typical use:
//   Memory mem;
//   ListBuilder b(&mem);                        // data arena from 0x08800000 up
//   b.drawBuffer(GE_FORMAT_8888, 0, 512);
//   b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
//   ...
//   b.finish();
//   u32 list = b.placeList();                   // copy the words into the arena
//   engine.startList(list, 0); engine.run();
//
// Recording: attach a DumpRecorder (authoring/scene_recorder.h) before emitting; it sees every word
// in execution order and turns it into REGISTERS blocks plus the data records a draw consumes
// (docs/ppdmp.md §4, §7).
#pragma once
#include <string>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/types.h"

namespace ge {

class DumpRecorder;

// Matrix kinds for setMatrix (ge-rules.md §3.4).
enum class GeMatrix { World, View, Proj, TexGen };

// Flags of ListBuilder::clear (the SDK's GU_COLOR/STENCIL/DEPTH_BUFFER_BIT, which sceGuClear
// shifts into CMODE bits 8..10: CEN, AEN, ZEN — ge-rules.md §3.10).
enum ClearFlags : u32 { CLEAR_COLOR = 1, CLEAR_STENCIL = 2, CLEAR_DEPTH = 4 };

// Light components for lightColor (sceGuLightColor's GU_AMBIENT/GU_DIFFUSE/GU_SPECULAR).
enum LightComponent : u32 { LIGHT_AMBIENT = 1, LIGHT_DIFFUSE = 2, LIGHT_SPECULAR = 4 };

// VTYPE building blocks (ge-rules.md §5.1; same values as the SDK's GU_* macros).
namespace vt {
constexpr u32 TC_8 = 1, TC_16 = 2, TC_F = 3;
constexpr u32 COL_5650 = 4 << 2, COL_5551 = 5 << 2, COL_4444 = 6 << 2, COL_8888 = 7 << 2;
constexpr u32 NRM_8 = 1 << 5, NRM_16 = 2 << 5, NRM_F = 3 << 5;
constexpr u32 POS_8 = 1 << 7, POS_16 = 2 << 7, POS_F = 3 << 7;
constexpr u32 W_8 = 1 << 9, W_16 = 2 << 9, W_F = 3 << 9;
constexpr u32 IDX_8 = 1 << 11, IDX_16 = 2 << 11, IDX_32 = 3 << 11;
constexpr u32 weights(u32 n) { return ((n - 1) & 7) << 14; }
constexpr u32 morphs(u32 n) { return ((n - 1) & 7) << 18; }
constexpr u32 THROUGH = 1u << 23;
}  // namespace vt

// One vertex in convenient units, packed by packVertex into the layout of a VTYPE.
struct BuildVertex {
    float w[8] = {};              // skinning weights (WC+1 used)
    float u = 0, v = 0;           // texture coordinate (transform mode: 1.0 = one texture size for
                                  // 8/16-bit; through mode: texels)
    u32 color = 0xFFFFFFFF;       // ABGR8888 (R in bits 7..0), converted to the VTYPE's format
    float nx = 0, ny = 0, nz = 1; // normal
    float x = 0, y = 0, z = 0;    // position (through mode: pixels, z 0–65535)
};

// Writes one vertex (one morph copy) in the layout of `vtype` (ge-rules.md §5.2, §5.4):
// fixed-point components are scaled (8-bit ×128, 16-bit ×32768; through-mode 16-bit positions
// and texture coordinates as given) and saturated to their range; colours are truncated to 16-bit
// formats. `out` must hold VertexLayout::fromVtype(vtype).size bytes; padding bytes are zeroed.
void packVertex(u32 vtype, const BuildVertex& v, u8* out);
// Packs a whole array (count vertices, one copy each) into a byte vector.
std::vector<u8> packVertices(u32 vtype, const BuildVertex* v, u32 count);

class ListBuilder {
public:
    static constexpr u32 kDefaultArena = 0x08800000;

    // `mem` receives placed data (may be null for a words-only builder: then the data-placing
    // calls fail and return 0). Data goes upward from `arenaBase`, 16-byte aligned.
    explicit ListBuilder(Memory* mem = nullptr, u32 arenaBase = kDefaultArena);

    const std::vector<u32>& words() const { return words_; }
    Memory* memory() const { return mem_; }
    // Every following word is also fed to the recorder (null detaches).
    void attach(DumpRecorder* rec) { rec_ = rec; }

    // ---- guest memory arena ----
    // Reserves `size` bytes (aligned) and returns the guest address, 0 when memory is missing or full.
    u32 alloc(u32 size, u32 align = 16);
    // alloc + copy. Returns the address or 0.
    u32 place(const void* data, u32 size, u32 align = 16);
    u32 arenaNext() const { return arenaNext_; }
    // CPU-side write to any guest address (e.g. a texture or CLUT uploaded to VRAM, as a game's
    // memcpy/sceDmacMemcpy would): writes memory now and tells the recorder. False if out of range.
    bool upload(u32 addr, const void* data, u32 size);
    bool uploadFill(u32 addr, u8 value, u32 size);
    // Copies the words emitted so far into the arena and returns the list address (0 on failure).
    u32 placeList(u32 align = 16);

    // ---- raw words ----
    void raw(u32 word);
    void cmd(u8 op, u32 arg) { raw((u32(op) << 24) | (arg & 0xFFFFFF)); }
    void cmdf(u8 op, float f) { cmd(op, toFloat24(f)); }
    void nop() { cmd(GE_CMD_NOP, 0); }

    // ---- flow control (ge-rules.md §3.1, §4.4, §4.5) ----
    void finish(u32 arg = 0);  // FINISH arg, END 0 (sceGuFinish)
    void end(u32 arg = 0);     // END arg
    // SIGNAL (behaviour<<16 | arg&0xFFFF), END endArg. For behaviour 0x03 (pause) the SDK follows
    // with FINISH/END; do that explicitly with finish().
    void signal(u32 behaviour, u32 arg, u32 endArg = 0);
    void base(u32 addr) { cmd(GE_CMD_BASE, (addr >> 8) & 0x0F0000); }
    void call(u32 addr);       // BASE, CALL (sceGuCallList)
    void jump(u32 addr);       // BASE, JUMP
    void ret() { cmd(GE_CMD_RET, 0); }
    // Places `sub`'s words in the arena and emits BASE + CALL to them. With a recorder attached,
    // `sub`'s words (up to its RET) are fed to it as the GE would execute them.
    u32 callList(const ListBuilder& sub);
    void offsetAddr(u32 addr) { cmd(GE_CMD_OFFSET, addr >> 8); }
    void origin() { cmd(GE_CMD_ORIGIN, 0); }

    // ---- frame buffers and view (ge-rules.md §3.5, §3.7, §3.10) ----
    // FPF fmt, FBP vramOffset, FBW width (sceGuDrawBuffer). vramOffset is relative to 0x04000000.
    void drawBuffer(u32 fmt, u32 vramOffset, u32 width);
    // ZBP, ZBW.
    void depthBuffer(u32 vramOffset, u32 width);
    // SX w/2, SY −h/2, TX cx, TY cy (sceGuViewport).
    void viewport(float cx, float cy, float w, float h);
    // OFFSETX x<<4, OFFSETY y<<4 (sceGuOffset).
    void offset(u32 x, u32 y);
    // SZ, TZ, MINZ, MAXZ as sceGuDepthRange: z = (near+far)>>1, SZ = z − near, TZ = z.
    void depthRange(u32 nearZ, u32 farZ);
    // SCISSOR1 (y1<<10|x1), SCISSOR2 ((y2−1)<<10|(x2−1)): x2, y2 exclusive as in
    // sceGuScissor(0, 0, 480, 272).
    void scissor(u32 x1, u32 y1, u32 x2, u32 y2);
    // REGION1 (y<<10|x), REGION2 ((y+h−1)<<10|(x+w−1)).
    void region(u32 x, u32 y, u32 w, u32 h);
    // Through-mode 8888 rectangles covering the scissor area, 64 pixels per column, like sceGuClear:
    // CMODE (flags<<8 | 1), VTYPE, BASE, VADR, PRIM RECTANGLES, CMODE 0. The vertex colour is
    // (color & 0xFFFFFF) | stencil<<24 (alpha is the stencil, ge-rules.md §8.4); z = depth.
    void clear(u32 flags, u32 color, u16 depth, u8 stencil = 0);

    // ---- state ----
    void enable(u8 enableCmd, bool on) { cmd(enableCmd, on ? 1 : 0); }
    void setVertexType(u32 vtype) { cmd(GE_CMD_VTYPE, vtype); }
    // Column-major 4×4 (m[4·col + row], as ScePspFMatrix4): 3×4 kinds send rows 0–2 of the four
    // columns (12 words), Proj all 16 (ge-rules.md §3.4 SDK note). N 0 first.
    void setMatrix(GeMatrix kind, const float m[16]);
    // 3×4 in GE element order (element k = row k%3, column k/3).
    void setMatrix3x4(GeMatrix kind, const float m[12]);
    // BONEN 12·i, 12 × BONED (GE element order).
    void setBoneMatrix(u32 i, const float m[12]);
    void setMorphWeight(u32 i, float w) { cmdf(u8(GE_CMD_WEIGHT0 + (i & 7)), w); }
    void shadeModel(bool gouraud) { cmd(GE_CMD_SHADE, gouraud); }
    // CULL bit: false culls clockwise triangles (drawing coordinates), true counter-clockwise (ge-rules.md §3.6).
    void cullMode(bool ccw) { cmd(GE_CMD_CULL, ccw); }

    // Textures (ge-rules.md §3.7, §3.8).
    // TBPn addr&0xFFFFFF, TBWn (addr>>8 & 0x0F0000)|bufw, TSIZEn (log2 h<<8 | log2 w), TFLUSH.
    void setTexture(u32 level, u32 addr, u32 w, u32 h, u32 bufw);
    // TMODE (maxLevel<<16 | multiclut<<8 | swizzle), TPF format, TFLUSH.
    void texMode(u32 format, u32 maxLevel, bool swizzle, bool multiClut = false);
    // TFUNC (doubling<<16 | rgba<<8 | func).
    void texFunc(u32 func, bool rgba, bool doubling = false);
    void texEnvColor(u32 rgb) { cmd(GE_CMD_TEC, rgb); }
    // TFILTER (mag<<8 | min).
    void texFilter(u32 min, u32 mag) { cmd(GE_CMD_TFILTER, (mag << 8) | min); }
    // TWRAP (vclamp<<8 | uclamp).
    void texWrap(bool uclamp, bool vclamp) { cmd(GE_CMD_TWRAP, (u32(vclamp) << 8) | u32(uclamp)); }
    // TLEVEL (offl<<16 | mode), offl = trunc(bias·16) clamped to −128…127 (ge-rules.md §3.8).
    void texLevelMode(u32 mode, float bias);
    void texSlope(float s) { cmdf(GE_CMD_TSLOPE, s); }
    // SU, SV, TU, TV.
    void texScale(float su, float sv);
    void texOffset(float tu, float tv);
    // TMAP (proj<<8 | mode).
    void texMapMode(u32 mode, u32 projSource = 0) { cmd(GE_CMD_TMAP, (projSource << 8) | mode); }
    // TSHADE (v<<8 | u): lights used for shade mapping (field order per ge-rules.md §3.8).
    void texShadeLights(u32 lu, u32 lv) { cmd(GE_CMD_TSHADE, (lv << 8) | lu); }
    void texFlush() { cmd(GE_CMD_TFLUSH, 0); }
    void texSync() { cmd(GE_CMD_TSYNC, 0); }
    // CLUT (start<<16 | mask<<8 | shift<<2 | fmt).
    void clutMode(u32 fmt, u32 shift, u32 mask, u32 start);
    // CBP addr&0xFFFFFF, CBW (addr>>8)&0x0F0000, CLOAD blocks.
    void clutLoad(u32 addr, u32 blocks);

    // Pixel operations (ge-rules.md §3.10).
    // BLEND (eq<<8 | b<<4 | a), FIXA, FIXB.
    void blendFunc(u32 eq, u32 a, u32 b, u32 fixA = 0, u32 fixB = 0);
    void alphaFunc(u32 func, u32 ref, u32 mask = 0xFF) { cmd(GE_CMD_ATEST, func | (ref & 0xFF) << 8 | (mask & 0xFF) << 16); }
    // CTEST func, CREF ref, CMSK mask.
    void colorFunc(u32 func, u32 ref, u32 mask);
    void stencilFunc(u32 func, u32 ref, u32 mask = 0xFF) { cmd(GE_CMD_STEST, func | (ref & 0xFF) << 8 | (mask & 0xFF) << 16); }
    void stencilOp(u32 sfail, u32 zfail, u32 zpass) { cmd(GE_CMD_SOP, sfail | zfail << 8 | zpass << 16); }
    void depthFunc(u32 func) { cmd(GE_CMD_ZTEST, func); }
    void depthMask(bool noWrite) { cmd(GE_CMD_ZMSK, noWrite); }
    void logicOp(u32 op) { cmd(GE_CMD_LOP, op); }
    // PMSK1 rgb, PMSK2 alpha (1 bits keep the frame buffer).
    void pixelMask(u32 rgbKeep, u32 alphaKeep);
    // DTTH1–4 from a 4×4 matrix m[row·4 + col] of values −8…7.
    void setDither(const int m[16]);

    // Lighting (ge-rules.md §3.6).
    // LXn, LYn, LZn, LTYPEn (type<<8 | comps) — comps is the raw LTYPE field: 0 ambient+diffuse,
    // 1 +specular, 2 powered diffuse (ge-rules.md §3.6); the SDK's order of words.
    void light(u32 n, u32 type, u32 comps, const float pos[3]);
    // LACn / LDCn / LSCn for each bit of `components`.
    void lightColor(u32 n, u32 components, u32 rgb);
    // LKAn, LKBn, LKCn.
    void lightAtt(u32 n, float a, float b, float c);
    // LDXn, LDYn, LDZn, LKSn exponent, LKOn cutoff (sceGuLightSpot).
    void lightSpot(u32 n, const float dir[3], float exponent, float cutoff);
    // AC rgb, AA alpha (sceGuAmbient, ABGR).
    void ambient(u32 abgr);
    // MATERIAL comps (bit 0 ambient, 1 diffuse, 2 specular from the vertex colour).
    void colorMaterial(u32 comps) { cmd(GE_CMD_MATERIAL, comps); }
    // MAC rgb, MAA alpha (ABGR).
    void materialAmbient(u32 abgr);
    void materialDiffuse(u32 rgb) { cmd(GE_CMD_MDC, rgb); }
    void materialSpecular(u32 rgb) { cmd(GE_CMD_MSC, rgb); }
    void materialEmissive(u32 rgb) { cmd(GE_CMD_MEC, rgb); }
    void specularPower(float k) { cmdf(GE_CMD_MK, k); }
    void lightMode(bool separateSpecular) { cmd(GE_CMD_LMODE, separateSpecular); }
    // FC rgb, FOG1 far, FOG2 1/(far−near) (0 when far == near), in sceGuFog's order.
    void fog(float nearZ, float farZ, u32 rgb);

    // Patches (ge-rules.md §3.2).
    void patchDivide(u32 u, u32 v) { cmd(GE_CMD_DIVIDE, (v << 8) | u); }
    void patchPrim(u32 ppm) { cmd(GE_CMD_PPM, ppm); }
    void patchFace(bool reverse) { cmd(GE_CMD_PFACE, reverse); }

    // ---- drawing ----
    // VTYPE vtype, [BASE, IADR indexAddr], [BASE, VADR vertexAddr], PRIM (prim<<16 | count), as
    // sceGuDrawArray. An address of 0 leaves that pointer as it is (continuing after the last draw).
    void drawArray(u32 prim, u32 vtype, u32 count, u32 indexAddr, u32 vertexAddr);
    // Same, placing host data in the arena first (indices may be null; their size follows vtype).
    void drawArrayData(u32 prim, u32 vtype, u32 count, const void* indices, const void* vertices);
    // One through-mode rectangle (manual §4.4: PRIM RECTANGLES, two opposite corners; here 8888
    // colour, 16-bit position, z 0) from (x1, y1) to (x2, y2), x2 and y2 exclusive, in one ABGR
    // colour: the plain coloured box tests and examples draw.
    void fillRect(u32 x1, u32 y1, u32 x2, u32 y2, u32 abgr);
    // VTYPE, [BASE, IADR], [BASE, VADR], BEZIER (v<<8 | u).
    void drawBezier(u32 vtype, u32 ucount, u32 vcount, u32 indexAddr, u32 vertexAddr);
    // VTYPE, [BASE, IADR], [BASE, VADR], SPLINE (vedge<<18 | uedge<<16 | v<<8 | u).
    void drawSpline(u32 vtype, u32 ucount, u32 vcount, u32 uedge, u32 vedge, u32 indexAddr, u32 vertexAddr);
    // Block transfer as sceGuCopyImage (ge-rules.md §3.11): XBP1, XBW1, XPOS1, XBP2, XBW2, XPOS2, XSIZE,
    // XSTART (1 for 8888, else 0). Strides in pixels; addresses are full guest addresses.
    void copyImage(u32 psm, u32 sx, u32 sy, u32 width, u32 height, u32 srcStride, u32 src, u32 dx, u32 dy,
                   u32 dstStride, u32 dst);

    // The scissor the builder last set (for clear), exclusive end.
    u32 scissorX1() const { return sx1_; }
    u32 scissorY1() const { return sy1_; }
    u32 scissorX2() const { return sx2_; }
    u32 scissorY2() const { return sy2_; }

private:
    void addressCmd(u8 op, u32 addr);
    u32 indexBytes(u32 vtype, u32 count) const;

    Memory* mem_;
    u32 arenaNext_;
    u32 arenaEnd_;
    std::vector<u32> words_;
    DumpRecorder* rec_ = nullptr;
    u32 sx1_ = 0, sy1_ = 0, sx2_ = 480, sy2_ = 272;
};

// Exact log2 of a power of two (the texture size exponent); the floor for other values.
u32 log2Floor(u32 v);

}  // namespace ge
