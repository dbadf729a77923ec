// SPDX-License-Identifier: MIT
// make_scenes: writes the project's own GE frame dumps (dumps/*.ppdmp) from scene descriptions
// built with ge::ListBuilder. Every scene draws a 480×272 frame into the 8888 frame buffer at
// VRAM 0x04000000 (stride 512); all data (vertices, textures, palettes) is generated here, so the
// output bytes are deterministic. docs/scenes.md says what each scene shows and exercises.
//
// Usage: make_scenes [--out DIR] [--list]      (DIR defaults to <source>/dumps)
//
// The scenes are in tools/scenes/ (one file each; scene_kit.h holds what they share). Each scene
// is built once: the builder places data in a private guest memory, emits the list,
// and a DumpRecorder turns the same command stream into records. The list is then executed on a
// GeEngine (no renderer) as a sanity check that it runs to FINISH without errors.
#include <cstdio>
#include <cstring>
#include <string>

#include "authoring/list_builder.h"
#include "authoring/scene_recorder.h"
#include "hle/dump/dump_writer.h"
#include "hle/ge_engine.h"
#include "tools/scenes/scene_kit.h"
#include "tools/scenes/scenes.h"

#ifndef GE2GL_SOURCE_DIR
#define GE2GL_SOURCE_DIR "."
#endif

using namespace ge;
using namespace ge::scenes;

namespace {

struct Scene {
    const char* name;
    void (*build)(ListBuilder&);
};
const Scene kScenes[] = {
    {"lit_textured_skinned", sceneLitTexturedSkinned},
    {"clut_dxt_sprites", sceneClutDxtSprites},
    {"bezier_spline", sceneBezierSpline},
    {"blend_stencil_logic", sceneBlendStencilLogic},
    {"render_to_texture", sceneRenderToTexture},
};

// The INIT state: a booted GE with identity matrices (the scene sets everything it uses).
GeState initialState() {
    GeState st;
    st.reset();
    const Mat4 id = identity();
    float m[12];
    to3x4(id, m);
    std::memcpy(st.world, m, sizeof m);
    std::memcpy(st.view, m, sizeof m);
    std::memcpy(st.tgen, m, sizeof m);
    std::memcpy(st.proj, id.m, sizeof id.m);
    for (int i = 0; i < 8; ++i) std::memcpy(st.bone + 12 * i, m, sizeof m);
    for (int op = 0; op < 256; ++op) st.regs[op] = u32(op) << 24;
    return st;
}

bool writeScene(const Scene& s, const std::string& dir) {
    Memory mem;
    dump::DumpWriter writer("GE2GL0001");
    DumpRecorder rec(mem, writer);
    ListBuilder b(&mem);
    const GeState init = initialState();
    rec.begin(init, 0x04000000, 512, GE_FORMAT_8888);
    b.attach(&rec);
    s.build(b);
    b.attach(nullptr);
    rec.end(0x04000000, 512, GE_FORMAT_8888);

    bool ok = true;
    for (const std::string& w : rec.warnings()) std::fprintf(stderr, "%s: warning: %s\n", s.name, w.c_str());

    // Sanity check: the executable list runs to FINISH on the engine without errors.
    const u32 list = b.placeList();
    GeEngine engine(mem);
    u32 ctx[512];
    init.saveContext(ctx);
    engine.loadContext(ctx);
    engine.startList(list, 0);
    RunStatus st = engine.run(1u << 24);
    if (st != RunStatus::Completed) {
        std::fprintf(stderr, "%s: list ended with %s (%s)\n", s.name, runStatusName(st), engine.lastErrorMessage().c_str());
        ok = false;
    }

    std::string err;
    const std::string path = dir + "/" + s.name + ".ppdmp";
    if (!writer.save(path, err)) {
        std::fprintf(stderr, "%s: %s\n", path.c_str(), err.c_str());
        return false;
    }
    std::printf("%-24s %5zu records, %7zu push bytes, %4u kicks, %5zu words, engine: %llu prims %llu patches\n", s.name,
                writer.dump().records.size(), writer.dump().pushbuf.size(), rec.kicks(), b.words().size(),
                (unsigned long long)engine.stats().prims, (unsigned long long)engine.stats().patches);
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    std::string dir = std::string(GE2GL_SOURCE_DIR) + "/dumps";
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--out" && i + 1 < argc) {
            dir = argv[++i];
        } else if (a == "--list") {
            for (const Scene& s : kScenes) std::printf("%s\n", s.name);
            return 0;
        } else {
            std::fprintf(stderr, "usage: make_scenes [--out DIR] [--list]\n");
            return 2;
        }
    }
    bool ok = true;
    for (const Scene& s : kScenes) ok = writeScene(s, dir) && ok;
    return ok ? 0 : 1;
}
