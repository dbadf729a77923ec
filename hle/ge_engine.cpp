// SPDX-License-Identifier: MIT
#include "hle/ge_engine.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hle/ge_time.h"
#include "hle/vertex_decoder.h"

namespace ge {

const char* geErrorName(GeError e) {
    switch (e) {
    case GeError::None: return "none";
    case GeError::BadListAddress: return "bad list address";
    case GeError::BadJumpTarget: return "bad jump target";
    case GeError::CallDepth: return "call depth exceeded";
    case GeError::SignalStack: return "signal stack";
    }
    return "?";
}

const char* runStatusName(RunStatus s) {
    switch (s) {
    case RunStatus::Idle: return "idle";
    case RunStatus::Completed: return "completed";
    case RunStatus::Ended: return "ended";
    case RunStatus::Stalled: return "stalled";
    case RunStatus::Paused: return "paused";
    case RunStatus::Budget: return "budget";
    case RunStatus::TimeLimit: return "GE time limit";
    case RunStatus::Error: return "error";
    }
    return "?";
}

GeEngine::GeEngine(Memory& mem, Renderer* renderer) : mem_(mem) { setRenderer(renderer); }

void GeEngine::setRenderer(Renderer* r) {
    renderer_ = r ? r : &nullRenderer_;
    pixelWorkSeen_ = renderer_->pixelWork();
    dirty_ = DIRTY_ALL;
}

GeEngine::Saved GeEngine::saved() const {
    Saved s;
    Saved::fields(s) = savedFields(*this);
    return s;
}

void GeEngine::restore(const Saved& s) {
    savedFields(*this) = Saved::fields(s);
    // The renderer's pixel count is its own (a fresh backend starts at 0): charge from here on.
    pixelWorkSeen_ = renderer_->pixelWork();
    if (pixelBudgetSet_) renderer_->setPixelBudget(~u64(0)), pixelBudgetSet_ = false;
    dirty_ = DIRTY_ALL;
    renderer_->clutLoaded(state_);
}

u32 GeEngine::formAddress(u32 arg24) const {
    u32 hi = (state_.regs[GE_CMD_BASE] & 0x00FF0000) << 8;
    return ((hi | (arg24 & 0xFFFFFF)) + state_.offsetAddr) & 0x0FFFFFFF;
}

void GeEngine::startList(u32 pc, u32 stall) {
    list_ = ListRegs{};
    list_.pc = Memory::normalize(pc);
    setStall(stall);
    state_.offsetAddr = 0;
    status_ = RunStatus::Budget;  // ready to run
    charge(getime::kListStart, &GeStats::cyclesCommands);
    lastError_ = GeError::None;
    lastErrorMsg_.clear();
    pauseRequested_ = false;
}

void GeEngine::resume() {
    pauseRequested_ = false;
    if (status_ == RunStatus::Paused) status_ = RunStatus::Budget;
}

bool GeEngine::loadContext(const u32 ctx[512]) {
    bool ok = state_.loadContext(ctx);
    dirty_ = DIRTY_ALL;
    return ok;
}

void GeEngine::fail(GeError e, const std::string& msg) {
    lastError_ = e;
    lastErrorMsg_ = msg;
    stopRequested_ = true;
    stopStatus_ = RunStatus::Error;
    if (listener_) listener_->onError(e, list_.pc, msg);
}

RunStatus GeEngine::run(u64 maxCommands) {
    switch (status_) {
    case RunStatus::Idle:
    case RunStatus::Completed:
    case RunStatus::Ended:
    case RunStatus::Error: return status_;
    case RunStatus::Paused: return status_;  // resume() first
    default: break;
    }
    stopRequested_ = false;
    broke_ = false;
    drawCut_ = false;
    u64 n = 0;
    for (;;) {
        if (list_.stall && list_.pc == list_.stall) {
            status_ = RunStatus::Stalled;
            break;
        }
        if (pauseRequested_) {
            status_ = RunStatus::Paused;
            break;
        }
        if (n >= maxCommands) {
            status_ = RunStatus::Budget;
            break;
        }
        if (stats_.cycles >= cycleLimit_) {
            status_ = RunStatus::TimeLimit;
            break;
        }
        if (stats_.cycles >= cycleStop_) {
            status_ = RunStatus::Budget;
            break;
        }
        const u8* p = mem_.ptr(list_.pc, 4);
        if (!p) {
            char buf[80];
            std::snprintf(buf, sizeof buf, "display list PC 0x%08x is outside memory", list_.pc);
            fail(GeError::BadListAddress, buf);
            status_ = RunStatus::Error;
            break;
        }
        u32 word = readLE32(p);
        if (!observers_.empty() && !std::all_of(observers_.begin(), observers_.end(), [&](CommandObserver* o) {
                return o->beforeCommand(list_.pc, word);
            })) {
            broke_ = true;
            status_ = RunStatus::Budget;
            break;
        }
        list_.pc += 4;
        ++n;
        execute(word);
        if (stopRequested_) {
            status_ = stopStatus_;
            break;
        }
    }
    if (listener_) listener_->onProgress(list_.pc);
    return status_;
}

bool GeEngine::jumpTo(u32 target) {
    target &= 0x0FFFFFFC;
    if (!mem_.valid(target, 4)) {
        char buf[80];
        std::snprintf(buf, sizeof buf, "jump to invalid address 0x%08x", target);
        fail(GeError::BadJumpTarget, buf);
        return false;
    }
    list_.pc = target;
    return true;
}

void GeEngine::matrixData(u8 op, u32 arg) {
    float v = float24(arg);
    float* m = nullptr;
    u32* idx = nullptr;
    u32 size = 0, dirty = DIRTY_TRANSFORM;
    switch (op) {
    case GE_CMD_BONED: m = state_.bone; idx = &state_.boneNum; size = 96; dirty = DIRTY_BONES; break;
    case GE_CMD_WORLDD: m = state_.world; idx = &state_.worldNum; size = 12; break;
    case GE_CMD_VIEWD: m = state_.view; idx = &state_.viewNum; size = 12; break;
    case GE_CMD_PROJD: m = state_.proj; idx = &state_.projNum; size = 16; break;
    default: m = state_.tgen; idx = &state_.tgenNum; size = 12; break;
    }
    // What sceGeGetMtx reads back (GeState::visibleMtx): its own index rules.
    switch (op) {
    case GE_CMD_BONED: state_.visibleMtx[*idx & 0x7F] = arg; break;
    case GE_CMD_WORLDD: state_.visibleMtx[96 + (*idx & 0xF)] = arg; break;
    case GE_CMD_VIEWD: state_.visibleMtx[108 + (*idx & 0xF)] = arg; break;
    case GE_CMD_PROJD: state_.visibleMtx[120 + (*idx & 0xF)] = arg; break;
    default:
        if ((*idx & 0xF) < 12) state_.visibleMtx[136 + (*idx & 0xF)] = arg;
        break;
    }
    // Data past the end is dropped for rendering; the index keeps counting (docs/ge-rules.md §3.4).
    if (*idx < size) {
        if (m[*idx] != v || std::signbit(m[*idx]) != std::signbit(v)) {
            m[*idx] = v;
            dirty_ |= dirty;
        }
    }
    if (*idx < 0xFFFF) ++*idx;
}

void GeEngine::execute(u32 word) {
    const u8 op = u8(word >> 24);
    const u32 arg = word & 0xFFFFFF;
    ++stats_.commands;
    charge(getime::kPerCommand, &GeStats::cyclesCommands);

    // Immediate-mode vertices end at the first command that is not part of them.
    if (!immVerts_.empty() && (op < GE_CMD_X2 || op > GE_CMD_I2)) flushImmediate();

    const u32 prev = state_.regs[op];
    state_.regs[op] = word;
    if (prev != word) {
        ++stats_.stateChanges;
        dirty_ |= geCmdDirty(op);
    }

    switch (op) {
    case GE_CMD_VADR: state_.vertexAddr = formAddress(arg); break;
    case GE_CMD_IADR: state_.indexAddr = formAddress(arg); break;
    case GE_CMD_PRIM: doPrim(arg); break;
    case GE_CMD_BEZIER:
    case GE_CMD_SPLINE: doPatch(word); break;
    case GE_CMD_BBOX: doBBox(arg); break;
    case GE_CMD_JUMP: jumpTo(formAddress(arg & 0xFFFFFC)); break;
    case GE_CMD_BJUMP:
        // Jump only when the last BBOX found the volume completely outside (BFLG = 0).
        if (!list_.bflg) jumpTo(formAddress(arg & 0xFFFFFC));
        break;
    case GE_CMD_CALL: {
        // The hardware has two return registers (RADR1/2, OADR1/2); a third level is refused, as
        // the uOFW firmware does (ge-rules.md §4.3).
        if (list_.callDepth >= 2) {
            fail(GeError::CallDepth, "CALL nested deeper than 2 levels");
            break;
        }
        u32 target = formAddress(arg & 0xFFFFFC);
        u32 retPc = list_.pc, retOffset = state_.offsetAddr;
        if (jumpTo(target)) {
            list_.callStack[list_.callDepth][0] = retPc;
            list_.callStack[list_.callDepth][1] = retOffset;
            ++list_.callDepth;
        }
        break;
    }
    case GE_CMD_RET:
        // RET with an empty stack is ignored (PPSSPP). BASE is not restored.
        if (list_.callDepth > 0) {
            --list_.callDepth;
            list_.pc = list_.callStack[list_.callDepth][0];
            state_.offsetAddr = list_.callStack[list_.callDepth][1];
        }
        break;
    case GE_CMD_END: doEnd(arg); break;
    case GE_CMD_SIGNAL: ++stats_.signals; break;  // acted on at the following END (ge-rules.md §4.4)
    case GE_CMD_FINISH:
        ++stats_.finishes;
        renderer_->finish();
        break;
    case GE_CMD_OFFSET: state_.offsetAddr = arg << 8; break;
    case GE_CMD_ORIGIN: state_.offsetAddr = (list_.pc - 4) & 0x0FFFFFFF; break;
    case GE_CMD_BONEN: state_.boneNum = arg & 0x7F; break;
    case GE_CMD_WORLDN: state_.worldNum = arg & 0xF; break;
    case GE_CMD_VIEWN: state_.viewNum = arg & 0xF; break;
    case GE_CMD_PROJN: state_.projNum = arg & 0xF; break;
    case GE_CMD_TGENN: state_.tgenNum = arg & 0xF; break;
    case GE_CMD_BONED:
    case GE_CMD_WORLDD:
    case GE_CMD_VIEWD:
    case GE_CMD_PROJD:
    case GE_CMD_TGEND: matrixData(op, arg); break;
    case GE_CMD_CLOAD: doClutLoad(arg); break;
    case GE_CMD_XSTART: doTransfer(arg); break;
    case GE_CMD_TFLUSH: renderer_->textureFlush(); break;
    case GE_CMD_TSYNC: renderer_->textureSync(); break;
    case GE_CMD_AP2: doImmediate(arg); break;
    default:
        if (!geCmdKnown(op)) ++stats_.unknownCommands;  // unknown opcodes are no-ops (ge-rules.md §2)
        break;
    }
    list_.lastOp = op;
    list_.lastWord = word;
}

void GeEngine::doPrim(u32 arg) {
    const u32 count = arg & 0xFFFF;
    const u32 type = (arg >> 16) & 7;  // bits 23..19 ignored: type 8 acts as 0 (ge-rules.md §3.2)
    const bool cont = type == GE_PRIM_KEEP_PREVIOUS;
    const GePrimType prim = cont ? lastPrim_ : GePrimType(type);
    if (!cont) lastPrim_ = prim;
    if (count == 0) return;  // draws nothing, pointers unchanged (ge-rules.md §8.11)

    PrimPacket pkt;
    pkt.state = &state_;
    pkt.dirty = takeDirty();
    pkt.prim = prim;
    pkt.continuation = cont;
    pkt.count = count;
    pkt.vtype = state_.op(GE_CMD_VTYPE);
    pkt.vertexAddr = state_.vertexAddr;
    pkt.indexAddr = state_.indexAddr;
    ++stats_.prims;
    stats_.vertices += count;
    if (!chargeDraw(getime::perVertexCost(state_) * count)) return;
    checkDrawData("PRIM", pkt.vtype, pkt.vertexAddr, pkt.indexAddr, count);
    renderer_->drawPrim(pkt);
    chargePixels();
    latchVertexAttributes(pkt);

    // Pointers advance past the consumed data (ge-rules.md §4.6).
    if (state_.indexSize()) state_.indexAddr = (state_.indexAddr + count * state_.indexSize()) & 0x0FFFFFFF;
    else state_.vertexAddr = (state_.vertexAddr + count * state_.vertexStride()) & 0x0FFFFFFF;
}

// The vertex unit keeps the last texture coordinate and normal it read (GeState::latchUV,
// latchNormal), which later draws without them use. Which vertex is read last follows the reference
// renderer (PPSSPP GPU/Software/TransformUnit.cpp, SoftwareVertexReader and ReadVertex): a format
// without position reads nothing; an indexed draw with more indices than its index range holds
// vertices reads that range in order (the highest index last), any other draw reads in draw order
// (its last index). The UV is read only with texture mapping on outside clear mode (readUV); the
// normal whenever the format has one. Patches leave both as they are (their vertices are generated).
void GeEngine::latchVertexAttributes(const PrimPacket& p) {
    const VertexReader r(mem_, state_, p.vtype);
    const bool uv = r.hasUV() && state_.TME_on() && !state_.isClearMode();
    if (!r.hasPosition() || (!uv && !r.hasNormal())) return;
    u32 last = p.count - 1;
    if (r.indexSize()) {
        u32 lo = 0, hi = 0, back = 0;
        if (!r.indexBounds(p.indexAddr, p.count, lo, hi, back)) return;
        last = u64(p.count) > u64(hi) - lo + 1 ? hi : back;
    }
    DecodedVertex v;
    if (!r.read(p.vertexAddr, last, v)) return;
    applySkinning(state_, p.vtype, v);
    if (uv) std::copy(v.uv, v.uv + 2, state_.latchUV);
    if (r.hasNormal()) std::copy(v.nrm, v.nrm + 3, state_.latchNormal);
}

void GeEngine::doPatch(u32 word) {
    const u8 op = u8(word >> 24);
    PatchPacket pkt;
    pkt.state = &state_;
    pkt.spline = op == GE_CMD_SPLINE;
    pkt.ucount = word & 0xFF;
    pkt.vcount = (word >> 8) & 0xFF;
    if (pkt.spline) {
        pkt.uknot = (word >> 16) & 3;
        pkt.vknot = (word >> 18) & 3;
    }
    // PPSSPP reads 7 bits of each division count and treats 0 as 1 (ge-rules.md §3.2).
    pkt.divU = std::max<u32>(1, state_.DIVIDE_u() & 0x7F);
    pkt.divV = std::max<u32>(1, state_.DIVIDE_v() & 0x7F);
    pkt.patchPrim = state_.PPM_prim();
    pkt.reverseFace = state_.PFACE_reverse();
    pkt.vtype = state_.op(GE_CMD_VTYPE);
    pkt.vertexAddr = state_.vertexAddr;
    pkt.indexAddr = state_.indexAddr;
    const u32 count = pkt.ucount * pkt.vcount;
    if (count == 0) return;
    pkt.dirty = takeDirty();
    ++stats_.patches;
    stats_.vertices += count;
    // Every generated vertex is transformed (PPSSPP charges nothing for patches): a surface of
    // (patches·divisions + 1) vertices a side — Bezier patches every 3 control points, spline
    // spans every point after the third (manual §5.2) — at most the tessellator's cap of 2^21.
    auto side = [&](u32 points, u32 div) -> u64 {
        const u64 spans = pkt.spline ? (points > 3 ? points - 3 : 1) : std::max<u32>(1, (points - 1) / 3);
        return spans * div + 1;
    };
    const u64 generated = std::min<u64>(side(pkt.ucount, pkt.divU) * side(pkt.vcount, pkt.divV), kMaxPatchOutputVertices);
    if (!chargeDraw(getime::perVertexCost(state_) * generated)) return;
    const char* what = pkt.spline ? "SPLINE" : "BEZIER";
    if (pkt.ucount >= 4 && pkt.vcount >= 4) {
        // Past the tessellator's output cap a surface is not drawn at all.
        const u64 total = patchOutputVertices(pkt);
        if (total > kMaxPatchOutputVertices) {
            char buf[200];
            std::snprintf(buf, sizeof buf,
                          "%s of %ux%u control points at %ux%u divisions makes %llu vertices, past the tessellator's "
                          "cap of 2097152: not drawn",
                          what, pkt.ucount, pkt.vcount, pkt.divU, pkt.divV, static_cast<unsigned long long>(total));
            reportDrop(buf);
        } else {
            checkDrawData(what, pkt.vtype, pkt.vertexAddr, pkt.indexAddr, count);
        }
    }
    renderer_->drawPatch(pkt);
    chargePixels();
    if (state_.indexSize()) state_.indexAddr = (state_.indexAddr + count * state_.indexSize()) & 0x0FFFFFFF;
    else state_.vertexAddr = (state_.vertexAddr + count * state_.vertexStride()) & 0x0FFFFFFF;
}

namespace {

// Position of one vertex in model space for BBOX (morphing applied; ge-rules.md §5.4/§5.5).
bool bboxPosition(const Memory& mem, const GeState& st, u32 addr, float out[3]) {
    const u32 vtype = st.op(GE_CMD_VTYPE);
    const VertexLayout l = VertexLayout::fromVtype(vtype);
    const u32 posFmt = (vtype >> 7) & 3;
    const u32 copies = ((vtype >> 18) & 7) + 1;
    out[0] = out[1] = out[2] = 0;
    for (u32 c = 0; c < copies; ++c) {
        const u8* p = mem.ptr(addr + c * l.size + l.posOff, posFmt == 3 ? 12 : posFmt == 2 ? 6 : 3);
        if (!p) return false;
        float w = copies > 1 ? st.WEIGHT_value(int(c)) : 1.0f;
        for (int i = 0; i < 3; ++i) {
            float v;
            switch (posFmt) {
            case 1: v = float(s8(p[i])) / 128.0f; break;
            case 2: v = float(s16(readLE16(p + 2 * i))) / 32768.0f; break;
            case 3: {
                u32 bits = readLE32(p + 4 * i);
                std::memcpy(&v, &bits, 4);
                break;
            }
            default: v = 0; break;
            }
            out[i] += w * v;
        }
    }
    return true;
}

}  // namespace

// Object culling (manual §11.1; ge-rules.md §3.1 BBOX notes): BFLG = 1 unless every vertex lies
// outside the same edge of the drawing area (REGION ∩ SCISSOR widened by one pixel, placed in screen
// space with OFFSETX/Y) or behind the near plane. An area touching the 4096 screen edge always passes.
bool GeEngine::chargeDraw(u64 vertexCycles) {
    // The draw's end: the run's time limit, or sooner the host's bound on one draw.
    drawEnd_ = ~u64(0);
    if (drawLimit_ != ~u64(0)) drawEnd_ = stats_.cycles + std::min(drawLimit_, ~u64(0) - stats_.cycles - 1);
    const u64 limit = std::min(cycleLimit_, drawEnd_);
    if (limit == ~u64(0)) {
        charge(vertexCycles, &GeStats::cyclesVertices);
        if (pixelBudgetSet_) renderer_->setPixelBudget(~u64(0)), pixelBudgetSet_ = false;
        return true;
    }
    if (stats_.cycles + vertexCycles > limit) {
        // The draw alone would overrun the limit (a patch near the tessellation cap, a huge
        // primitive count): it is not drawn.
        stats_.cycles = limit;
        stopRequested_ = true;
        stopStatus_ = RunStatus::TimeLimit;
        drawCut_ = limit == drawEnd_;
        if (drawCut_) reportDrop("a draw whose vertex work alone takes more than the host's GE-time budget: not drawn", true);
        return false;
    }
    charge(vertexCycles, &GeStats::cyclesVertices);
    renderer_->setPixelBudget((limit - stats_.cycles) * 3);  // pixelCost: 1/3 cycle a pixel
    pixelBudgetSet_ = true;
    return true;
}

void GeEngine::reportDrop(const std::string& message, bool cut) {
    ++(cut ? stats_.drawsCut : stats_.drawsDropped);
    if (listener_) listener_->onDrop(list_.pc, message);
}

// The renderers draw without what they cannot read (docs/ge-rules.md §3.4); the host hears of it.
// Cheap for the usual draw: an indexed draw reads its indices only when the largest vertex its
// index size can name would lie outside memory.
void GeEngine::checkDrawData(const char* what, u32 vtype, u32 vertexAddr, u32 indexAddr, u32 count) {
    const VertexReader r(mem_, state_, vtype);
    const u32 stride = state_.vertexStride();
    const u32 isize = r.indexSize();
    char buf[200];
    if (isize) {
        if (!mem_.valid(indexAddr, count * isize)) {
            std::snprintf(buf, sizeof buf, "%s: its %u indices at 0x%08x lie outside guest memory: not drawn", what,
                          count, indexAddr);
            reportDrop(buf);
            return;
        }
        u64 maxIndex = isize == 1 ? 0xFF : isize == 2 ? 0xFFFF : 0xFFFFFFFF;
        if (mem_.valid(vertexAddr, u32(std::min<u64>((maxIndex + 1) * stride, 0xFFFFFFFF)))) return;
        std::vector<u32>& idx = latchIndices_;
        if (!r.readIndices(indexAddr, count, idx) || idx.empty()) return;
        maxIndex = *std::max_element(idx.begin(), idx.end());
        if (mem_.valid(vertexAddr, u32(std::min<u64>((maxIndex + 1) * stride, 0xFFFFFFFF)))) return;
        std::snprintf(buf, sizeof buf,
                      "%s: vertex %llu of the data at 0x%08x (stride %u) lies outside guest memory: the vertices "
                      "there are not drawn",
                      what, static_cast<unsigned long long>(maxIndex), vertexAddr, stride);
        reportDrop(buf);
        return;
    }
    if (mem_.valid(vertexAddr, count * stride)) return;
    std::snprintf(buf, sizeof buf,
                  "%s: %u vertices at 0x%08x (stride %u) run outside guest memory: the vertices there are not drawn",
                  what, count, vertexAddr, stride);
    reportDrop(buf);
}

void GeEngine::chargePixels() {
    const u64 w = renderer_->pixelWork();
    if (w > pixelWorkSeen_) {
        charge(getime::pixelCost(w - pixelWorkSeen_), &GeStats::cyclesPixels);
    }
    pixelWorkSeen_ = w;
    if (drawEnd_ != ~u64(0) && stats_.cycles >= drawEnd_) {
        // The pixels reached the host's bound on one draw: the renderer cut them there, so the
        // draw took that long (its estimate counts the whole primitives).
        stats_.cycles = drawEnd_;
        stopRequested_ = true;
        stopStatus_ = RunStatus::TimeLimit;
        drawCut_ = true;
        reportDrop("a draw whose pixels take more than the host's GE-time budget: cut there", true);
    }
}

void GeEngine::doBBox(u32 arg) {
    ++stats_.bboxes;
    const u32 n = arg & 0xFFFF;
    charge(getime::kPerBBoxVertex * n, &GeStats::cyclesCommands);
    const u32 stride = state_.vertexStride();
    const u32 isize = state_.indexSize();
    const u32 vbase = state_.vertexAddr, ibase = state_.indexAddr;
    // Advance the pointers as a draw would (ge-rules.md §4.6).
    if (isize) state_.indexAddr = (state_.indexAddr + n * isize) & 0x0FFFFFFF;
    else state_.vertexAddr = (state_.vertexAddr + n * stride) & 0x0FFFFFFF;
    if (n == 0) {
        list_.bflg = false;
        return;
    }
    // Only a 0x100-vertex window decides for large counts.
    u32 first = 0, last = n;
    if (n > 0x200) first = n - 0x200, last = std::min(n, first + 0x100);
    else if (n > 0x100) last = n - 0x100;

    const float offx = state_.OFFSETX_value() / 16.0f, offy = state_.OFFSETY_value() / 16.0f;
    const float x1 = float(std::max(state_.REGION1_x(), state_.SCISSOR1_x())) - 1 + offx;
    const float y1 = float(std::max(state_.REGION1_y(), state_.SCISSOR1_y())) - 1 + offy;
    const float x2 = float(std::min(state_.REGION2_x(), state_.SCISSOR2_x())) + 1 + offx;
    const float y2 = float(std::min(state_.REGION2_y(), state_.SCISSOR2_y())) + 1 + offy;
    // The area reaching past the 4096-pixel coordinate space lets every box pass; reaching pixel
    // 4095 does not (pspautotests gpu/bounding/viewport, OFFSETX 3615 with a 480-pixel region: the
    // area's right edge at 4095 still culls; PPSSPP DrawEngineCommon::TestBoundingBox).
    if (x1 < 1 || y1 < 1 || x2 >= 4096 || y2 >= 4096) {
        list_.bflg = true;
        return;
    }
    const float sx = state_.SX_value(), sy = state_.SY_value(), tx = state_.TX_value(), ty = state_.TY_value();
    // Plane functions in clip space; a vertex is outside a plane when its value is negative. The
    // depth planes (z >= -w, z <= w) count only with depth clipping on (CMD_CLE): with it off
    // (depth clamped), a box far beyond either depth plane still passes (pspautotests
    // gpu/bounding/planes and viewport, "clamp"/"noclamp" cases; PPSSPP
    // DrawEngineCommon::TestBoundingBox). docs/ge-rules.md §3.1.
    const bool depthPlanes = state_.CLE_on();
    u32 outsideAll = depthPlanes ? 0x3F : 0x0F;
    for (u32 i = first; i < last; ++i) {
        u32 index = i;
        if (isize) {
            u32 ia = ibase + i * isize;
            index = isize == 1 ? mem_.read8(ia) : isize == 2 ? mem_.read16(ia) : mem_.read32(ia);
        }
        float m[3];
        if (!bboxPosition(mem_, state_, vbase + index * stride, m)) {
            outsideAll = 0;  // unreadable data: do not cull
            break;
        }
        const float* W = state_.world;
        const float* V = state_.view;
        const float* P = state_.proj;
        float w[3], v[3], c[4];
        for (int r = 0; r < 3; ++r) w[r] = W[r] * m[0] + W[3 + r] * m[1] + W[6 + r] * m[2] + W[9 + r];
        for (int r = 0; r < 3; ++r) v[r] = V[r] * w[0] + V[3 + r] * w[1] + V[6 + r] * w[2] + V[9 + r];
        for (int r = 0; r < 4; ++r) c[r] = P[r] * v[0] + P[4 + r] * v[1] + P[8 + r] * v[2] + P[12 + r];
        u32 out = 0;
        // screen x = sx*cx/cw + tx; inside when x1 <= x <= x2 (multiplying through by cw >= 0).
        if (sx * c[0] + (tx - x1) * c[3] < 0) out |= 1;
        if ((x2 - tx) * c[3] - sx * c[0] < 0) out |= 2;
        if (sy * c[1] + (ty - y1) * c[3] < 0) out |= 4;
        if ((y2 - ty) * c[3] - sy * c[1] < 0) out |= 8;
        if (depthPlanes && c[2] + c[3] < 0) out |= 16;  // beyond the near plane
        if (depthPlanes && c[3] - c[2] < 0) out |= 32;  // beyond the far plane
        outsideAll &= out;
        if (!outsideAll) break;
    }
    list_.bflg = outsideAll == 0;
}

// A transfer base address in the window just above VRAM's mirrors (0x04800000-0x04FFFFFF) reads
// and writes VRAM from its start again: the bit above the mirrors is dropped (pspautotests
// gpu/transfer/invalid "0 bytes valid": 0x04800000 -> 0x04100000 copies what lies at 0x04000000;
// PPSSPP GPUCommon::DoBlockTransfer clears bit 23 of such an address). docs/ge-rules.md §3.11.
static u32 transferBase(u32 addr) { return (addr & 0x04800000) == 0x04800000 ? addr & ~0x00800000u : addr; }

void GeEngine::doTransfer(u32 arg) {
    TransferPacket t;
    t.src = transferBase(state_.transferSrcAddr());
    t.srcStride = state_.transferSrcStride();
    t.srcX = state_.XPOS1_x();
    t.srcY = state_.XPOS1_y();
    t.dst = transferBase(state_.transferDstAddr());
    t.dstStride = state_.transferDstStride();
    t.dstX = state_.XPOS2_x();
    t.dstY = state_.XPOS2_y();
    t.width = state_.XSIZE_w1() + 1;
    t.height = state_.XSIZE_h1() + 1;
    t.bpp = (arg & 1) ? 4 : 2;
    ++stats_.transfers;
    charge(getime::transferCost(u64(t.width) * t.height * t.bpp), &GeStats::cyclesTransfers);
    renderer_->blockTransfer(t, mem_);
}

void GeEngine::doClutLoad(u32 arg) {
    u32 blocks = arg & 0x3F;
    if ((arg & 0x7F) == 0x40) blocks = 64;  // as PPSSPP's recorder records it (ge-rules.md §3.8)
    const u32 bytes = std::min<u32>(blocks * 32, sizeof(state_.clut));
    const u32 addr = state_.clutAddr();
    renderer_->syncMemoryForRead(addr, bytes);
    const u32 avail = mem_.validSize(addr, bytes);
    if (avail) std::memcpy(state_.clut, mem_.ptr(addr, avail), avail);
    if (avail < bytes) {
        // Bytes outside valid memory load as zero (a PSP: pspautotests gpu/clut/address, a load
        // from just past VRAM's mirrors reads colour 0, tests/conformance/clut_address.cpp; the
        // reference renderer zero-fills likewise, SoftGpu::Execute_LoadClut).
        std::memset(state_.clut + avail, 0, bytes - avail);
        mem_.noteBadAccess(addr + avail);
    }
    state_.clutLoadedBytes = bytes;
    dirty_ |= DIRTY_CLUT;
    ++stats_.clutLoads;
    renderer_->clutLoaded(state_);
}

void GeEngine::flushImmediate() {
    ImmPacket pkt;
    pkt.state = &state_;
    pkt.dirty = takeDirty();
    pkt.prim = immPrim_;
    pkt.flags = immFlags_;
    pkt.vertices.swap(immVerts_);
    immVerts_.clear();
    ++stats_.immediates;
    if (!chargeDraw(getime::perVertexCost(state_) * pkt.vertices.size())) return;
    renderer_->drawImmediate(pkt);
    chargePixels();
}

void GeEngine::doImmediate(u32 arg) {
    ImmVertex v;
    const bool through = state_.isThrough();
    const float bx = through ? 0x8000 : float(state_.OFFSETX_value());
    const float by = through ? 0x8000 : float(state_.OFFSETY_value());
    v.x = (float(state_.X2_value()) - bx) / 16.0f;
    v.y = (float(state_.Y2_value()) - by) / 16.0f;
    v.z = u16(state_.Z2_value());
    v.s = state_.S2_value();
    v.t = state_.T2_value();
    v.q = state_.Q2_value();
    const u32 rgb = state_.RGB2_rgb();
    v.color[0] = u8(rgb), v.color[1] = u8(rgb >> 8), v.color[2] = u8(rgb >> 16), v.color[3] = u8(arg);
    const u32 sec = state_.I2_rgb();
    v.secondary[0] = u8(sec), v.secondary[1] = u8(sec >> 8), v.secondary[2] = u8(sec >> 16);
    v.fog = u8(state_.F2_fog());
    const u32 type = (arg >> 8) & 7;
    if (type != GE_PRIM_KEEP_PREVIOUS || immVerts_.empty()) {
        if (!immVerts_.empty()) flushImmediate();  // a new primitive starts: emit the collected one
        if (type != GE_PRIM_KEEP_PREVIOUS) immPrim_ = GePrimType(type);
        immFlags_ = arg & 0xFFF800;  // flag bits 11..23 of the primitive's first vertex
    }
    if (immVerts_.size() < 0x10000) immVerts_.push_back(v);
}

void GeEngine::doEnd(u32 arg) {
    const u32 pc = list_.pc;
    charge(getime::kEnd, &GeStats::cyclesCommands);
    if (list_.lastOp == GE_CMD_SIGNAL) {
        const u32 sig = list_.lastWord;
        const u32 behaviour = (sig >> 16) & 0xFF, sarg = sig & 0xFFFF;
        const u32 sigAddr = (pc - 8) & 0x0FFFFFFF;
        const u32 data = (sarg << 16) | (arg & 0xFFFF);
        auto offsetForm = [&](u32 a) {
            return ((((state_.regs[GE_CMD_BASE] & 0x00FF0000) << 8) | a) + state_.offsetAddr) & 0x0FFFFFFF;
        };
        auto pushFrame = [&]() -> bool {
            if (list_.signalStack.size() >= list_.signalStackMax) {
                fail(GeError::SignalStack, "signal CALL beyond the list's stack");
                return false;
            }
            list_.signalStack.push_back({list_.pc, state_.offsetAddr, state_.regs[GE_CMD_BASE]});
            return true;
        };
        switch (behaviour) {
        case 0x01:  // HANDLER_SUSPEND
        case 0x02:  // HANDLER_CONTINUE
            if (listener_) listener_->onSignal(behaviour, sarg, arg, pc);
            break;
        case 0x03:  // HANDLER_PAUSE: acted on at the next FINISH + END (ge-rules.md §4.4)
            list_.pauseAtFinish = true;
            list_.pauseSignalArg = sarg;
            list_.pauseEndArg = arg;
            break;
        case 0x08: list_.syncAtFinish = true; break;  // SYNC
        case 0x10: jumpTo(data); break;                // JUMP (absolute)
        case 0x13: jumpTo(sigAddr + data); break;      // RJUMP
        case 0x15: jumpTo(offsetForm(data)); break;    // OJUMP
        case 0x11:                                     // CALL
            if (pushFrame() && !jumpTo(data)) list_.signalStack.pop_back();
            break;
        case 0x14:  // RCALL
            if (pushFrame() && !jumpTo(sigAddr + data)) list_.signalStack.pop_back();
            break;
        case 0x16:  // OCALL
            if (pushFrame() && !jumpTo(offsetForm(data))) list_.signalStack.pop_back();
            break;
        case 0x12:  // RET: PC, OFFSET and BASE restored
            if (list_.signalStack.empty()) {
                fail(GeError::SignalStack, "signal RET with an empty stack");
            } else {
                ListRegs::SigFrame f = list_.signalStack.back();
                list_.signalStack.pop_back();
                list_.pc = f.pc;
                state_.offsetAddr = f.offset;
                state_.regs[GE_CMD_BASE] = f.base;
            }
            break;
        default:
            if ((behaviour >= 0x20 && behaviour <= 0x2F) || behaviour == 0x30 || behaviour == 0x38) {
                // RTBPn/OTBPn/RCBP/OCBP (uOFW): set a texture level or the CLUT address from an
                // address formed like RJUMP/OJUMP; TBW width from END bits 23..16.
                const bool relative = behaviour < 0x28 || behaviour == 0x30;
                const u32 a = relative ? ((sigAddr + data) & 0x0FFFFFFF) : offsetForm(data);
                if (a & 0xF) break;  // must be 16-byte aligned
                if (behaviour >= 0x30) {
                    execute((u32(GE_CMD_CBP) << 24) | (a & 0xFFFFFF));
                    execute((u32(GE_CMD_CBW) << 24) | ((a >> 8) & 0x0F0000));
                } else {
                    const u32 n = behaviour & 7;
                    execute((u32(GE_CMD_TBP0 + n) << 24) | (a & 0xFFFFFF));
                    execute((u32(GE_CMD_TBW0 + n) << 24) | ((a >> 8) & 0x0F0000) | ((arg >> 16) & 0xFF));
                }
            }
            // 0xF0/0xFF debugger breaks and unknown codes: resume at once.
            break;
        }
        if (listener_) listener_->onEnd(pc);
        return;
    }
    if (list_.lastOp == GE_CMD_FINISH) {
        const u32 finishArg = list_.lastWord & 0xFFFF;
        if (listener_) listener_->onEnd(pc);
        if (list_.syncAtFinish) {  // SYNC mark: resume immediately, no callback
            list_.syncAtFinish = false;
            return;
        }
        if (list_.pauseAtFinish) {
            list_.pauseAtFinish = false;
            stopRequested_ = true;
            stopStatus_ = RunStatus::Paused;
            if (listener_) listener_->onSignal(0x03, list_.pauseSignalArg, list_.pauseEndArg, pc);
            return;
        }
        stopRequested_ = true;
        stopStatus_ = RunStatus::Completed;
        if (listener_) listener_->onFinish(finishArg, pc);
        return;
    }
    // END without SIGNAL/FINISH: the GE stops (uOFW); PPSSPP would ignore it (ge-rules.md §4.3 conflict).
    stopRequested_ = true;
    stopStatus_ = RunStatus::Ended;
    if (listener_) listener_->onEnd(pc);
}

}  // namespace ge
