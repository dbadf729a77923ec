// SPDX-License-Identifier: MIT
// Frame-dump recording through the C ABI (include/ge2gl/ge2gl.h "Frame-dump recording";
// docs/recording.md): a hle/dump FrameRecorder attached to the handle's engine between
// ge2gl_record_begin and ge2gl_record_end, and the .ppdmp file written at the end.
#include "api/context.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "hle/dump/ppdmp.h"
#include "hle/dump/recorder.h"

using namespace ge2gl_impl;

// The handle's recording (context.h holds it by shared_ptr, so the type stays private here).
struct ge2gl_recording {
    std::string path;
    ge::dump::FrameRecorder rec;
    ge2gl_recording(ge::GeEngine& e, std::string p) : path(std::move(p)), rec(e) {}
};

namespace {

std::string sysError(const char* what, const std::string& path, int err) {
    return std::string(what) + " '" + path + "': " + std::strerror(err);
}

// Attaching or detaching mid-command (from a callback inside a run, or while another thread's run
// is inside a command) would change the engine's observers while it iterates them.
ge2gl_status refuseMidRun(ge2gl_context* h, Call& c, const char* what) {
    if (reentrant(h)) return c.error(GE2GL_ERR_REENTRANT, std::string(what) + " cannot be called from inside a GE callback");
    if (h->sce->inRun()) return c.error(GE2GL_ERR_BAD_STATE, std::string(what) + ": the GE is executing a command");
    return GE2GL_OK;
}

// Checks at begin that the file can be written, so a bad path fails at once rather than after a
// recorded frame; leaves no file behind that was not there.
bool probeWritable(const std::string& path, int& err) {
    const bool existed = ::access(path.c_str(), F_OK) == 0;
    std::FILE* f = std::fopen(path.c_str(), "ab");  // "a": an existing file keeps its bytes
    if (!f) {
        err = errno;
        return false;
    }
    std::fclose(f);
    if (!existed) std::remove(path.c_str());
    return true;
}

bool writeFile(const std::string& path, const std::vector<ge::u8>& bytes, int& err) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) {
        err = errno;
        return false;
    }
    const bool wrote = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    if (!wrote) err = errno ? errno : EIO;
    if (std::fclose(f) != 0 && wrote) {
        err = errno ? errno : EIO;
        return false;
    }
    return wrote;
}

}  // namespace

extern "C" {

ge2gl_status ge2gl_record_begin(ge2gl_context* h, const char* path) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!path || !*path) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "path is NULL or empty");
        if (h->recording)
            return c.error(GE2GL_ERR_BAD_STATE, "already recording to '" + h->recording->path + "': call ge2gl_record_end first");
        if (ge2gl_status s = refuseMidRun(h, c, "ge2gl_record_begin"); s != GE2GL_OK) return s;
        int err = 0;
        if (!probeWritable(path, err)) return c.error(GE2GL_ERR_INVALID_ARGUMENT, sysError("cannot write the dump to", path, err));
        auto rec = std::make_shared<ge2gl_recording>(*h->engine, path);
        rec->rec.begin();
        h->recording = std::move(rec);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_record_display(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!h->recording) return c.error(GE2GL_ERR_BAD_STATE, "not recording: call ge2gl_record_begin first");
        if (format < GE2GL_FORMAT_565 || format > GE2GL_FORMAT_8888) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown pixel format");
        if (ge2gl_status s = refuseMidRun(h, c, "ge2gl_record_display"); s != GE2GL_OK) return s;
        h->recording->rec.display(addr, stride, ge::u32(format));
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_record_end(ge2gl_context* h) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!h->recording)
            return c.error(GE2GL_ERR_BAD_STATE, "not recording: ge2gl_record_begin was not called or the recording already ended");
        if (ge2gl_status s = refuseMidRun(h, c, "ge2gl_record_end"); s != GE2GL_OK) return s;
        std::shared_ptr<ge2gl_recording> rec = std::move(h->recording);
        h->recording.reset();
        rec->rec.end();
        if (!rec->rec.failure().empty()) return c.error(GE2GL_ERR_BAD_STATE, rec->rec.failure() + "; nothing written");
        const std::vector<ge::u8> bytes = ge::dump::serializeDump(rec->rec.dump());
        if (bytes.empty())
            return c.error(GE2GL_ERR_BAD_STATE, "the recording does not fit in a .ppdmp (over the reader's size limits); nothing written");
        int err = 0;
        if (!writeFile(rec->path, bytes, err)) return c.error(GE2GL_ERR_INVALID_ARGUMENT, sysError("I/O error writing the dump", rec->path, err));
        // Success; what the dump could not express is left for ge2gl_last_message.
        std::string notes;
        for (const std::string& w : rec->rec.warnings()) notes += (notes.empty() ? "" : "; ") + w;
        h->message = notes;
        return GE2GL_OK;
    });
}

}  // extern "C"
