// SPDX-License-Identifier: MIT
// A Renderer between the engine and a backend that numbers the draws and lets a tool act on each
// (accuracy tools): `keep` decides whether draw n reaches the backend (render/compare
// --skip/--only), `after` runs once the backend has it (blame's per-draw ownership, bisect's
// lockstep comparison). Draws are numbered from 1 in the order they reach the backend: PRIM,
// BEZIER and SPLINE kicks with vertices, and immediate-mode primitives, in one sequence.
// --replay-end (player.h) counts kick words in the dump instead, empty PRIMs included: on a dump
// with empty kicks or immediate-mode primitives the two numberings differ (README, "blame").
// Everything else is forwarded unchanged.
#pragma once
#include <functional>
#include <string>

#include "hle/renderer.h"

namespace ge::tools {

// What the engine handed the backend for one draw (DrawHook::last()).
struct DrawInfo {
    u64 draw = 0;                     // DrawHook number (from 1); 0: not a draw
    std::string kind;                 // "prim" | "bezier" | "spline" | "immediate"
    GePrimType prim = GE_PRIM_POINTS; // prim / immediate: resolved primitive type
    u32 vertices = 0;                 // vertex (or index) count; control points for patches
    std::string state;                // filled by tools that summarise the state (blame.h)
    u32 fbAddr = 0, fbStride = 0, fbFormat = 0;  // the draw's colour target (filled likewise)
};

class DrawHook final : public Renderer {
public:
    explicit DrawHook(Renderer& inner) : inner_(inner) {}
    Renderer& inner() { return inner_; }
    u64 draws() const { return draws_; }           // draws seen so far (kept or not)
    const DrawInfo& last() const { return last_; }  // kind, primitive, vertices of the last draw

    std::function<bool(u64 draw)> keep;   // null: keep every draw
    std::function<void(u64 draw)> after;  // null: nothing
    // After a block transfer (transfer true: the backend may hold the result, sync before
    // reading) or a memoryWritten() (guest memory holds the bytes) reached the backend. May be null.
    std::function<void(u32 addr, u32 size, bool transfer)> afterWrite;

    void drawPrim(const PrimPacket& p) override {
        draw("prim", p.prim, p.count, p, [&](const PrimPacket& q) { inner_.drawPrim(q); });
    }
    void drawPatch(const PatchPacket& p) override {
        draw(p.spline ? "spline" : "bezier", GE_PRIM_TRIANGLES, p.ucount * p.vcount, p,
             [&](const PatchPacket& q) { inner_.drawPatch(q); });
    }
    void drawImmediate(const ImmPacket& p) override {
        draw("immediate", p.prim, u32(p.vertices.size()), p, [&](const ImmPacket& q) { inner_.drawImmediate(q); });
    }
    void blockTransfer(const TransferPacket& t, Memory& mem) override {
        inner_.blockTransfer(t, mem);
        if (afterWrite) afterWrite(t.dstBegin(), t.dstBytes(), true);
    }
    void clutLoaded(const GeState& st) override { inner_.clutLoaded(st); }
    void textureFlush() override { inner_.textureFlush(); }
    void textureSync() override { inner_.textureSync(); }
    void finish() override { inner_.finish(); }
    void syncMemoryForRead(u32 addr, u32 size) override { inner_.syncMemoryForRead(addr, size); }
    void memoryWritten(u32 addr, u32 size) override {
        inner_.memoryWritten(addr, size);
        if (afterWrite) afterWrite(addr, size, false);
    }
    void flushToMemory() override { inner_.flushToMemory(); }
    void hostMayHaveWritten(bool frameBuffers) override { inner_.hostMayHaveWritten(frameBuffers); }
    void takeDirtyRanges(std::vector<std::pair<u32, u32>>& out) override { inner_.takeDirtyRanges(out); }
    bool holdsNewerThanMemory(u32 addr, u32 size) const override { return inner_.holdsNewerThanMemory(addr, size); }
    u64 pixelWork() const override { return inner_.pixelWork(); }
    void setPixelBudget(u64 pixels) override { inner_.setPixelBudget(pixels); }

private:
    // A packet's `dirty` names the register groups changed since the previous packet; a left-out
    // draw's groups go with the next draw that reaches the backend, whose caches would otherwise
    // keep state from before the left-out draw's changes.
    template <class P, class F>
    void draw(const char* kind, GePrimType prim, u32 vertices, const P& p, F&& f) {
        const u64 n = ++draws_;
        last_ = DrawInfo{};
        last_.draw = n, last_.kind = kind, last_.prim = prim, last_.vertices = vertices;
        if (keep && !keep(n)) {
            skippedDirty_ |= p.dirty;
            return;
        }
        if (skippedDirty_ & ~p.dirty) {
            P q = p;
            q.dirty |= skippedDirty_;
            skippedDirty_ = 0;
            f(q);
        } else {
            skippedDirty_ = 0;
            f(p);
        }
        if (after) after(n);
    }
    Renderer& inner_;
    u64 draws_ = 0;
    u32 skippedDirty_ = 0;
    DrawInfo last_;
};

}  // namespace ge::tools
