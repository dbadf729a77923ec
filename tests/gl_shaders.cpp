// SPDX-License-Identifier: MIT
// Shader generation and program caching: key canonicalisation, generator fuzzing (random keys →
// GLSL → compile and link on the headless context), the on-disk program-binary cache (a second
// renderer compiles nothing), shader dumps, stats, and EGL context creation.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "shadergen/keys_from_state.h"
#include "shadergen/shader_gen.h"
#include "tests/gl_fixture.h"
#include "translator/gl_context.h"
#include "translator/shader_cache.h"

namespace ge::gltest {
namespace {

namespace sg = shadergen;

// The draw flags of `st` with the ppsspp profile (the reference's alpha-test rules on).
sg::DrawFlags flags(const GeState& st) { return sg::DrawFlags::fromState(st, geo::AccuracyProfile::ppsspp()); }

namespace fs = std::filesystem;

fs::path freshDir(const char* name) {
    fs::path d = fs::path(GE2GL_BINARY_DIR) / "gl_test_tmp" / name;
    std::error_code ec;
    fs::remove_all(d, ec);
    fs::create_directories(d, ec);
    return d;
}

TEST(GlShaderKeys, CanonicalizeClearsDontCares) {
    sg::FsKey a, b;
    a.tex = 0;
    a.texFunc = 3;  // meaningless without texturing
    a.texMagLinear = 1;
    a.blend = 0;
    a.blendA = 7;
    sg::canonicalize(a);
    sg::canonicalize(b);
    EXPECT_TRUE(sg::keyEqual(a, b));
    // Clear mode drops every test and colour op.
    sg::FsKey c;
    c.clearMode = 1;
    c.clearColor = 1;
    c.alphaTest = 3;
    c.blend = 1;
    c.fog = 1;
    sg::canonicalize(c);
    EXPECT_EQ(c.alphaTest, 0);
    EXPECT_EQ(c.blend, 0);
    EXPECT_EQ(c.fog, 0);
    EXPECT_EQ(c.clearColor, 1);
}

TEST(GlShaderKeys, StateToKeysDecidesDestinationReads) {
    GeState st;
    st.reset();
    st.regs[GE_CMD_FPF] = (uint32_t(GE_CMD_FPF) << 24) | GE_FORMAT_8888;
    sg::HostCaps caps;
    caps.fbFetch = 1;
    sg::PipelineKeys k = sg::keysFromState(st, flags(st), caps, false);
    EXPECT_EQ(k.fs.dstRead, sg::DstRead::None);  // nothing reads the destination
    EXPECT_FALSE(k.ff.colorMask[3]);              // no stencil: the alpha byte is kept
    st.regs[GE_CMD_ABE] = (uint32_t(GE_CMD_ABE) << 24) | 1;
    k = sg::keysFromState(st, flags(st), caps, false);
    EXPECT_EQ(k.fs.dstRead, sg::DstRead::FbFetch);
    k = sg::keysFromState(st, flags(st), caps, true);
    EXPECT_EQ(k.fs.dstRead, sg::DstRead::Texture);  // baseline
    // A partial PMSK needs the destination even without blending.
    st.regs[GE_CMD_ABE] = (uint32_t(GE_CMD_ABE) << 24);
    st.regs[GE_CMD_PMSK1] = (uint32_t(GE_CMD_PMSK1) << 24) | 0x0F;
    k = sg::keysFromState(st, flags(st), caps, false);
    EXPECT_EQ(k.fs.dstRead, sg::DstRead::FbFetch);
    // A whole protected channel is a plain colour mask.
    st.regs[GE_CMD_PMSK1] = (uint32_t(GE_CMD_PMSK1) << 24) | 0xFF;
    k = sg::keysFromState(st, flags(st), caps, false);
    EXPECT_EQ(k.fs.dstRead, sg::DstRead::None);
    EXPECT_FALSE(k.ff.colorMask[0]);
    EXPECT_TRUE(k.ff.colorMask[1]);
}

TEST(GlShaderKeys, GeneratedSourceStartsWithDescription) {
    sg::FsKey k;
    k.tex = 1;
    k.texFunc = 2;
    k.blend = 1;
    k.blendA = 2;
    k.blendB = 3;
    k.dstRead = sg::DstRead::Texture;
    sg::canonicalize(k);
    std::string src;
    ASSERT_TRUE(sg::generateFragmentShader(k, sg::HostCaps{}, src));
    EXPECT_NE(src.find("// ge2gl " + sg::describe(k)), std::string::npos);
    EXPECT_NE(sg::describe(k).find("tex=blend"), std::string::npos);
    EXPECT_NE(sg::describe(k).find("blend=add(2,3)"), std::string::npos);
    // Framebuffer fetch without the capability is refused, not silently produced.
    k.dstRead = sg::DstRead::FbFetch;
    std::string err;
    EXPECT_FALSE(sg::generateFragmentShader(k, sg::HostCaps{}, src, &err));
    EXPECT_FALSE(err.empty());
}

sg::FsKey randomKey(std::mt19937& rng, const sg::HostCaps& caps) {
    auto r = [&](int n) { return u8(std::uniform_int_distribution<int>(0, n - 1)(rng)); };
    sg::FsKey k;
    k.clearMode = r(5) == 0;
    k.clearColor = r(2), k.clearAlpha = r(2), k.clearDepth = r(2);
    k.flatShade = r(2);
    k.tex = r(3) != 0;
    k.texFunc = r(8), k.texAlpha = r(2), k.texDouble = r(2);
    k.texMagLinear = r(2), k.texMinLinear = r(2), k.texMip = r(3), k.texLodMode = r(3);
    k.texClampU = r(2), k.texClampV = r(2);
    k.fog = r(2);
    k.alphaTest = r(9), k.colorTest = r(5), k.depthRange = r(2);
    k.fbFormat = r(4);
    k.stencilTest = r(3) == 0 ? u8(1 + r(8)) : 0;
    k.sopFail = r(6), k.sopZFail = r(6), k.sopZPass = r(6);
    k.depthTest = r(2) ? u8(1 + r(8)) : 0;
    k.depthWrite = r(2);
    k.blend = r(2) ? u8(1 + r(6)) : 0;
    k.blendA = r(16), k.blendB = r(16);
    k.logicOp = r(3) == 0 ? u8(1 + r(16)) : 0;
    k.dither = r(2);
    k.writeAlpha = r(2);
    const bool dst = k.stencilTest || k.blend || k.logicOp || r(4) == 0;
    if (dst) {
        k.dstRead = (caps.fbFetch && r(2)) ? sg::DstRead::FbFetch : sg::DstRead::Texture;
        k.maskRgb = 1;
        k.maskAlpha = 1;
        if (k.stencilTest && k.depthTest)
            k.depthRead = (caps.depthFetch && r(2)) ? sg::DepthRead::Fetch : sg::DepthRead::Texture;
    }
    sg::canonicalize(k);
    return k;
}

TEST(GlShaderGen, FuzzedKeysCompileAndLink) {
    std::string err;
    auto ctx = gl::GlContext::create(gl::ContextKind::OSMesa, err);
    if (!ctx) GTEST_SKIP() << "no GL context: " << err;
    const sg::HostCaps caps = ctx->caps().hostCaps(false);
    gl::ProgramCache cache(*ctx, caps, "", "");
    std::mt19937 rng(1234);
    int built = 0;
    for (int i = 0; i < 256; ++i) {
        const sg::FsKey fk = randomKey(rng, caps);
        sg::VsKey vk;
        vk.flatShade = fk.flatShade;
        std::string e;
        const gl::Program* p = cache.get(vk, fk, &e);
        ASSERT_NE(p, nullptr) << sg::describe(fk) << "\n" << e;
        ++built;
    }
    EXPECT_EQ(built, 256);
    EXPECT_GT(cache.stats().compiles, 0u);
    // The float-interpolation variant (hosts without GL 4.0 + ARB_gpu_shader_int64).
    const sg::HostCaps floatCaps = ctx->caps().hostCaps(false, true);
    EXPECT_EQ(floatCaps.exactInterp, 0);
    gl::ProgramCache floatCache(*ctx, floatCaps, "", "");
    for (int i = 0; i < 64; ++i) {
        const sg::FsKey fk = randomKey(rng, floatCaps);
        sg::VsKey vk;
        vk.flatShade = fk.flatShade;
        std::string e;
        ASSERT_NE(floatCache.get(vk, fk, &e), nullptr) << sg::describe(fk) << "\n" << e;
    }
}

// A scene that needs several programs: clear, textured blended rectangles, stencil.
void buildCacheScene(GlScene& s) {
    s.setupFrame();
    s.b->clear(CLEAR_COLOR | CLEAR_STENCIL | CLEAR_DEPTH, 0x00204060, 0, 0);
    std::vector<u32> tex(64, 0x80FF8040u);
    const u32 addr = s.b->place(tex.data(), 256);
    s.b->texMode(GE_TFMT_8888, 0, false);
    s.b->setTexture(0, addr, 8, 8, 8);
    s.b->texFunc(0, true);
    s.b->enable(GE_CMD_TME, true);
    s.b->enable(GE_CMD_ABE, true);
    s.b->blendFunc(0, 2, 3);
    s.rect(0, 0, 32, 32, 0xFFFFFFFF, 0, 0, 8, 8);
    s.b->enable(GE_CMD_ABE, false);
    s.b->enable(GE_CMD_TME, false);
    s.b->enable(GE_CMD_STE, true);
    s.b->stencilFunc(1, 9);
    s.b->stencilOp(0, 0, 2);
    s.rect(16, 16, 48, 48, 0xFF00FF00);
    s.b->enable(GE_CMD_STE, false);
}

class GlCacheScene : public GlScene {
public:
    void TestBody() override {}
    // A renderer with `opt` on fresh memory, then buildCacheScene run on it; false (with err)
    // when no GL context can be created.
    bool render(const gl::GlOptions& opt, std::string& err) {
        mem = std::make_unique<Memory>();
        renderer = gl::createGlRenderer(*mem, opt, err);
        if (!renderer) return false;
        engine = std::make_unique<GeEngine>(*mem, renderer.get());
        b = std::make_unique<ListBuilder>(mem.get());
        buildCacheScene(*this);
        run();
        return true;
    }
};

// The scene rendered with program binaries under `dir`; false (err says why) without a GL context.
bool renderWithProgramCache(GlCacheScene& s, const fs::path& dir, std::string& err) {
    gl::GlOptions opt;
    opt.programCacheDir = dir.string();
    return s.render(opt, err);
}

TEST(GlProgramCache, SecondRendererCompilesNothing) {
    const fs::path dir = freshDir("progcache");
    u32 firstPixels[4] = {};
    for (int pass = 0; pass < 2; ++pass) {
        std::string err;
        GlCacheScene s;
        if (!renderWithProgramCache(s, dir, err)) GTEST_SKIP() << "no GL context: " << err;
        const gl::GlStats st = s.renderer->stats();
        const u32 px[4] = {s.px32(4, 4), s.px32(20, 20), s.px32(40, 40), s.px32(60, 60)};
        if (pass == 0) {
            EXPECT_GT(st.shaderCompiles, 0u);
            EXPECT_EQ(st.diskCacheHits, 0u);
            std::copy(px, px + 4, firstPixels);
        } else {
            EXPECT_EQ(st.shaderCompiles, 0u) << gl::glStatsText(st);
            EXPECT_GT(st.diskCacheHits, 0u);
            for (int i = 0; i < 4; ++i) EXPECT_EQ(px[i], firstPixels[i]) << i;
        }
    }
}

// The directory is bounded (ProgramCache::trimDisk): past kMaxDiskPrograms binaries, the first
// write of a cache removes the oldest until half remain, and stale temporary files; it leaves
// other files alone.
TEST(GlProgramCache, DiskDirectoryIsTrimmedToHalfItsBoundOldestFirst) {
    const fs::path dir = freshDir("progtrim");
    const size_t bound = gl::ProgramCache::kMaxDiskPrograms, extra = 10;
    const auto now = fs::file_time_type::clock::now();
    for (size_t i = 0; i < bound + extra; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "%016zx.bin", i);
        std::ofstream(dir / name) << "old";
        // File i is i seconds younger than file 0: the lowest numbers are the oldest.
        fs::last_write_time(dir / name, now - std::chrono::hours(1) + std::chrono::seconds(i));
    }
    std::ofstream(dir / "notes.txt") << "not the cache's";
    // Temporary files of writers that died: an old one goes, a fresh one (a writer at work) stays.
    std::ofstream(dir / "00000000000000aa.bin.tmp.1.2.3") << "half";
    fs::last_write_time(dir / "00000000000000aa.bin.tmp.1.2.3", now - std::chrono::hours(2));
    std::ofstream(dir / "00000000000000bb.bin.tmp.4.5.6") << "half";
    std::string err;
    GlCacheScene s;
    if (!renderWithProgramCache(s, dir, err)) GTEST_SKIP() << "no GL context: " << err;
    const gl::GlStats st = s.renderer->stats();
    ASSERT_GT(st.shaderCompiles, 0u);  // so something was written
    size_t bins = 0;
    for (const auto& e : fs::directory_iterator(dir)) bins += e.path().extension() == ".bin";
    EXPECT_EQ(bins, bound / 2 + st.shaderCompiles);
    EXPECT_FALSE(fs::exists(dir / "0000000000000000.bin"));  // the oldest went
    char newest[32];
    std::snprintf(newest, sizeof newest, "%016zx.bin", bound + extra - 1);
    EXPECT_TRUE(fs::exists(dir / newest));
    EXPECT_TRUE(fs::exists(dir / "notes.txt"));
    EXPECT_FALSE(fs::exists(dir / "00000000000000aa.bin.tmp.1.2.3"));
    EXPECT_TRUE(fs::exists(dir / "00000000000000bb.bin.tmp.4.5.6"));
}

TEST(GlProgramCache, ShaderDumpWritesSources) {
    const fs::path dir = freshDir("shaderdump");
    gl::GlOptions opt;
    opt.shaderDumpDir = dir.string();
    std::string err;
    GlCacheScene s;
    if (!s.render(opt, err)) GTEST_SKIP() << "no GL context: " << err;
    int frags = 0, verts = 0;
    for (auto& e : fs::directory_iterator(dir)) {
        frags += e.path().extension() == ".frag";
        verts += e.path().extension() == ".vert";
    }
    const gl::GlStats st = s.renderer->stats();
    EXPECT_EQ(u64(frags), st.shaderCompiles);
    EXPECT_EQ(verts, frags);
    // Stats text has one line per counter.
    const std::string text = gl::glStatsText(st);
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 21);
    EXPECT_NE(text.find("shaderCompiles"), std::string::npos);
    EXPECT_GT(st.uniformUploads, 0u);
    EXPECT_GT(st.draws, 0u);
    EXPECT_GT(st.readbacks, 0u);
}

TEST(GlContext, EglSurfacelessRendersLikeOsmesa) {
    u32 pixels[2][2] = {};
    for (int kind = 0; kind < 2; ++kind) {
        gl::GlOptions opt;
        opt.context = kind ? gl::ContextKind::EGL : gl::ContextKind::OSMesa;
        std::string err;
        GlCacheScene s;
        if (!s.render(opt, err)) GTEST_SKIP() << (kind ? "EGL" : "OSMesa") << " unavailable: " << err;
        pixels[kind][0] = s.px32(4, 4);
        pixels[kind][1] = s.px32(20, 20);
        // presentFrame gives a presentable texture name on either context.
        std::string perr;
        EXPECT_NE(s.renderer->presentFrame(0x04000000, 64, GE_FORMAT_8888, 64, 32, 128, 64, perr), 0u) << perr;
    }
    EXPECT_EQ(pixels[0][0], pixels[1][0]);
    EXPECT_EQ(pixels[0][1], pixels[1][1]);
}

}  // namespace
}  // namespace ge::gltest
