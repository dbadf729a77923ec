// SPDX-License-Identifier: MIT
// fuzz_seeds: writes seed corpora for the harnesses that do not take a dump as such, from the
// project's dumps (and any others given): each dump is replayed with the dump player on a
// GeEngine whose renderer records, per distinct vertex format / texture format / patch, an input
// in the format of the vertex (f), texture (e) and spline (g) harnesses; the dump's REGISTERS
// words become a display list for the list (d) and C ABI (h) harnesses, and the GE at the end of
// the frame a save-state payload for the save-state harness (i).
//
// Every dump is also written in the replay harnesses' uncompressed "open" form (fuzz_common.h).
//
// The loader harness gets the files themselves (and the .ppdmp inside each zip), up to 1 MiB.
//
// Usage: fuzz_seeds OUTDIR DUMP...
//        (writes OUTDIR/{load,replay,list,texture,vertex,spline,api,savestate}/NAME-N)
// The input formats are those described at the top of each harness.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "hle/savestate.h"
#include "hle/texture_decoder.h"
#include "hle/vertex_decoder.h"
#include "tests/fuzz/fuzz_common.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

constexpr size_t kSeedMax = 64 << 10;

void put8(std::vector<u8>& v, u32 x) { v.push_back(u8(x)); }
void put16(std::vector<u8>& v, u32 x) { put8(v, x), put8(v, x >> 8); }
void put32(std::vector<u8>& v, u32 x) { put16(v, x), put16(v, x >> 16); }
u32 cmd(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

// The state a vertex or patch draw depends on, as command words (matrices uploaded in full),
// at most 255 (the harnesses' count byte).
std::vector<u32> stateWords(const GeState& st, u32 vtype) {
    std::vector<u32> w;
    auto matrix = [&](u8 num, u8 dat, const float* m, int n) {
        w.push_back(cmd(num, 0));
        for (int i = 0; i < n; ++i) w.push_back(cmd(dat, toFloat24(m[i])));
    };
    matrix(GE_CMD_WORLDN, GE_CMD_WORLDD, st.world, 12);
    matrix(GE_CMD_VIEWN, GE_CMD_VIEWD, st.view, 12);
    matrix(GE_CMD_PROJN, GE_CMD_PROJD, st.proj, 16);
    if (st.TMAP_mode() == 1) matrix(GE_CMD_TGENN, GE_CMD_TGEND, st.tgen, 12);
    const u32 wc = (vtype >> 9) & 3 ? ((vtype >> 14) & 7) + 1 : 0;
    if (wc) matrix(GE_CMD_BONEN, GE_CMD_BONED, st.bone, int(12 * wc));
    const std::pair<int, int> ranges[] = {{0x13, 0x1F}, {0x2C, 0x33}, {0x36, 0x38}, {0x42, 0x4D},
                                          {0x50, 0x9F}, {0xC0, 0xC1}, {0xCD, 0xCE}, {0xD4, 0xD6}};
    for (auto [a, b] : ranges)
        for (int op = a; op <= b && w.size() < 255; ++op)
            if (st.regs[size_t(op)]) w.push_back(st.regs[size_t(op)]);
    w.resize(std::min<size_t>(w.size(), 255));
    return w;
}

struct Seeds {
    fs::path dir;
    std::string name;
    int n = 0;
    void write(const char* harness, const std::vector<u8>& bytes, size_t max = kSeedMax) {
        if (bytes.size() > max) return;
        const fs::path d = dir / harness;
        fs::create_directories(d);
        std::ofstream f(d / (name + "-" + std::to_string(n++)), std::ios::binary);
        f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
};

// Guest bytes [addr, addr + size), zeros where memory is not valid.
std::vector<u8> grab(const Memory& mem, u32 addr, u32 size) {
    std::vector<u8> out(size, 0);
    for (u32 i = 0; i < size; ++i) out[i] = mem.read8(addr + i);
    return out;
}

class Tap : public Renderer {
public:
    Tap(Memory& mem, Seeds& s) : mem_(mem), s_(s) {}

    void drawPrim(const PrimPacket& p) override {
        const GeState& st = *p.state;
        if (st.TME_on() && !st.isClearMode()) texture(st);
        if (!vertexKinds_.insert({p.vtype, u32(p.prim)}).second || p.count == 0) return;
        VertexReader reader(mem_, st, p.vtype);
        std::vector<u32> idx;
        if (!reader.readIndices(p.indexAddr, std::min<u32>(p.count, 512), idx)) return;
        u32 hi = 0;
        for (u32 i : idx) hi = std::max(hi, i);
        const u32 vbytes = std::min<u32>((hi + 1) * reader.stride(), 48 << 10);
        const u32 ibytes = u32(idx.size()) * reader.indexSize();
        std::vector<u8> v;
        put32(v, p.vtype);
        put16(v, std::min<u32>(p.count, 512));
        put8(v, u32(p.prim));
        put8(v, 0);
        put32(v, (vbytes + 3) & ~3u);  // index offset
        put32(v, 0x3F000000);          // t = 0.5
        const std::vector<u32> w = stateWords(st, p.vtype);
        put8(v, u32(w.size()));
        for (u32 x : w) put32(v, x);
        std::vector<u8> data = grab(mem_, p.vertexAddr, vbytes);
        data.resize((vbytes + 3) & ~3u, 0);
        if (ibytes) {
            const std::vector<u8> ib = grab(mem_, p.indexAddr, ibytes);
            data.insert(data.end(), ib.begin(), ib.end());
        }
        v.insert(v.end(), data.begin(), data.end());
        s_.write("vertex", v);
    }

    void drawPatch(const PatchPacket& p) override {
        const GeState& st = *p.state;
        if (!patchKinds_.insert({p.vtype, p.spline, p.patchPrim}).second) return;
        VertexReader reader(mem_, st, p.vtype);
        const u32 n = p.ucount * p.vcount;
        std::vector<u32> idx;
        if (!reader.readIndices(p.indexAddr, n, idx)) return;
        u32 hi = 0;
        for (u32 i : idx) hi = std::max(hi, i);
        const u32 vbytes = std::min<u32>((hi + 1) * reader.stride(), 48 << 10);
        std::vector<u8> v;
        put8(v, u32(p.spline) | (p.patchPrim << 1) | (u32(p.reverseFace) << 3));
        put8(v, p.ucount);
        put8(v, p.vcount);
        put8(v, p.uknot | (p.vknot << 2));
        put8(v, p.divU);
        put8(v, p.divV);
        const u32 ioff = (vbytes + 3) & ~3u;
        put16(v, ioff);
        put32(v, p.vtype);
        const std::vector<u32> w = stateWords(st, p.vtype);
        put8(v, u32(w.size()));
        for (u32 x : w) put32(v, x);
        std::vector<u8> data = grab(mem_, p.vertexAddr, vbytes);
        data.resize(ioff, 0);
        if (reader.indexSize()) {
            const std::vector<u8> ib = grab(mem_, p.indexAddr, n * reader.indexSize());
            data.insert(data.end(), ib.begin(), ib.end());
        }
        v.insert(v.end(), data.begin(), data.end());
        s_.write("spline", v);
    }

    void drawImmediate(const ImmPacket&) override {}

private:
    void texture(const GeState& st) {
        const u32 fmt = st.TPF_format();
        if (!textureKinds_.insert({fmt, st.regs[GE_CMD_TSIZE0], st.TMODE_swizzle()}).second) return;
        const u32 maxLevel = st.TMODE_maxlevel();
        std::vector<u8> data;
        for (u32 l = 0; l <= maxLevel; ++l) {
            const u32 bytes = std::min<u32>(textureLevelBytes(st, int(l)), 48 << 10);
            const std::vector<u8> b = grab(mem_, st.textureAddr(int(l)), bytes);
            data.insert(data.end(), b.begin(), b.end());
        }
        data.resize((data.size() + 15) & ~size_t(15), 0);
        const u32 clutOffset = u32(data.size());
        data.insert(data.end(), st.clut, st.clut + st.clutLoadedBytes);
        std::vector<u8> v;
        put8(v, fmt);
        put8(v, (st.TMODE_swizzle() << 2) | (maxLevel << 3) | (u32(st.TMODE_multiclut()) << 6));
        put8(v, st.TSIZE_wlog(0) | (st.TSIZE_hlog(0) << 4));
        u8 shrink = 0;  // levels that keep the previous level's size
        for (u32 l = 1; l < 8; ++l)
            if (st.regs[size_t(GE_CMD_TSIZE0 + l)] == st.regs[size_t(GE_CMD_TSIZE0 + l - 1)]) shrink |= u8(1 << (l - 1));
        put8(v, shrink);
        put16(v, st.TBW_width(0));
        const u32 clut = st.op(GE_CMD_CLUT);
        put16(v, clut);
        put8(v, clut >> 16);
        put8(v, st.clutLoadedBytes / 32);
        put16(v, clutOffset / 16);
        put32(v, 0);  // gap
        put8(v, 0);
        const u8 extra[] = {GE_CMD_TFILTER, GE_CMD_TWRAP, GE_CMD_TLEVEL, GE_CMD_TSLOPE};
        put8(v, 4);
        for (u8 op : extra) put32(v, st.regs[op]);
        const float pts[8][4] = {{0, 0, 0, 1},       {0.5f, 0.5f, 0, 1}, {1, 1, 1, 1},       {0.25f, 0.75f, 2, 2},
                                 {-0.5f, 1.5f, 0, 1}, {0.1f, 0.9f, 3, 1}, {0.99f, 0.01f, 0, 4}, {2.5f, -3.5f, 1, 1}};
        for (const auto& p : pts)
            for (float f : p) {
                u32 bits;
                std::memcpy(&bits, &f, 4);
                put32(v, bits);
            }
        v.insert(v.end(), data.begin(), data.end());
        s_.write("texture", v);
    }

    Memory& mem_;
    Seeds& s_;
    std::set<std::pair<u32, u32>> vertexKinds_;
    std::set<std::tuple<u32, bool, u32>> patchKinds_;
    std::set<std::tuple<u32, u32, bool>> textureKinds_;
};

// The dump's REGISTERS words as one list (texture addresses dropped as the player drops them),
// FINISH + END appended.
std::vector<u32> listWords(const dump::Dump& d, size_t maxWords) {
    std::vector<u32> w;
    for (const dump::Record& r : d.records) {
        if (r.type != dump::REGISTERS) continue;
        const u8* p = d.payload(r);
        if (!p) continue;
        for (u32 i = 0; i + 4 <= r.size && w.size() < maxWords; i += 4) {
            const u32 x = readLE32(p + i);
            const u8 op = u8(x >> 24);
            if (op == GE_CMD_FINISH || op == GE_CMD_END || op == GE_CMD_JUMP || op == GE_CMD_CALL) continue;
            w.push_back(x);
        }
    }
    w.push_back(cmd(GE_CMD_FINISH, 0));
    w.push_back(cmd(GE_CMD_END, 0));
    return w;
}

void listSeeds(const dump::Dump& d, Seeds& s) {
    const std::vector<u32> words = listWords(d, 12000);
    std::vector<u8> v;
    put8(v, 0);  // RAM start, no stall
    put8(v, 0);
    put16(v, 0);
    put32(v, 256);
    for (u32 x : words) put32(v, x);
    s.write("list", v);
    v[0] = 4;  // the same against a moving stall address
    s.write("list", v);

    // The C ABI: write the list in 4 KiB pieces, enqueue it, wait for it, read a frame, peek.
    std::vector<u8> a;
    put8(a, 0);          // 64 MiB RAM
    put8(a, 0xC0);       // SDK 6.60
    put16(a, 0xFFF);     // wait budget
    const size_t bytes = words.size() * 4;
    for (size_t off = 0; off < bytes && a.size() + 4200 < kSeedMax; off += 4092) {
        const size_t len = std::min<size_t>(4092, bytes - off);
        put8(a, 0);  // mem_write
        put8(a, 2);  // 0x08800000 + offset
        put32(a, u32(off));
        put16(a, u32(len));
        for (size_t k = 0; k < len; ++k) put8(a, u8(words[(off + k) / 4] >> (8 * ((off + k) % 4))));
    }
    put8(a, 9);  // set_callback
    for (int k = 0; k < 4; ++k) put32(a, 0x08900000 + 16 * k);
    put8(a, 1);  // enqueue 0x08800000, no stall, cbid 0, args with a context at 0x08A00000
    put8(a, 2);
    put32(a, 0);
    put8(a, 0);
    put8(a, 0);
    put8(a, 16 | 2 | 1);
    put8(a, 2);
    put32(a, 0x200000);
    put8(a, 6);  // draw_sync wait
    put8(a, 0);
    put8(a, 1);
    put8(a, 5);  // list_sync peek on the first ID
    put8(a, 0);
    put8(a, 1);
    put8(a, 18);  // read_frame 64×64 at VRAM start, stride 512, 8888
    put8(a, 1);
    put32(a, 0);
    put16(a, 512);
    put8(a, 3);
    put8(a, 64);
    put8(a, 64);
    put8(a, 0);
    put8(a, 11);  // save_context
    put8(a, 15);  // get_cmd PRIM, get_matrix world
    put8(a, 4);
    put8(a, 8);
    s.write("api", a);
}

// Short dumps cut from a long one: the INIT record, then a run of consecutive records with their
// payloads moved into a push buffer of their own, about `maxBytes` each; at most `count` of them,
// spread over the frame. (A replay harness draws only a few milliseconds of GE time per input,
// so a whole frame's later draws would never run.)
std::vector<dump::Dump> pieces(const dump::Dump& d, size_t maxBytes, size_t count) {
    std::vector<dump::Dump> all;
    if (d.records.empty() || d.records[0].type != dump::INIT) return all;
    size_t i = 1;
    while (i < d.records.size() || all.empty()) {
        dump::Dump p;
        p.version = d.version;
        p.gameId = d.gameId;
        std::map<std::pair<u32, u32>, u32> moved;
        auto add = [&](const dump::Record& r) {
            dump::Record q = r;
            if (r.size && d.payloadInRange(r)) {
                auto [it, fresh] = moved.try_emplace({r.ptr, r.size}, 0);
                if (fresh) {
                    p.pushbuf.resize((p.pushbuf.size() + 15) & ~size_t(15), 0);
                    it->second = u32(p.pushbuf.size());
                    const u8* b = d.payload(r);
                    p.pushbuf.insert(p.pushbuf.end(), b, b + r.size);
                }
                q.ptr = it->second;
            }
            p.records.push_back(q);
        };
        add(d.records[0]);
        size_t bytes = 3 + dump::kRecordBytes + dump::kInitBytes;
        while (i < d.records.size()) {
            const dump::Record& r = d.records[i];
            const size_t cost = dump::kRecordBytes + (d.payloadInRange(r) ? r.size : 0);
            if (p.records.size() > 1 && bytes + cost > maxBytes) break;
            add(r);
            bytes += cost;
            ++i;
        }
        all.push_back(std::move(p));
    }
    if (all.size() <= count) return all;
    std::vector<dump::Dump> some;
    for (size_t k = 0; k < count; ++k) some.push_back(std::move(all[k * all.size() / count]));
    return some;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: fuzz_seeds OUTDIR DUMP...\n");
        return 2;
    }
    int bad = 0;
    for (int i = 2; i < argc; ++i) {
        dump::Dump d;
        std::string err;
        if (!dump::loadDump(argv[i], d, err)) {
            std::fprintf(stderr, "fuzz_seeds: %s\n", err.c_str());
            ++bad;
            continue;
        }
        Seeds s;
        s.dir = argv[1];
        s.name = fs::path(argv[i]).filename().string();
        for (char& c : s.name)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
        // The loader harness: the file as it is and, for a zip, the .ppdmp inside.
        {
            std::ifstream f(argv[i], std::ios::binary);
            std::error_code ec;
            std::vector<u8> bytes(size_t(fs::file_size(argv[i], ec)));
            f.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
            bytes.resize(size_t(f.gcount()));
            s.write("load", bytes, fuzz::kMaxInput);
            std::vector<u8> raw;
            if (bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] == 'K' &&
                dump::extractPpdmpFromZip(bytes.data(), bytes.size(), raw, err))
                s.write("load", raw, fuzz::kMaxInput);
        }
        Memory mem;
        Tap tap(mem, s);
        GeEngine eng(mem, &tap);
        dump::ReplayOptions opt;
        dump::ReplayResult res;
        dump::replayDump(d, eng, opt, res, err);
        {
            // The save-state harness: the GE at the end of the frame, as a payload (mode 1).
            SceGe sce(eng);
            std::vector<u8> st = savestate::save(eng, sce, nullptr, {});
            st.erase(st.begin(), st.begin() + savestate::kHeaderSize);
            st.insert(st.begin(), u8(1));
            s.write("savestate", st);
        }
        listSeeds(d, s);
        for (const dump::Dump& p : pieces(d, 48 << 10, 4)) s.write("replay", fuzz::toOpenForm(p), fuzz::kMaxInput);
    }
    return bad ? 1 : 0;
}
