// SPDX-License-Identifier: MIT
#include "tests/conformance/gu_sim.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "backend/factory.h"

namespace ge::conformance {

bool GuSim::create(const std::string& backend, std::string& err) {
    backend_ = backend;
    mem_ = std::make_unique<Memory>();
    ge::backend::BackendOptions bo;
    // The hardware values are the PSP's: the psp profile (geometry/accuracy_profile.h). For
    // measuring the other profile's counts (docs/conformance.md), GE2GL_CONFORMANCE_ACCURACY=ppsspp;
    // the floors are the psp profile's.
    bo.accuracy = ge::geo::AccuracyProfile::psp();
    if (const char* acc = std::getenv("GE2GL_CONFORMANCE_ACCURACY")) {
        if (!ge::geo::AccuracyProfile::fromName(acc, bo.accuracy)) {
            err = std::string("GE2GL_CONFORMANCE_ACCURACY: unknown profile ") + acc;
            return false;
        }
    }
    if (backend == "soft") {
        bo.kind = ge::backend::BackendKind::Soft;
        bo.threads = 1;
    } else if (backend == "gl") {
        bo.kind = ge::backend::BackendKind::Gl;
    } else {
        err = "unknown backend " + backend;
        return false;
    }
    renderer_ = ge::backend::createBackend(*mem_, bo, err).renderer;
    if (!renderer_) return false;
    engine_ = std::make_unique<GeEngine>(*mem_, renderer_.get());
    return true;
}

void GuSim::init() {
    // GeState starts with every register 0, as sceGuInit's reset list leaves all but these two.
    b_ = std::make_unique<ListBuilder>(mem_.get(), arena_);
    b_->cmd(GE_CMD_TBW0, 0x040004);
    b_->cmd(GE_CMD_TSIZE0, 0x101);
    finishSync();
    firstStart_ = true;
}

ListBuilder& GuSim::start() {
    b_ = std::make_unique<ListBuilder>(mem_.get(), arena_);
    if (firstStart_) {
        static constexpr int kDither[16] = {-4, 0, -3, 1, 2, -2, 3, -1, -3, 1, -4, 0, 3, -1, 2, -2};
        b_->setDither(kDither);
        b_->cmd(GE_CMD_DIVIDE, (16 << 8) | 16);
        b_->colorMaterial(LIGHT_AMBIENT | LIGHT_DIFFUSE | LIGHT_SPECULAR);
        b_->specularPower(1.0f);
        b_->texScale(1.0f, 1.0f);
        firstStart_ = false;
    }
    return *b_;
}

void GuSim::finishSync() {
    b_->finish();
    const u32 addr = b_->placeList();
    arena_ = b_->arenaNext();
    engine_->startList(addr, 0);
    engine_->run();
    renderer_->finish();
}

void GuSim::cpuWrite(u32 addr, const void* data, u32 size) {
    renderer_->flushToMemory();  // the GE's earlier drawing lands before the CPU's bytes
    u8* p = mem_->ptr(addr, size);
    if (!p) return;
    std::memcpy(p, data, size);
    renderer_->memoryWritten(addr, size);
}

void GuSim::fillVram32(u32 offset, u32 value, u32 words) {
    std::vector<u32> buf(words, value);
    writeVram(offset, buf.data(), words * 4);
}

u32 GuSim::readVram32(u32 offset) {
    renderer_->flushToMemory();
    return readLE32(mem_->vram() + offset);
}

const u8* GuSim::readBytes(u32 addr, u32 size) {
    renderer_->flushToMemory();
    return mem_->ptr(addr, size);
}

u16 GuSim::readVram16(u32 offset) {
    renderer_->flushToMemory();
    return readLE16(mem_->vram() + offset);
}

int TestRun::passed() const {
    int n = 0;
    for (const Checkpoint& c : checkpoints) n += c.pass();
    return n;
}

std::string TestRun::report() const {
    char line[256];
    std::snprintf(line, sizeof line, "%s [%s]: %d/%d checkpoints\n", test.c_str(), backend.c_str(), passed(), total());
    std::string out = line;
    for (const Checkpoint& c : checkpoints)
        if (!c.pass()) {
            std::snprintf(line, sizeof line, "  FAIL %s: got %08x, hardware %08x (mask %08x)\n", c.name.c_str(), c.got,
                          c.expected, c.mask);
            out += line;
        }
    return out;
}

}  // namespace ge::conformance
