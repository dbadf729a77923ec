// SPDX-License-Identifier: MIT
// Human-readable key descriptions: the first comment line of every generated
// shader, shown in dumps, failing tests and logs.
#include <string>

#include "shadergen/shader_keys.h"

namespace ge::shadergen {
namespace {

const char* const kCmp[8] = {"never", "always", "eq", "ne", "lt", "le", "gt", "ge"};
const char* const kTexFunc[5] = {"modulate", "decal", "blend", "replace", "add"};
const char* const kBlendEq[6] = {"add", "sub", "rsub", "min", "max", "abs"};
const char* const kSop[6] = {"keep", "zero", "replace", "invert", "incr", "decr"};
const char* const kFmt[4] = {"5650", "5551", "4444", "8888"};

void add(std::string& s, const char* text) {
    if (!s.empty()) s += ' ';
    s += text;
}
void addKv(std::string& s, const char* k, const std::string& v) {
    if (!s.empty()) s += ' ';
    s += k;
    s += '=';
    s += v;
}

}  // namespace

std::string describe(const VsKey& k) {
    std::string s = "VS";
    add(s, k.flatShade ? "flat" : "gouraud");
    return s;
}

std::string describe(const HostCaps& c) {
    std::string s;
    if (c.fbFetch) add(s, "fbfetch");
    if (c.depthFetch) add(s, "depthfetch");
    if (c.textureBarrier) add(s, "barrier");
    if (c.programBinary) add(s, "progbin");
    if (c.exactInterp) add(s, "exactinterp");
    if (s.empty()) s = "baseline";
    return s;
}

std::string describe(const FsKey& k) {
    std::string s = "FS";
    addKv(s, "fmt", kFmt[k.fbFormat & 3]);
    if (k.flatShade) add(s, "flat");
    if (k.clearMode) {
        std::string w;
        if (k.clearColor) w += "rgb";
        if (k.clearAlpha) w += "a";
        if (k.clearDepth) w += "z";
        addKv(s, "clear", w.empty() ? "-" : w);
    }
    if (k.tex) {
        std::string t = kTexFunc[k.texFunc > 4 ? 4 : k.texFunc];
        if (k.texAlpha) t += "+a";
        if (k.texDouble) t += "x2";
        addKv(s, "tex", t);
        std::string f = std::string(k.texMagLinear ? "mag:lin" : "mag:near") + (k.texMinLinear ? ",min:lin" : ",min:near");
        if (k.texMip) f += k.texMip == 2 ? ",mip:lin" : ",mip:near";
        if (k.texMip || k.texMinLinear != k.texMagLinear) f += ",lod" + std::to_string(k.texLodMode);
        addKv(s, "filt", f);
        if (k.texTarget)
            addKv(s, "rtt", std::to_string(k.texTarget - 1) + "as" + std::to_string(k.texFormat));
        if (k.texClampU || k.texClampV)
            addKv(s, "clamp", std::string(k.texClampU ? "u" : "") + (k.texClampV ? "v" : ""));
    }
    if (k.fog) add(s, "fog");
    if (k.alphaTest == 9) addKv(s, "atest", "nonzero");
    else if (k.alphaTest) addKv(s, "atest", kCmp[(k.alphaTest - 1) & 7]);
    if (k.colorTest) addKv(s, "ctest", kCmp[(k.colorTest - 1) & 7]);
    if (k.depthRange) add(s, "zrange");
    if (k.stencilTest)
        addKv(s, "stest",
              std::string(kCmp[(k.stencilTest - 1) & 7]) + "/" + kSop[k.sopFail % 6] + "," + kSop[k.sopZFail % 6] +
                  "," + kSop[k.sopZPass % 6]);
    if (k.depthTest) addKv(s, "ztest", std::string(kCmp[(k.depthTest - 1) & 7]) + (k.depthWrite ? "+w" : ""));
    if (k.blend)
        addKv(s, "blend",
              std::string(kBlendEq[(k.blend - 1) % 6]) + "(" + std::to_string(k.blendA) + "," + std::to_string(k.blendB) +
                  ")");
    if (k.logicOp) addKv(s, "lop", std::to_string(k.logicOp - 1));
    if (k.dither) add(s, "dither");
    if (k.writeAlpha) add(s, "writeA");
    if (k.dstRead != DstRead::None) addKv(s, "dst", k.dstRead == DstRead::FbFetch ? "fetch" : "tex");
    if (k.depthRead != DepthRead::None) addKv(s, "zread", k.depthRead == DepthRead::Fetch ? "fetch" : "tex");
    return s;
}

}  // namespace ge::shadergen
