// SPDX-License-Identifier: MIT
// The renderer behind the handle's lock release (render_gate.h).
#include "api/render_gate.h"

#include <thread>

#include "api/context.h"

namespace ge2gl_impl {

template <class F>
void RenderGate::outside(F&& f) {
    ge2gl_context* h = h_;
    std::unique_lock<std::recursive_mutex>* lk = h->runLock;
    if (!lk || h->rendering || h->runThread != std::this_thread::get_id()) {
        f();
        return;
    }
    // The engine stands inside a command; its state stays as it is until the lock is back. The
    // GL context (if any) stays current here: calls that need it wait while `rendering`.
    h->rendering = true;
    lk->unlock();
    struct Relock {
        ge2gl_context* h;
        std::unique_lock<std::recursive_mutex>* lk;
        ~Relock() {
            lk->lock();
            h->rendering = false;
            applyDeferred(h);
            h->renderIdle.notify_all();
        }
    } relock{h, lk};
    f();
}

void RenderGate::drawPrim(const ge::PrimPacket& p) {
    outside([&] { inner_->drawPrim(p); });
}
void RenderGate::drawPatch(const ge::PatchPacket& p) {
    outside([&] { inner_->drawPatch(p); });
}
void RenderGate::drawImmediate(const ge::ImmPacket& p) {
    outside([&] { inner_->drawImmediate(p); });
}
void RenderGate::blockTransfer(const ge::TransferPacket& t, ge::Memory& mem) {
    outside([&] { inner_->blockTransfer(t, mem); });
}
void RenderGate::finish() {
    outside([&] { inner_->finish(); });
}
void RenderGate::syncMemoryForRead(ge::u32 addr, ge::u32 size) {
    outside([&] { inner_->syncMemoryForRead(addr, size); });
}
void RenderGate::memoryWritten(ge::u32 addr, ge::u32 size) {
    outside([&] { inner_->memoryWritten(addr, size); });
}
void RenderGate::flushToMemory() {
    outside([&] { inner_->flushToMemory(); });
}

}  // namespace ge2gl_impl
