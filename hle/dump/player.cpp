// SPDX-License-Identifier: MIT
#include "hle/dump/player.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <unordered_map>
#include <vector>

#include "hle/dump/replay_memory.h"
#include "hle/ge_time.h"

namespace ge::dump {

namespace {

bool isKick(u8 op) { return op == GE_CMD_PRIM || op == GE_CMD_BEZIER || op == GE_CMD_SPLINE; }

// PPSSPP's player: a 256 KiB list buffer from the top of user memory, payloads mapped from the
// bottom (replay_memory.h). User memory is that of a 32 MiB PSP: 0x08800000–0x0A000000.
constexpr u32 kUserBase = 0x08800000, kUserEnd = 0x0A000000;
constexpr u32 kListBufSize = 256u << 10;
// Commands one catch-up may run: a list buffer's worth and some. A sound dump never needs more
// (the buffer wraps, and runs, before it fills); a corrupt loop ends as a list error.
constexpr u64 kRunBudget = kListBufSize / 4 + 4096;

u32 cmd(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

class Replayer {
public:
    Replayer(const Dump& d, ReplayTarget& t, const ReplayOptions& opt, ReplayResult& res)
        : d_(d), t_(t), opt_(opt), res_(res),
          heap_(kUserBase, std::min<u32>(kUserEnd, Memory::kRamBase + t.ramSize())),
          mapper_(d.pushbuf, t, heap_) {}

    bool play(std::string& err);

private:
    u32 map(const Record& r) {
        const u32 a = mapper_.map(r.ptr, r.size, [this] { sync(); });
        if (!a) warn(std::string("no guest memory left for a ") + recordTypeName(r.type) + " payload");
        return a;
    }
    // Where in a REGISTERS payload the words are that the player rewrites or counts: TBPn, TBWn,
    // SIGNAL, BASE and the kicks (docs/ppdmp.md §6.2). Found once per distinct payload, keyed by
    // its offset and size: a dump may point many records at one block (§3.1), and each record
    // then costs a copy of the block plus the rewrites, not a walk over its words.
    struct BlockScan {
        bool dense = false;         // too many such words to keep: each use walks the block
        std::vector<u32> special;   // word indices, in order
    };
    const BlockScan& scanBlock(const Record& r, const u8* p);
    // Rewrites the word at `w` as the player does; false when it is the kick --replay-end stops at.
    bool translateWord(u8* w);
    void registers(const Record& r, const u8* p);
    // Writes `size` bytes into the list buffer, in pieces that `produce(dst, offset, n)` fills;
    // it returns how many of the n bytes to write (fewer: the block ends there).
    template <class Produce>
    void appendToList(size_t size, Produce&& produce);
    void wrapList();
    void sync();
    void endList();
    // `cpu`: a write the game's CPU/DMA made (MEMCPYDATA), else the player's own copy.
    void hostWrite(u32 addr, const u8* data, u32 size, bool cpu = false) {
        (cpu ? cpuBytes_ : playerBytes_) += size;
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
    GuestHeap heap_;
    PushbufMapper mapper_;

    std::vector<u32> pending_;  // words queued by data records for the next REGISTERS block
    std::vector<u8> head_;      // pending_ as list bytes, ahead of a block (reused)
    std::vector<u8> piece_;     // one piece of a block on its way into the list buffer (reused)
    // Scans of REGISTERS payloads by (offset << 32 | size). Bounded: kept scans hold at most
    // kMaxScanIndices indices and kMaxScans entries (the cache starts over when full), and a
    // payload with more than kMaxBlockSpecials such words is marked dense instead.
    std::unordered_map<u64, BlockScan> scans_;
    u64 scanIndices_ = 0;
    static constexpr size_t kMaxBlockSpecials = 1u << 16, kMaxScanIndices = 1u << 22, kMaxScans = 1u << 16;
    // Blocks below this size are walked word by word as they are copied, not looked up: most
    // records of a game's dump are a few state words and a kick, each its own payload, and a
    // kept scan would cost more than the walk (a hash-table entry and an allocation per record).
    static constexpr u32 kWalkBelowBytes = 256;
    u32 listBuf_ = 0;           // 0 until the first REGISTERS block (as PPSSPP)
    u32 pos_ = 0;               // where the next word goes
    u32 lastTex_[8] = {}, lastBufw_[8] = {};
    u32 lastBase_ = ~0u;  // unknown
    bool clutAddrPending_ = false;
    u32 clutAddr_ = 0, clutFlags_ = 0;
    u32 memcpyDest_ = 0;
    u64 kicks_ = 0;
    bool stopped_ = false;  // --replay-end reached, or the GE-time budget used up
    // GE-time budget (ReplayOptions::maxGeMs): the target's estimate counted from `cycleBase_`,
    // plus the game's CPU/DMA writes the dump replays (MEMSET/MEMCPYDATA, charged like block
    // transfers) and the player's own copies (FRAMEBUF/CLUT data, push-buffer slabs and extras:
    // no PSP work at all, charged at a host copy's pace so that a dump cannot make the player
    // copy without end; hle/ge_time.h).
    // REGISTERS records cost the player a scan of each distinct payload and a copy of every
    // block into its list buffer (res_.scannedBytes, res_.listBytes), charged the same way: a
    // dump that repeats one large block cannot make the player copy without end either, whether
    // or not the GE gets to run the words.
    u64 budget_ = ~u64(0), cycleBase_ = 0, cpuBytes_ = 0, playerBytes_ = 0;
    size_t record_ = 0;
    u64 copyCycles() const {
        return getime::transferCost(cpuBytes_) +
               getime::hostCopyCost(playerBytes_ + mapper_.stats().bytesCopied + res_.scannedBytes + res_.listBytes);
    }
    bool copiesLeft() {
        if (copyCycles() < budget_) return true;
        budgetExhausted();
        return false;
    }
    // Hands the GE what is left of the budget; false (and the replay stops) when nothing is.
    bool budgetLeft();
    void budgetExhausted();
};

bool Replayer::budgetLeft() {
    if (budget_ == ~u64(0)) return true;
    const u64 used = copyCycles();
    if (used >= budget_ || t_.geCycles() - cycleBase_ >= budget_ - used) {
        budgetExhausted();
        return false;
    }
    t_.setTimeLimit(cycleBase_ + (budget_ - used));
    return true;
}

void Replayer::budgetExhausted() {
    if (res_.timeLimitHit) return;
    res_.timeLimitHit = true;
    stopped_ = true;
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "GE time budget of %.1f ms used up at record %zu (%llu draws recorded so far): the rest of the "
                  "frame is not drawn (--max-ge-ms)",
                  opt_.maxGeMs, record_, (unsigned long long)kicks_);
    res_.warning = buf;  // this says more about the picture than any earlier warning
}

// "Run the list so far": move the stall address to the end of what was written and let the GE
// catch up (PPSSPP DumpExecute::SyncStall; nothing before the list exists).
void Replayer::sync() {
    if (!listBuf_ || !budgetLeft()) return;
    ++res_.syncs;
    const RunStatus s = t_.runTo(pos_, kRunBudget);
    if (s == RunStatus::Stalled) return;
    if (s == RunStatus::TimeLimit) {
        budgetExhausted();
        return;
    }
    ++res_.listErrors;
    char buf[160];
    std::snprintf(buf, sizeof buf, "display list stopped (%s%s%s) before the end of the recorded commands",
                  runStatusName(s), s == RunStatus::Error ? ": " : "",
                  s == RunStatus::Error ? t_.lastError().c_str() : "");
    warn(buf);
    // Restart the list where the player writes next, keeping all state.
    t_.startList(pos_, pos_);
}

// BASE + JUMP back to the start of the buffer, then a catch-up: the GE follows the jump and stalls
// at the start before the player writes over what it has run (DumpExecute::Registers).
void Replayer::wrapList() {
    writeWord(pos_, cmd(GE_CMD_BASE, (listBuf_ >> 8) & 0xFF0000));
    writeWord(pos_ + 4, cmd(GE_CMD_JUMP, listBuf_ & 0xFFFFFF));
    pos_ = listBuf_;
    lastBase_ = listBuf_ >> 24;
    ++res_.listWraps;
    sync();
}

template <class Produce>
void Replayer::appendToList(size_t size, Produce&& produce) {
    const u32 end = listBuf_ + kListBufSize;
    // PPSSPP wraps when the words and 8 bytes for the next BASE + JUMP would reach the end.
    if (u64(pos_) + size + 8 >= end) wrapList();
    size_t i = 0;
    while (i < size && !stopped_) {
        // A block larger than the whole buffer (PPSSPP would write past its end): written in
        // pieces, each run before the list wraps over it. Without that catch-up the GE would
        // still stand at the buffer's start, where the last wrap put the stall address, and run
        // nothing of the block but its last piece.
        const size_t room = size_t(end - pos_ - 12) / 4 * 4;
        if (room == 0) {
            wrapList();
            continue;
        }
        size_t n = std::min(size - i, room);
        piece_.resize(n);
        const size_t want = n;
        n = produce(piece_.data(), i, n);
        t_.write(pos_, piece_.data(), u32(n));
        res_.listBytes += n;
        pos_ += u32(n);
        i += n;
        if (n < want || stopped_ || !copiesLeft()) break;
        if (i < size) {
            sync();
            if (!stopped_) wrapList();
        }
    }
}

const Replayer::BlockScan& Replayer::scanBlock(const Record& r, const u8* p) {
    const u64 key = (u64(r.ptr) << 32) | r.size;
    if (auto it = scans_.find(key); it != scans_.end()) return it->second;
    ++res_.blockScans;
    res_.scannedBytes += r.size;
    BlockScan scan;
    const u32 n = r.size / 4;
    for (u32 i = 0; i < n; ++i) {
        const u8 op = p[4 * i + 3];
        if ((op >= GE_CMD_TBP0 && op <= GE_CMD_TBP7) || (op >= GE_CMD_TBW0 && op <= GE_CMD_TBW7) ||
            op == GE_CMD_SIGNAL || op == GE_CMD_BASE || isKick(op)) {
            if (scan.special.size() == kMaxBlockSpecials) {
                scan.dense = true;
                scan.special = {};
                break;
            }
            scan.special.push_back(i);
        }
    }
    if (scans_.size() >= kMaxScans || scanIndices_ + scan.special.size() > kMaxScanIndices) {
        scans_.clear();
        scanIndices_ = 0;
    }
    scanIndices_ += scan.special.size();
    return scans_.emplace(key, std::move(scan)).first->second;
}

bool Replayer::translateWord(u8* at) {
    u32 w = readLE32(at);
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
    } else if (isKick(op)) {
        ++kicks_;
        if (opt_.replayEnd && kicks_ >= opt_.replayEnd) {
            stopped_ = true;  // --replay-end: this kick is the block's last word
            return false;
        }
    }
    writeLE32(at, w);
    return true;
}

void Replayer::registers(const Record& r, const u8* p) {
    if (!listBuf_) {
        // The list starts with one NOP, enqueued stalled at its end (docs/ppdmp.md §6.1).
        listBuf_ = heap_.alloc(kListBufSize, true);
        if (!listBuf_) {
            warn("no guest memory for the display list");
            return;
        }
        pos_ = listBuf_;
        writeWord(pos_, 0);
        pos_ += 4;
        t_.startList(listBuf_, pos_);
        t_.runTo(pos_, 16);
    }
    // A small block is walked whole as it is copied (charged as a scan); a larger one through
    // its kept scan.
    const bool small = r.size < kWalkBelowBytes;
    if (small) {
        ++res_.blockScans;
        res_.scannedBytes += r.size;
    }
    const BlockScan* scan = small ? nullptr : &scanBlock(r, p);
    const bool walk = !scan || scan->dense;
    // The queued words, then the block's words as they are with the few the player rewrites
    // patched in (payload and list buffer both hold little-endian GE words), produced one list
    // piece at a time so that no copy of a whole large block is made.
    std::vector<u8>& head = head_;
    head.resize(4 * pending_.size());
    for (size_t k = 0; k < pending_.size(); ++k) writeLE32(&head[4 * k], pending_[k]);
    pending_.clear();
    const size_t words = r.size / 4;
    size_t next = 0;  // the next entry of scan.special, or the next word when the scan is dense
    auto produce = [&](u8* dst, size_t off, size_t n) -> size_t {
        // [off, off + n) of head + payload; off and n are multiples of 4.
        const size_t from = off, to = off + n;
        if (from < head.size()) std::memcpy(dst, &head[from], std::min(to, head.size()) - from);
        if (to > head.size()) {
            const size_t a = std::max(from, head.size());
            std::memcpy(dst + (a - from), p + (a - head.size()), to - a);
        }
        const size_t firstWord = from > head.size() ? (from - head.size()) / 4 : 0;
        const size_t endWord = to > head.size() ? (to - head.size()) / 4 : 0;
        auto rewrite = [&](size_t w) {
            return translateWord(dst + (head.size() + 4 * w - from));
        };
        if (walk) {
            for (next = std::max(next, firstWord); next < endWord; ++next)
                if (!rewrite(next)) return head.size() + 4 * (next + 1) - from;  // the kick ends the block
        } else {
            const std::vector<u32>& special = scan->special;
            for (; next < special.size() && special[next] < endWord; ++next)
                if (!rewrite(special[next])) return head.size() + 4 * (special[next] + 1) - from;
        }
        return n;
    };
    appendToList(head.size() + 4 * words, produce);
    if (opt_.timing == ReplayTiming::Eager) sync();
}

// ppdmp.md §6.3 as PPSSPP's SubmitListEnd: FINISH + END (words still queued by data records after the
// last block are dropped), run to completion.
void Replayer::endList() {
    if (!listBuf_ || res_.timeLimitHit) return;
    writeWord(pos_, cmd(GE_CMD_FINISH, 0));
    writeWord(pos_ + 4, cmd(GE_CMD_END, 0));
    pos_ += 8;
    if (!budgetLeft()) return;
    ++res_.syncs;
    const RunStatus s = t_.runTo(pos_, kRunBudget);
    if (s == RunStatus::TimeLimit) {
        budgetExhausted();
    } else if (s != RunStatus::Completed) {
        ++res_.listErrors;
        warn(std::string("final list ended as '") + runStatusName(s) + "'");
    }
}

bool Replayer::play(std::string& err) {
    if (d_.records.empty() || d_.records[0].type != INIT) {
        err = "dump does not start with an INIT record";
        return false;
    }
    if (opt_.maxGeMs > 0) budget_ = getime::cyclesFromMs(opt_.maxGeMs);
    cycleBase_ = t_.geCycles();
    const Record* prev = nullptr;
    for (size_t ri = 0; ri < d_.records.size() && !stopped_; ++ri) {
        record_ = ri;
        // Host copies are charged as they happen; the GE's own work at each catch-up (sync).
        if (!copiesLeft()) break;
        const Record& r = d_.records[ri];
        ++res_.records;
        const u8* p = d_.payload(r);
        if (!p) {
            warn(std::string("record ") + recordTypeName(r.type) + " points outside the push buffer");
            prev = &r;
            continue;
        }
        const int texLevel = textureLevelOf(r.type), fbLevel = framebufLevelOf(r.type);
        if (texLevel >= 0) {
            const u32 a = map(r);
            if (a && a != lastTex_[texLevel]) {
                pending_.push_back(cmd(GE_CMD_TBW0 + texLevel, ((a >> 8) & 0xFF0000) | lastBufw_[texLevel]));
                pending_.push_back(cmd(GE_CMD_TBP0 + texLevel, a & 0xFFFFFF));
                lastTex_[texLevel] = a;
            }
        } else if (fbLevel >= 0) {
            const u32 v = d_.payloadWord(r, 0), bufw = d_.payloadWord(r, 1) & 0xFFFF, flags = d_.payloadWord(r, 2);
            if (v != lastTex_[fbLevel] || bufw != lastBufw_[fbLevel]) {
                pending_.push_back(cmd(GE_CMD_TBW0 + fbLevel, ((v >> 8) & 0xFF0000) | bufw));
                pending_.push_back(cmd(GE_CMD_TBP0 + fbLevel, v & 0xFFFFFF));
                lastTex_[fbLevel] = v;
                lastBufw_[fbLevel] = bufw;
            }
            // Copied at once, without a sync: in PPSSPP timing these bytes land before draws
            // recorded ahead of them that have not run. Flag bit 1 ("unchanged VRAM") is
            // trustworthy from version 6 on (ppdmp.md §3.3). Flag bit 0 ("target": a buffer drawn earlier
            // in this recording) is skipped too: both our backends keep what they drew, as
            // PPSSPP's software renderer does (ppdmp.md §6.2).
            if (r.size > 16 && !(d_.version >= 6 && (flags & 2)) && !(flags & 1)) hostWrite(v, p + 16, r.size - 16);
        } else {
            switch (r.type) {
            case INIT: {
                // Applied at once (PPSSPP: gstate.Restore), not through the list.
                u32 ctx[512] = {};
                if (r.size < kInitBytes) warn("short INIT record");
                if (r.size) std::memcpy(ctx, p, std::min<u32>(r.size, kInitBytes));
                // The running list's OFFSET is its own, starting at 0 (ppdmp.md §6.1).
                ctx[7] = 0;
                t_.loadContext(ctx);
                for (int i = 0; i < 8; ++i) lastTex_[i] = lastBufw_[i] = 0;
                lastBase_ = ~0u;
                break;
            }
            case REGISTERS: registers(r, p); break;
            case VERTICES:
            case INDICES: {
                const u32 a = map(r);
                if (!a) break;
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
                    // At once, like FRAMEBUF data, and with the same rule for flag bit 0.
                    if (!(clutFlags_ & 1)) hostWrite(clutAddr_, p, r.size);
                    clutAddrPending_ = false;
                } else {
                    const u32 a = map(r);
                    if (a) {
                        pending_.push_back(cmd(GE_CMD_CBW, (a >> 8) & 0xFF0000));
                        pending_.push_back(cmd(GE_CMD_CBP, a & 0xFFFFFF));
                        // The palette at recording start (newer v6 dumps): load it into palette
                        // RAM, which matches the recording's state (ppdmp.md §6.4).
                        if (prev && prev->type == INIT) pending_.push_back(cmd(GE_CMD_CLOAD, std::min<u32>(r.size / 32, 32)));
                    }
                }
                break;
            case TRANSFERSRC: {
                const u32 a = map(r);
                if (!a) break;
                // The XBW1 word of the state is needed: the GE must have run the block that set it.
                sync();
                const u32 xbw1 = t_.readRegister(GE_CMD_XBW1);
                pending_.push_back(cmd(GE_CMD_XBW1, (xbw1 & 0xFFFF) | ((a >> 8) & 0xFF0000)));
                pending_.push_back(cmd(GE_CMD_XBP1, a & 0xFFFFFF));
                break;
            }
            case MEMSET: {
                // CPU writes to RAM are not replayed at all; to VRAM after a catch-up.
                const u32 dest = d_.payloadWord(r, 0), value = d_.payloadWord(r, 1), size = d_.payloadWord(r, 2);
                if (Memory::isVram(dest)) {
                    sync();
                    cpuBytes_ += t_.fill(dest, u8(value), size);
                }
                break;
            }
            case MEMCPYDEST: memcpyDest_ = d_.payloadWord(r, 0); break;
            case MEMCPYDATA:
                if (Memory::isVram(memcpyDest_)) {
                    sync();
                    hostWrite(memcpyDest_, p, r.size, true);
                }
                break;
            case EDRAMTRANS:
                sync();
                if (!t_.setEdramTranslation(d_.payloadWord(r, 0))) warn("invalid eDRAM translation value");
                break;
            case DISPLAY:
                sync();
                res_.hasDisplay = true;
                res_.displayAddr = d_.payloadWord(r, 0);
                res_.displayStride = d_.payloadWord(r, 1);
                res_.displayFormat = d_.payloadWord(r, 2) & 0xFF;  // ppdmp.md §3.2: mask the format
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
    endList();
    t_.setTimeLimit(~u64(0));
    res_.geCycles = t_.geCycles() - cycleBase_ + copyCycles();
    res_.playerBytes = playerBytes_ + mapper_.stats().bytesCopied;
    res_.cpuBytes = cpuBytes_;
    res_.draws = kicks_;
    res_.slabMaps = mapper_.stats().slabMaps;
    res_.extraMaps = mapper_.stats().extraMaps;
    t_.finishFrame();
    return true;
}

}  // namespace

const char* replayTimingName(ReplayTiming t) { return t == ReplayTiming::Eager ? "eager" : "ppsspp"; }

bool parseReplayTiming(const std::string& s, ReplayTiming& out) {
    if (s == "ppsspp") out = ReplayTiming::Ppsspp;
    else if (s == "eager") out = ReplayTiming::Eager;
    else return false;
    return true;
}

DumpSummary summarize(const Dump& d) {
    DumpSummary s;
    // Records may share a payload (a hostile dump: one 4 MiB block behind 200k records): each
    // distinct block is scanned once, so the work is bounded by the push buffer's size.
    struct Counts {
        u64 commands = 0, prims = 0, patches = 0, transfers = 0, clutLoads = 0;
    };
    std::map<std::pair<u32, u32>, Counts> scanned;
    for (const Record& r : d.records) {
        if (r.type < 32) ++s.recordsByType[r.type];
        if (!isKnownRecordType(r.type)) ++s.unknownRecords;
        if (r.type != REGISTERS) continue;
        const u8* p = d.payload(r);
        if (!p) continue;
        auto [it, fresh] = scanned.try_emplace({r.ptr, r.size});
        Counts& c = it->second;
        if (fresh) {
            for (u32 i = 0; i < r.size / 4; ++i) {
                const u8 op = p[4 * i + 3];
                ++c.commands;
                if (op == GE_CMD_PRIM) ++c.prims;
                if (op == GE_CMD_BEZIER || op == GE_CMD_SPLINE) ++c.patches;
                if (op == GE_CMD_XSTART) ++c.transfers;
                if (op == GE_CMD_CLOAD) ++c.clutLoads;
            }
        }
        s.commands += c.commands, s.prims += c.prims, s.patches += c.patches;
        s.transfers += c.transfers, s.clutLoads += c.clutLoads;
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
