// SPDX-License-Identifier: MIT
// GE disassembler: names every command and field (from ge_cmds.def / ge_fields.def).
#pragma once
#include <string>

#include "hle/types.h"

namespace ge {

// "ATEST func=4 ref=0x80 mask=0xff"; unknown opcodes print as "UNKNOWN_03 0x123456".
std::string disassemble(u32 word);

}  // namespace ge
