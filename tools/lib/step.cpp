// SPDX-License-Identifier: MIT
#include "tools/lib/step.h"

#include <cstdio>
#include <filesystem>

#include "debugger/debugger.h"
#include "hle/dump/player.h"

namespace ge::tools {

namespace {

struct BreakSpec {
    enum Kind { Draw, Prim, Op, Addr, Command } kind = Draw;
    u32 value = 0;  // opcode or address
    u64 nth = 1;
};

bool parseNumber(const std::string& s, u64& out) {
    if (s.empty()) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtoull(s.c_str(), &end, 0);
    return errno == 0 && *end == 0;
}

bool parseBreak(const std::string& text, BreakSpec& b, std::string& err) {
    const size_t colon = text.find(':');
    const std::string kind = text.substr(0, colon), rest = colon == std::string::npos ? "" : text.substr(colon + 1);
    const size_t colon2 = rest.find(':');
    const std::string first = rest.substr(0, colon2), second = colon2 == std::string::npos ? "" : rest.substr(colon2 + 1);
    u64 n = 0;
    err = "bad --break '" + text + "' (draw:N, prim:N, command:N, op:NAME[:N], addr:ADDR[:N]; N from 1)";
    if (kind == "draw" || kind == "prim" || kind == "command") {
        b.kind = kind == "draw" ? BreakSpec::Draw : kind == "prim" ? BreakSpec::Prim : BreakSpec::Command;
        if (!parseNumber(first, n) || n == 0 || !second.empty()) return false;
        b.nth = n;
    } else if (kind == "op" || kind == "addr") {
        if (kind == "op") {
            b.kind = BreakSpec::Op;
            int found = -1;
            for (int op = 0; op < 256; ++op)
                if (geCmdKnown(u8(op)) && first == geCmdName(u8(op))) found = op;
            if (found < 0) return err = "unknown opcode name '" + first + "' in --break", false;
            b.value = u32(found);
        } else {
            b.kind = BreakSpec::Addr;
            if (!parseNumber(first, n) || n > 0xFFFFFFFFu || (n & 3)) return false;
            b.value = Memory::normalize(u32(n));
        }
        if (!second.empty() && (!parseNumber(second, n) || n == 0)) return false;
        b.nth = second.empty() ? 1 : n;
    } else {
        return false;
    }
    err.clear();
    return true;
}

Image gray(const std::vector<u8>& v, u32 w, u32 h) {
    Image img;
    img.width = int(w), img.height = int(h);
    for (u8 g : v) img.rgba.push_back(0xFF000000u | g * 0x010101u);
    return img;
}

std::string fmt(const char* f, auto... args) {
    char buf[256];
    std::snprintf(buf, sizeof buf, f, args...);
    return buf;
}

// Takes the buffers at the first command after it is armed (the break's command has run then).
class AfterCapture : public CommandObserver {
public:
    AfterCapture(GeEngine& e, StepResult& out) : e_(e), out_(out) {}
    bool armed = false, done = false;
    // Armed during the break command's own observer round (this observer comes after the
    // breakpoints): that call is skipped, the next one comes after the command ran.
    bool beforeCommand(u32, u32) override {
        if (armed && !done) {
            if (sawBreakCommand_) capture();
            sawBreakCommand_ = true;
        }
        return true;
    }
    void capture() {
        done = true;
        e_.renderer()->flushToMemory();
        const Memory& mem = e_.memory();
        const GeState& st = e_.state();
        std::vector<u8> rgba, sten;
        std::vector<u16> depth;
        out_.fbAddr = st.framebufAddr(), out_.fbStride = st.framebufStride(), out_.fbFormat = st.framebufFormat();
        if (debug::readColor(mem, st, 480, 272, rgba)) {
            out_.color.width = 480, out_.color.height = 272;
            for (size_t i = 0; i < rgba.size(); i += 4)
                out_.color.rgba.push_back(u32(rgba[i]) | u32(rgba[i + 1]) << 8 | u32(rgba[i + 2]) << 16 | 0xFF000000u);
        }
        if (debug::readDepth(mem, st, 480, 272, depth)) {
            std::vector<u8> hi;
            for (u16 d : depth) hi.push_back(u8(d >> 8));
            out_.depth = gray(hi, 480, 272);
        }
        if (debug::readStencil(mem, st, 480, 272, sten)) out_.stencil = gray(sten, 480, 272);
    }

private:
    GeEngine& e_;
    StepResult& out_;
    bool sawBreakCommand_ = false;
};

}  // namespace

bool stepDump(const std::string& path, const StepOptions& opt, StepResult& out, std::string& err) {
    BreakSpec spec;
    if (!parseBreak(opt.breakAt, spec, err)) return false;
    dump::Dump d;
    if (!dump::loadDump(path, d, err)) return false;
    Memory mem;
    std::unique_ptr<Renderer> backend = createBackend(opt.render, mem, err).renderer;
    if (!backend) return false;
    GeEngine eng(mem, backend.get());
    debug::Breakpoints bp;
    AfterCapture after(eng, out);
    u64 seen = 0, commands = 0;
    std::vector<std::pair<std::string, Image>> images;
    // Every command is offered to onBreak (kNextCommand stays pending while it answers "go on").
    bp.breakOnce(debug::kNextCommand);
    bp.onBreak = [&](u32 pc, u32 word) {
        ++commands;
        if (out.hit) return false;
        const u8 op = u8(word >> 24);
        bool match = false;
        switch (spec.kind) {
        case BreakSpec::Draw: match = debug::isDrawKick(word); break;
        case BreakSpec::Prim: match = op == GE_CMD_PRIM; break;
        case BreakSpec::Op: match = op == spec.value; break;
        case BreakSpec::Addr: match = Memory::normalize(pc) == spec.value; break;
        case BreakSpec::Command: match = true; break;
        }
        if (!match || ++seen < spec.nth) return false;
        out.hit = true;
        eng.renderer()->flushToMemory();  // textures drawn by earlier draws are read from memory
        std::string& r = out.report;
        r += fmt("break: %s #%llu at 0x%08x (command %llu, draw %llu of the frame so far)\n", opt.breakAt.c_str(),
                 (unsigned long long)spec.nth, pc, (unsigned long long)commands, (unsigned long long)bp.draws());
        r += "\n== list ==\n" + debug::listText(eng.list(), eng.state());
        r += "\n== disassembly ==\n" + debug::disassembly(mem, pc - 16, 16, pc);
        std::vector<debug::DrawVertex> verts;
        std::string verr;
        geo::AccuracyProfile acc;
        geo::AccuracyProfile::fromName(opt.render.accuracy.c_str(), acc);  // checked by createBackend above
        if (op == GE_CMD_PRIM && debug::drawVertices(mem, eng.state(), word, acc, verts, verr)) {
            r += fmt("\n== vertices (%zu) ==\n", verts.size());
            r += "   #        pos (decoded)              uv           colour  ->   screen x, y, z        s, t       colour out\n";
            for (size_t i = 0; i < verts.size(); ++i) {
                const debug::DrawVertex& v = verts[i];
                r += fmt("%4zu %9.3f %9.3f %9.3f  %7.3f %7.3f  %02x%02x%02x%02x -> %8.3f %8.3f %5d  %7.4f %7.4f  %02x%02x%02x%02x%s\n", i,
                         double(v.in.pos[0]), double(v.in.pos[1]), double(v.in.pos[2]), double(v.in.uv[0]), double(v.in.uv[1]),
                         v.in.color[0], v.in.color[1], v.in.color[2], v.in.color[3], double(v.screenX), double(v.screenY),
                         v.screenZ, double(v.s), double(v.t), v.color[0], v.color[1], v.color[2], v.color[3],
                         v.outside ? "  (outside: dropped)" : "");
            }
        } else if (op == GE_CMD_PRIM) {
            r += "\n== vertices ==\n" + verr + "\n";
        }
        const GeState& st = eng.state();
        if (st.TME_on()) {
            r += fmt("\n== texture ==\nformat %u, levels 0-%u, level 0 %ux%u at 0x%08x\n", u32(st.textureFormat()),
                     st.TMODE_maxlevel(), st.textureWidth(0), st.textureHeight(0), st.textureAddr(0));
            for (u32 l = 0; l <= st.TMODE_maxlevel() && !opt.outDir.empty(); ++l) {
                u32 w = 0, h = 0;
                std::vector<u8> rgba;
                if (!debug::readTexture(mem, st, int(l), w, h, rgba)) continue;
                Image img;
                img.width = int(w), img.height = int(h);
                for (size_t i = 0; i < rgba.size(); i += 4)
                    img.rgba.push_back(u32(rgba[i]) | u32(rgba[i + 1]) << 8 | u32(rgba[i + 2]) << 16 | u32(rgba[i + 3]) << 24);
                images.emplace_back(fmt("texture-L%u.png", l), img);
            }
        }
        const std::vector<u32> clut = debug::readClut(st);
        r += fmt("\n== CLUT ==\n%zu entries decoded, format %u, %u bytes loaded; first 8:", clut.size(), st.CLUT_format(),
                 st.clutLoadedBytes);
        for (size_t i = 0; i < 8; ++i) r += fmt(" %08x", clut[i]);
        r += "\n";
        if (!opt.outDir.empty()) {
            Image img;
            img.width = 16, img.height = int(clut.size() / 16);
            img.rgba = clut;
            images.emplace_back("clut.png", img);
        }
        r += "\n== registers and matrices ==\n" + debug::stateText(st);
        after.armed = true;
        return false;  // take it in place and go on
    };
    eng.addObserver(&bp);
    eng.addObserver(&after);
    dump::ReplayOptions ro;
    ro.timing = opt.render.replayTiming;
    ro.maxGeMs = opt.render.maxGeMs;
    dump::ReplayResult res;
    if (!dump::replayDump(d, eng, ro, res, err)) return false;
    if (out.hit && !after.done) after.capture();  // the break's command was the frame's last
    if (!opt.outDir.empty() && out.hit) {
        std::error_code ec;
        std::filesystem::create_directories(opt.outDir, ec);
        images.emplace_back("color.png", out.color);
        images.emplace_back("depth.png", out.depth);
        images.emplace_back("stencil.png", out.stencil);
        for (auto& [name, img] : images) {
            if (img.rgba.empty()) continue;
            if (!writePng((std::filesystem::path(opt.outDir) / name).string(), img, err)) return false;
            out.report += "wrote " + (std::filesystem::path(opt.outDir) / name).string() + "\n";
        }
    }
    return true;
}

}  // namespace ge::tools
