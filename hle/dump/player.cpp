#include "hle/dump/player.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

namespace ge::dump {

namespace {

bool isKick(u8 op) { return op == GE_CMD_PRIM || op == GE_CMD_BEZIER || op == GE_CMD_SPLINE; }

constexpr u32 kListBase = 0x08000000;       // 1 MiB display-list buffer
constexpr u32 kListEnd = 0x08100000;
constexpr u32 kArenaBase = kListEnd;        // payloads from here to the end of RAM
constexpr u32 kSlabSize = 1u << 20;         // PPSSPP's push-buffer mapping granularity
constexpr u32 kTailMax = 64u << 10;         // bytes after a texture/CLUT payload kept readable

u32 cmd(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

class Replayer {
public:
    Replayer(const Dump& d, ReplayTarget& t, const ReplayOptions& opt, ReplayResult& res)
        : d_(d), t_(t), opt_(opt), res_(res) {}

    bool play(std::string& err);

private:
    // Copies a payload into free guest RAM, 4- or 16-byte aligned; identical payloads share one
    // copy. Returns 0 when it does not fit. With `withTail`, the push-buffer bytes that follow the
    // payload (to the end of its 1 MiB slab, at most kTailMax) are copied after it: PPSSPP's player
    // maps whole 1 MiB slabs of the push buffer into guest memory, so a texture read past its
    // recorded size (a DXT texture whose rows run beyond bufw, NFS Carbon) sees the dump's next
    // bytes, and the references were rendered that way. A payload that straddles two slabs gets
    // an exact copy there too, so it gets no tail here.
    u32 place(const Record& r, u32 align, bool withTail = false);
    void appendWords(const std::vector<u32>& words);
    void runSoFar();
    void hostWrite(u32 addr, const u8* data, u32 size) {
        if (t_.write(addr, data, size) < size) warn("a VRAM copy in the dump runs past the end of memory");
    }
    void writeWord(u32 addr, u32 w) {
        u8 b[4];
        writeLE32(b, w);
        t_.write(addr, b, 4);
    }
    void queueBaseFor(u32 a) {
        if ((a >> 24) != lastBase_) {
            pending_.push_back(cmd(GE_CMD_BASE, (a >> 8) & 0xFF0000));
            lastBase_ = a >> 24;
        }
    }
    void warn(const std::string& w) {
        if (res_.warning.empty()) res_.warning = w;
    }

    const Dump& d_;
    ReplayTarget& t_;
    const ReplayOptions& opt_;
    ReplayResult& res_;

    std::vector<u32> pending_;
    u32 writePos_ = kListBase;
    u32 arenaPos_ = kArenaBase;
    std::map<std::tuple<u32, u32, u32>, u32> placed_;
    u32 lastTex_[8] = {}, lastBufw_[8] = {};
    u32 lastBase_ = ~0u;  // unknown
    bool clutAddrPending_ = false;
    u32 clutAddr_ = 0, clutFlags_ = 0;
    u32 memcpyDest_ = 0;
    u64 kicks_ = 0;
    bool stopped_ = false;  // --replay-end reached
};

u32 Replayer::place(const Record& r, u32 align, bool withTail) {
    const u8* p = d_.payload(r);
    if (!p) return 0;
    auto key = std::make_tuple(r.ptr, r.size, align);
    if (auto it = placed_.find(key); it != placed_.end()) return it->second;
    u32 tail = 0;
    if (withTail && r.size) {
        const u64 end = u64(r.ptr) + r.size;  // payload() checked it lies in pushbuf
        const u64 slabEnd = (u64(r.ptr) / kSlabSize + 1) * kSlabSize;
        if ((end - 1) / kSlabSize == u64(r.ptr) / kSlabSize)
            tail = u32(std::min<u64>({slabEnd, u64(d_.pushbuf.size()), end + kTailMax}) - end);
    }
    const u64 ramEnd = u64(Memory::kRamBase) + t_.ramSize();
    u32 a = (arenaPos_ + align - 1) & ~(align - 1);
    if (u64(a) + r.size + tail > ramEnd) {
        // Wrap around: everything placed before has been consumed by the list already run
        // (each REGISTERS block runs at once), except the pending block's own data.
        placed_.clear();
        a = kArenaBase;
        if (u64(a) + r.size > ramEnd) return 0;
        tail = u32(std::min<u64>(tail, ramEnd - a - r.size));
    }
    t_.write(a, p, r.size + tail);
    arenaPos_ = a + r.size + tail;
    placed_[key] = a;
    return a;
}

void Replayer::appendWords(const std::vector<u32>& words) {
    size_t i = 0;
    while (i < words.size()) {
        // Room for a chunk plus the BASE + JUMP that wrap the buffer.
        u32 room = (kListEnd - writePos_) / 4;
        if (room <= 2) {
            writeWord(writePos_, cmd(GE_CMD_BASE, (kListBase >> 8) & 0xFF0000));
            writeWord(writePos_ + 4, cmd(GE_CMD_JUMP, kListBase & 0xFFFFFF));
            writePos_ = kListBase;
            lastBase_ = kListBase >> 24;
            // Let the GE follow the jump before the start of the buffer is overwritten.
            t_.runTo(writePos_, 16);
            continue;
        }
        size_t n = std::min<size_t>(words.size() - i, room - 2);
        std::vector<u8> bytes(4 * n);
        for (size_t k = 0; k < n; ++k) writeLE32(&bytes[4 * k], words[i + k]);
        t_.write(writePos_, bytes.data(), u32(bytes.size()));
        writePos_ += u32(4 * n);
        i += n;
        if (i < words.size()) runSoFar();
    }
}

void Replayer::runSoFar() {
    // Blocks never branch backwards in a sound dump; a generous budget turns a corrupt loop into
    // an error instead of a hang.
    RunStatus s = t_.runTo(writePos_, u64(kListEnd - kListBase) / 4 * 4 + 4096);
    if (s == RunStatus::Stalled) return;
    ++res_.listErrors;
    char buf[160];
    std::snprintf(buf, sizeof buf, "display list stopped (%s%s%s) before the end of the recorded commands",
                  runStatusName(s), s == RunStatus::Error ? ": " : "",
                  s == RunStatus::Error ? t_.lastError().c_str() : "");
    warn(buf);
    // Restart the list where the player writes next, keeping all state.
    t_.startList(writePos_, writePos_);
}

bool Replayer::play(std::string& err) {
    if (d_.records.empty() || d_.records[0].type != INIT) {
        err = "dump does not start with an INIT record";
        return false;
    }
    // The first INIT is applied before the list starts, as a game restores a context before it
    // enqueues (sceGeRestoreContext fails while the GE is drawing).
    bool started = false;
    auto startOnce = [&] {
        if (started) return;
        started = true;
        // §6.1: the list starts with one NOP, stalled at its end.
        writeWord(writePos_, 0);
        writePos_ += 4;
        t_.startList(kListBase, writePos_);
        t_.runTo(writePos_, 16);
    };

    const Record* prev = nullptr;
    for (size_t ri = 0; ri < d_.records.size() && !stopped_; ++ri) {
        if (ri > 0) startOnce();
        const Record& r = d_.records[ri];
        ++res_.records;
        const u8* p = d_.payload(r);
        if (!p && r.size) {
            warn(std::string("record ") + recordTypeName(r.type) + " points outside the push buffer");
            prev = &r;
            continue;
        }
        const int texLevel = textureLevelOf(r.type), fbLevel = framebufLevelOf(r.type);
        if (texLevel >= 0) {
            u32 a = place(r, 16, true);
            if (a && a != lastTex_[texLevel]) {
                pending_.push_back(cmd(GE_CMD_TBW0 + texLevel, ((a >> 8) & 0xFF0000) | lastBufw_[texLevel]));
                pending_.push_back(cmd(GE_CMD_TBP0 + texLevel, a & 0xFFFFFF));
                lastTex_[texLevel] = a;
            }
        } else if (fbLevel >= 0) {
            const u32 v = d_.payloadWord(r, 0), bufw = d_.payloadWord(r, 1), flags = d_.payloadWord(r, 2);
            if (v != lastTex_[fbLevel] || bufw != lastBufw_[fbLevel]) {
                pending_.push_back(cmd(GE_CMD_TBW0 + fbLevel, ((v >> 8) & 0xFF0000) | (bufw & 0xFFFF)));
                pending_.push_back(cmd(GE_CMD_TBP0 + fbLevel, v & 0xFFFFFF));
                lastTex_[fbLevel] = v;
                lastBufw_[fbLevel] = bufw;
            }
            // Flag bit 1 ("unchanged VRAM") is trustworthy from version 6 on (§3.3). Flag bit 0
            // ("target": a buffer drawn earlier in this recording) is skipped too: both our backends
            // keep what they drew, as PPSSPP's software renderer does (§6.2), and the recorded bytes
            // would overwrite the frame with what the recording GPU had at that moment.
            if (r.size > 16 && !(d_.version >= 6 && (flags & 2)) && !(flags & 1)) hostWrite(v, p + 16, r.size - 16);
        } else {
            switch (r.type) {
            case INIT: {
                u32 ctx[512] = {};
                if (r.size < kInitBytes) warn("short INIT record");
                std::memcpy(ctx, p, std::min<u32>(r.size, kInitBytes));
                // The running list's OFFSET is its own, starting at 0 (§6.1).
                ctx[7] = 0;
                t_.loadContext(ctx);
                for (int i = 0; i < 8; ++i) lastTex_[i] = lastBufw_[i] = 0;
                lastBase_ = ~0u;
                break;
            }
            case REGISTERS: {
                std::vector<u32> words;
                words.swap(pending_);
                const u32 n = r.size / 4;
                words.reserve(words.size() + n);
                for (u32 i = 0; i < n; ++i) {
                    u32 w = readLE32(p + 4 * i);
                    const u8 op = u8(w >> 24);
                    if (op >= GE_CMD_TBP0 && op <= GE_CMD_TBP7) {
                        w = 0;  // texture addresses come from the data records
                    } else if (op >= GE_CMD_TBW0 && op <= GE_CMD_TBW7) {
                        const int lv = op - GE_CMD_TBW0;
                        const u32 width = w & 0xFFFF;
                        if (width == lastBufw_[lv]) w = 0;
                        else w = cmd(op, ((lastTex_[lv] >> 8) & 0xFF0000) | width);
                        lastBufw_[lv] = width;
                    } else if (op == GE_CMD_SIGNAL || op == GE_CMD_BASE) {
                        lastBase_ = ~0u;
                    }
                    words.push_back(w);
                    if (isKick(op)) {
                        ++kicks_;
                        if (opt_.replayEnd && kicks_ >= opt_.replayEnd) {
                            stopped_ = true;
                            break;
                        }
                    }
                }
                appendWords(words);
                runSoFar();
                break;
            }
            case VERTICES:
            case INDICES: {
                u32 a = place(r, 4);
                if (!a) {
                    warn("vertex/index data does not fit in guest RAM");
                    break;
                }
                queueBaseFor(a);
                pending_.push_back(cmd(r.type == VERTICES ? GE_CMD_VADR : GE_CMD_IADR, a & 0xFFFFFF));
                break;
            }
            case CLUTADDR:
                clutAddrPending_ = true;
                clutAddr_ = d_.payloadWord(r, 0);
                clutFlags_ = d_.payloadWord(r, 1);
                break;
            case CLUT:
                if (clutAddrPending_) {
                    if (!(clutFlags_ & 1)) hostWrite(clutAddr_, p, r.size);  // same rule as FRAMEBUF
                    clutAddrPending_ = false;
                } else {
                    u32 a = place(r, 16, true);
                    if (a) {
                        pending_.push_back(cmd(GE_CMD_CBW, (a >> 8) & 0xFF0000));
                        pending_.push_back(cmd(GE_CMD_CBP, a & 0xFFFFFF));
                        // The palette at recording start (newer v6 dumps): load it into palette
                        // RAM, which matches the recording's state (§6.4).
                        if (prev && prev->type == INIT) pending_.push_back(cmd(GE_CMD_CLOAD, std::min<u32>(r.size / 32, 32)));
                    }
                }
                break;
            case TRANSFERSRC: {
                u32 a = place(r, 16);
                runSoFar();
                if (a) {
                    const u32 xbw1 = t_.readRegister(GE_CMD_XBW1);
                    pending_.push_back(cmd(GE_CMD_XBW1, (xbw1 & 0xFFFF) | ((a >> 8) & 0xFF0000)));
                    pending_.push_back(cmd(GE_CMD_XBP1, a & 0xFFFFFF));
                }
                break;
            }
            case MEMSET: {
                runSoFar();
                const u32 dest = d_.payloadWord(r, 0), value = d_.payloadWord(r, 1), size = d_.payloadWord(r, 2);
                if (Memory::isVram(dest)) t_.fill(dest, u8(value), size);
                break;
            }
            case MEMCPYDEST: memcpyDest_ = d_.payloadWord(r, 0); break;
            case MEMCPYDATA:
                runSoFar();
                if (Memory::isVram(memcpyDest_)) hostWrite(memcpyDest_, p, r.size);
                break;
            case EDRAMTRANS:
                runSoFar();
                if (!t_.setEdramTranslation(d_.payloadWord(r, 0))) warn("invalid eDRAM translation value");
                break;
            case DISPLAY:
                runSoFar();
                res_.hasDisplay = true;
                res_.displayAddr = d_.payloadWord(r, 0);
                res_.displayStride = d_.payloadWord(r, 1);
                res_.displayFormat = d_.payloadWord(r, 2) & 0xFF;  // §3.2: mask the format
                break;
            default: {
                char buf[64];
                std::snprintf(buf, sizeof buf, "unknown record type 0x%02x (record %zu)", r.type, ri);
                err = buf;
                t_.finishFrame();
                return false;
            }
            }
        }
        prev = &r;
    }
    startOnce();
    // §6.3: finish the list and wait for it.
    std::vector<u32> tail;
    tail.swap(pending_);
    tail.push_back(cmd(GE_CMD_FINISH, 0));
    tail.push_back(cmd(GE_CMD_END, 0));
    appendWords(tail);
    RunStatus s = t_.runTo(writePos_, u64(kListEnd - kListBase) / 4 * 4 + 4096);
    if (s != RunStatus::Completed) {
        ++res_.listErrors;
        warn(std::string("final list ended as '") + runStatusName(s) + "'");
    }
    res_.draws = kicks_;
    t_.finishFrame();
    return true;
}

}  // namespace

DumpSummary summarize(const Dump& d) {
    DumpSummary s;
    for (const Record& r : d.records) {
        if (r.type < 32) ++s.recordsByType[r.type];
        if (!isKnownRecordType(r.type)) ++s.unknownRecords;
        if (r.type != REGISTERS) continue;
        const u8* p = d.payload(r);
        if (!p) continue;
        for (u32 i = 0; i < r.size / 4; ++i) {
            const u8 op = p[4 * i + 3];
            ++s.commands;
            if (op == GE_CMD_PRIM) ++s.prims;
            if (op == GE_CMD_BEZIER || op == GE_CMD_SPLINE) ++s.patches;
            if (op == GE_CMD_XSTART) ++s.transfers;
            if (op == GE_CMD_CLOAD) ++s.clutLoads;
        }
    }
    s.draws = s.prims + s.patches;
    return s;
}

void displayedFramebuffer(const ReplayResult& r, const GeState& st, u32& addr, u32& stride, u32& format) {
    if (r.hasDisplay) {
        addr = r.displayAddr;
        stride = r.displayStride;
        format = r.displayFormat & 3;
    } else {
        addr = st.framebufAddr();
        stride = st.framebufStride();
        format = st.framebufFormat();
    }
    if (stride == 0 || stride > 1024) stride = 512;
}

u32 EngineTarget::write(u32 addr, const void* data, u32 size) {
    Memory& mem = eng_.memory();
    const u32 n = mem.validSize(addr, size);
    if (!n) return 0;
    eng_.renderer()->syncMemoryForRead(addr, n);
    mem.write(addr, data, n);
    eng_.renderer()->memoryWritten(addr, n);
    return n;
}

u32 EngineTarget::fill(u32 addr, u8 value, u32 size) {
    Memory& mem = eng_.memory();
    const u32 n = mem.validSize(addr, size);
    if (!n) return 0;
    eng_.renderer()->syncMemoryForRead(addr, n);
    mem.fill(addr, value, n);
    eng_.renderer()->memoryWritten(addr, n);
    return n;
}

bool replayDump(const Dump& d, ReplayTarget& target, const ReplayOptions& opt, ReplayResult& result, std::string& err) {
    result = ReplayResult{};
    Replayer r(d, target, opt, result);
    return r.play(err);
}

bool replayDump(const Dump& d, GeEngine& engine, const ReplayOptions& opt, ReplayResult& result, std::string& err) {
    EngineTarget t(engine);
    return replayDump(d, t, opt, result, err);
}

}  // namespace ge::dump
