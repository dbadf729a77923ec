// SPDX-License-Identifier: GPL-2.0-or-later
// Part of ge2gl's PPSSPP integration (integrations/ppsspp). This file is compiled into PPSSPP,
// which is licensed under the GNU GPL version 2.0 or later; so is this file.
//
// sceGe_user on ge2gl's GE: the same module name and function NIDs as PPSSPP's table in
// Core/HLE/sceGe.cpp, each function handing the call to GPU_Ge2gl, where libge2gl decides what it
// does (list IDs, states, errors). What stays PPSSPP's is the CPU side of a syscall: the cycles a
// call costs the emulated CPU (the same figures PPSSPP's own sceGe charges), rescheduling, and the
// kernel's pointer checks that come before the GE is asked.
#include "GPU/Ge2gl/Ge2glSceGe.h"

#include "Common/CommonTypes.h"
#include "Common/Log.h"
#include "Core/Config.h"
#include "Core/CoreParameter.h"
#include "Core/HLE/ErrorCodes.h"
#include "Core/HLE/FunctionWrappers.h"
#include "Core/HLE/HLE.h"
#include "Core/System.h"
#include "GPU/Ge2gl/Ge2glGpu.h"

namespace {

// Every function below runs only after the GPU core started (the game's code runs after
// GPU_Init); without it the call fails as the firmware fails a call it cannot serve.
constexpr u32 kNoGe = 0x80000021;  // SCE_ERROR_BUSY

GPU_Ge2gl *Core() { return GPU_Ge2gl::Active(); }

u32 sceGeEdramGetAddr() {
    hleEatCycles(150);
    return hleLogVerbose(Log::sceGe, 0x04000000);
}

u32 sceGeEdramGetSize() { return hleLogVerbose(Log::sceGe, 0x00200000); }

u32 sceGeListEnQueue(u32 list, u32 stall, int cbid, u32 args) {
    const u32 r = Core() ? u32(Core()->SceEnqueue(list, stall, cbid, args, false)) : kNoGe;
    hleEatCycles(490);
    hleCoreTimingForceCheck();
    return hleLogDebug(Log::sceGe, r);
}

u32 sceGeListEnQueueHead(u32 list, u32 stall, int cbid, u32 args) {
    const u32 r = Core() ? u32(Core()->SceEnqueue(list, stall, cbid, args, true)) : kNoGe;
    hleEatCycles(480);
    hleCoreTimingForceCheck();
    return hleLogDebug(Log::sceGe, r);
}

int sceGeListDeQueue(u32 id) {
    const int r = Core() ? Core()->SceDequeue(int32_t(id)) : int(kNoGe);
    hleReSchedule("dlist dequeued");
    return hleLogDebug(Log::sceGe, r);
}

int sceGeListUpdateStallAddr(u32 id, u32 stall) {
    hleEatCycles(190);
    hleCoreTimingForceCheck();
    const int r = Core() ? Core()->SceUpdateStall(int32_t(id), stall) : int(kNoGe);
    return hleLogDebug(Log::sceGe, r);
}

int sceGeListSync(u32 id, u32 mode) {
    hleEatCycles(220);
    const int r = Core() ? Core()->SceListSync(int32_t(id), int32_t(mode)) : int(kNoGe);
    return hleLogDebug(Log::sceGe, r);
}

u32 sceGeDrawSync(u32 mode) {
    if (PSP_CoreParameter().compat.flags().DrawSyncEatCycles)
        hleEatCycles(500000);
    else if (!PSP_CoreParameter().compat.flags().DrawSyncInstant)
        hleEatCycles(1240);
    const u32 r = Core() ? u32(Core()->SceDrawSync(int32_t(mode))) : kNoGe;
    return hleLogDebug(Log::sceGe, r);
}

int sceGeBreak(u32 mode, u32 param) {
    if (mode > 1) return hleLogWarning(Log::sceGe, SCE_KERNEL_ERROR_INVALID_MODE, "invalid mode");
    // The kernel refuses a parameter block reaching past user space before the GE is asked
    // (pspautotests gpu/ge/break: 0xDEADBEEF, -1 and 0x7FFFFFF0 give 0x80000023).
    if (int32_t(param) < 0 || int32_t(param + 16) < 0) return hleLogWarning(Log::sceGe, SCE_KERNEL_ERROR_PRIV_REQUIRED, "invalid param pointer");
    const int r = Core() ? Core()->SceBreak(int32_t(mode)) : int(kNoGe);
    return hleLogDebug(Log::sceGe, r);
}

int sceGeContinue() {
    const int r = Core() ? Core()->SceContinue() : int(kNoGe);
    hleEatCycles(220);
    hleReSchedule("ge continue");
    return hleLogDebug(Log::sceGe, r);
}

u32 sceGeSetCallback(u32 structAddr) {
    const u32 r = Core() ? u32(Core()->SceSetCallback(structAddr)) : kNoGe;
    return hleLogDebug(Log::sceGe, r);
}

int sceGeUnsetCallback(u32 cbid) {
    const int r = Core() ? Core()->SceUnsetCallback(int32_t(cbid)) : int(kNoGe);
    return hleLogDebug(Log::sceGe, r);
}

u32 sceGeSaveContext(u32 addr) {
    const u32 r = Core() ? u32(Core()->SceSaveContext(addr)) : kNoGe;
    return hleLogDebug(Log::sceGe, r);
}

u32 sceGeRestoreContext(u32 addr) {
    const u32 r = Core() ? u32(Core()->SceRestoreContext(addr)) : kNoGe;
    return hleLogDebug(Log::sceGe, r);
}

u32 sceGeGetCmd(int op) {
    const u32 r = Core() ? Core()->SceGetCmd(op) : kNoGe;
    return hleLogDebug(Log::sceGe, r);
}

int sceGeGetMtx(int type, u32 addr) {
    const int r = Core() ? Core()->SceGetMtx(type, addr) : int(kNoGe);
    return hleLogDebug(Log::sceGe, r);
}

int sceGeGetStack(int index, u32 addr) {
    const int r = Core() ? Core()->SceGetStack(index, addr) : int(kNoGe);
    return hleLogDebug(Log::sceGe, r);
}

u32 sceGeEdramSetAddrTranslation(u32 value) {
    const u32 r = Core() ? u32(Core()->SceEdramSetAddrTranslation(value)) : kNoGe;
    return hleLogDebug(Log::sceGe, r);
}

// NIDs: the firmware's sceGe_user exports (the same numbers PPSSPP's table uses).
const HLEFunction kSceGeUser[] = {
    {0xE47E40E4, &WrapU_V<sceGeEdramGetAddr>, "sceGeEdramGetAddr", 'x', ""},
    {0xAB49E76A, &WrapU_UUIU<sceGeListEnQueue>, "sceGeListEnQueue", 'x', "xxip"},
    {0x1C0D95A6, &WrapU_UUIU<sceGeListEnQueueHead>, "sceGeListEnQueueHead", 'x', "xxip"},
    {0xE0D68148, &WrapI_UU<sceGeListUpdateStallAddr>, "sceGeListUpdateStallAddr", 'i', "xx"},
    {0x03444EB4, &WrapI_UU<sceGeListSync>, "sceGeListSync", 'x', "xx"},
    {0xB287BD61, &WrapU_U<sceGeDrawSync>, "sceGeDrawSync", 'x', "x"},
    {0xB448EC0D, &WrapI_UU<sceGeBreak>, "sceGeBreak", 'i', "xx"},
    {0x4C06E472, &WrapI_V<sceGeContinue>, "sceGeContinue", 'i', ""},
    {0xA4FC06A4, &WrapU_U<sceGeSetCallback>, "sceGeSetCallback", 'i', "p"},
    {0x05DB22CE, &WrapI_U<sceGeUnsetCallback>, "sceGeUnsetCallback", 'i', "x"},
    {0x1F6752AD, &WrapU_V<sceGeEdramGetSize>, "sceGeEdramGetSize", 'x', ""},
    {0xB77905EA, &WrapU_U<sceGeEdramSetAddrTranslation>, "sceGeEdramSetAddrTranslation", 'x', "x"},
    {0xDC93CFEF, &WrapU_I<sceGeGetCmd>, "sceGeGetCmd", 'x', "i"},
    {0x57C8945B, &WrapI_IU<sceGeGetMtx>, "sceGeGetMtx", 'i', "ip"},
    {0x438A385A, &WrapU_U<sceGeSaveContext>, "sceGeSaveContext", 'x', "x"},
    {0x0BF608FB, &WrapU_U<sceGeRestoreContext>, "sceGeRestoreContext", 'x', "x"},
    {0x5FB86AB0, &WrapI_U<sceGeListDeQueue>, "sceGeListDeQueue", 'i', "x"},
    {0xE66CB92E, &WrapI_IU<sceGeGetStack>, "sceGeGetStack", 'i', "ix"},
};

}  // namespace

bool Ge2gl_RegisterSceGeModule() {
    if (!Ge2gl_Selected()) return false;
    RegisterHLEModule("sceGe_user", ARRAY_SIZE(kSceGeUser), kSceGeUser);
    return true;
}
