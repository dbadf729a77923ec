// SPDX-License-Identifier: MIT
// Harness (i): the save-state loader (hle/savestate.h) and the GE that runs from whatever state it
// accepted. A blob that passes the checks must never lead the engine or the sceGe layer out of
// bounds, and a loaded state must save and load again.
//
// Input: u8 mode, then bytes. Mode bit 0: the bytes are a payload, wrapped in a correct header
// (size, xxHash64; bit 1 sets the guest-memory flag) so that the fuzzer reaches the section parsers
// past the checksum; else the bytes are the whole blob as a host would hand it over. A state that
// loads is run for at most 2,000 commands (drawing nothing: the loader is under test, not the
// renderers) and then saved and reloaded.
#include <xxhash.h>

#include <cstdint>
#include <cstdlib>

#include "hle/savestate.h"
#include "tests/fuzz/fuzz_common.h"

using namespace ge;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1 || size > fuzz::kMaxInput) return -1;
    const u8 mode = data[0];
    std::vector<u8> blob;
    if (mode & 1) {
        const u8* p = data + 1;
        const size_t n = size - 1;
        const u64 hash = XXH64(p, n, 0);
        const u8 head[] = {'G', 'E', '2', 'G', 'L', 'S', 'T', 0x1a, savestate::kFormatVersion, 0, 0, 0, u8((mode >> 1) & 1), 0, 0, 0};
        blob.assign(head, head + sizeof head);
        for (int i = 0; i < 8; ++i) blob.push_back(u8(u64(n) >> (8 * i)));
        for (int i = 0; i < 8; ++i) blob.push_back(u8(hash >> (8 * i)));
        blob.insert(blob.end(), p, p + n);
    } else {
        blob.assign(data + 1, data + size);
    }

    // 1 MiB of RAM keeps a memory section small enough to be reached.
    static Memory mem(1u << 20);
    mem.clear();
    NullRenderer null;
    GeEngine eng(mem, &null);
    SceGe sce(eng);
    savestate::HostFlags host;
    bool hadMemory = false;
    std::string err;
    if (!savestate::load(blob, eng, sce, mem, host, hadMemory, err)) {
        if (err.empty()) std::abort();  // a refusal always says why
        return 0;
    }
    eng.setTimeLimit(eng.stats().cycles + getime::cyclesFromMs(0.5));
    sce.run(2000);
    const std::vector<u8> again = savestate::save(eng, sce, hadMemory ? &mem : nullptr, host);
    GeEngine eng2(mem, &null);
    SceGe sce2(eng2);
    if (!savestate::load(again, eng2, sce2, mem, host, hadMemory, err)) std::abort();  // what we save, we load
    return 0;
}
