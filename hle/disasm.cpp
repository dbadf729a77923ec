// SPDX-License-Identifier: MIT
#include "hle/disasm.h"

#include <cstdio>

#include "hle/ge_state.h"

namespace ge {

std::string disassemble(u32 word) {
    const u8 op = u8(word >> 24);
    std::string s = geCmdName(op);
    std::string fields = geFormatFields(word);
    if (!fields.empty()) {
        s += ' ';
        s += fields;
    } else if (word & 0xFFFFFF) {
        char buf[16];
        std::snprintf(buf, sizeof buf, " 0x%06x", word & 0xFFFFFF);
        s += buf;
    }
    return s;
}

}  // namespace ge
