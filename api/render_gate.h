// SPDX-License-Identifier: MIT
// The renderer as the plugin API's engine sees it: every call forwarded to the backend, the
// long ones (drawing, flushes, write-backs, transfers) made with the handle's lock released.
//
// Why (docs/plugin-api.md "Threads"): an emulator's CPU thread updates stalls, queues lists,
// writes guest memory and reads GE registers while its GE thread draws. Holding the handle's
// lock through a draw made those calls wait for the draw (a second and more for a list of
// full-screen blended sprites). The GE-running thread therefore leaves the lock while the
// backend works ("rendering"); the engine stands inside one command then and does not change
// its state until it has the lock again. Calls that only read the engine's state or change the
// list queue ("light" calls, Call::Light) go on meanwhile; what they would tell the backend
// (memory written, the host may have written) is kept and handed over by the GE thread when
// the backend returns. Every other call waits until no draw is in progress (Call's constructor).
#pragma once
#include "hle/renderer.h"

struct ge2gl_context;

namespace ge2gl_impl {

class RenderGate : public ge::Renderer {
public:
    RenderGate(ge2gl_context* h, ge::Renderer* inner) : h_(h), inner_(inner) {}

    void drawPrim(const ge::PrimPacket& p) override;
    void drawPatch(const ge::PatchPacket& p) override;
    void drawImmediate(const ge::ImmPacket& p) override;
    void blockTransfer(const ge::TransferPacket& t, ge::Memory& mem) override;
    void finish() override;
    void syncMemoryForRead(ge::u32 addr, ge::u32 size) override;
    void memoryWritten(ge::u32 addr, ge::u32 size) override;
    void flushToMemory() override;

    // Short bookkeeping: forwarded with the lock held.
    void clutLoaded(const ge::GeState& s) override { inner_->clutLoaded(s); }
    void textureFlush() override { inner_->textureFlush(); }
    void textureSync() override { inner_->textureSync(); }
    void hostMayHaveWritten(bool frameBuffers) override { inner_->hostMayHaveWritten(frameBuffers); }
    void takeDirtyRanges(std::vector<std::pair<ge::u32, ge::u32>>& out) override { inner_->takeDirtyRanges(out); }
    bool holdsNewerThanMemory(ge::u32 addr, ge::u32 size) const override {
        return inner_->holdsNewerThanMemory(addr, size);
    }
    ge::u64 pixelWork() const override { return inner_->pixelWork(); }
    void setPixelBudget(ge::u64 pixels) override { inner_->setPixelBudget(pixels); }

private:
    // Runs f with the handle's lock released when called by the thread running the GE under it;
    // otherwise (a host call, a callback) as is.
    template <class F>
    void outside(F&& f);

    ge2gl_context* h_;
    ge::Renderer* inner_;
};

}  // namespace ge2gl_impl
