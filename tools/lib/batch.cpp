// SPDX-License-Identifier: MIT
#include "tools/lib/batch.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "tools/lib/json_io.h"

namespace ge::tools {

namespace fs = std::filesystem;

namespace {

double nowSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int fail(const std::string& msg) {
    std::fprintf(stderr, "ge2gl: %s\n", msg.c_str());
    return 1;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

bool digitsOnly(const std::string& s, size_t maxLen) {
    return !s.empty() && s.size() <= maxLen && s.find_first_not_of("0123456789") == std::string::npos;
}

// A JSON member, or null when the object has none.
const Json* member(const Json& obj, const char* key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

// A whole number 0..2^53 from a JSON number ("7" or "7.0").
bool wholeNumber(const Json* v, u64& out) {
    constexpr u64 kMax = u64(1) << 53;
    if (!v || !v->is_number()) return false;
    if (v->is_number_unsigned()) {
        const u64 n = v->get<u64>();
        if (n > kMax) return false;
        out = n;
        return true;
    }
    if (v->is_number_integer()) {
        const std::int64_t i = v->get<std::int64_t>();
        if (i < 0 || u64(i) > kMax) return false;
        out = u64(i);
        return true;
    }
    const double d = v->get<double>();
    if (!(d >= 0) || d > double(kMax) || d != std::floor(d)) return false;
    out = u64(d);
    return true;
}

}  // namespace

// ---- shards and order ----

bool parseShard(const std::string& text, Shard& out, std::string& err) {
    const size_t slash = text.find('/');
    const std::string why = "expected i/n with 1 <= i <= n <= 100000 (e.g. 2/4)";
    if (slash == std::string::npos || !digitsOnly(text.substr(0, slash), 6) || !digitsOnly(text.substr(slash + 1), 6)) {
        err = why;
        return false;
    }
    const u64 i = std::stoull(text.substr(0, slash)), n = std::stoull(text.substr(slash + 1));
    if (i < 1 || n < 1 || i > n || n > 100000) {
        err = why;
        return false;
    }
    out.index = i, out.count = n;
    return true;
}

std::vector<IndexedDump> sortDumps(const std::vector<std::string>& paths) {
    std::vector<std::pair<std::string, std::string>> keyed;
    for (const auto& p : paths) keyed.emplace_back(dumpName(p), p);
    std::sort(keyed.begin(), keyed.end());
    std::vector<IndexedDump> out;
    for (size_t i = 0; i < keyed.size(); ++i) out.push_back({u64(i + 1), keyed[i].second});
    return out;
}

std::vector<IndexedDump> shardDumps(const std::vector<IndexedDump>& sorted, const Shard& s) {
    std::vector<IndexedDump> out;
    for (const auto& d : sorted)
        if ((d.index - 1) % s.count == s.index - 1) out.push_back(d);
    return out;
}

// ---- summary and JSON ----

CompareSummary summarize(const std::vector<CompareRow>& rows) {
    CompareSummary s;
    std::vector<double> mses, times;
    for (const CompareRow& r : rows)
        if (r.error.empty()) {
            mses.push_back(r.mse);
            times.push_back(r.seconds);
            s.within01 += r.mse <= 0.1;
            s.within10 += r.mse <= 10;
        }
    s.dumps = rows.size();
    s.rendered = mses.size();
    s.medianMse = median(mses);
    s.medianSeconds = median(times);
    return s;
}

std::string summaryLine(const CompareSummary& s, bool times) {
    char buf[256];
    int n = std::snprintf(buf, sizeof buf, "summary: %zu dumps, %zu rendered, %d within MSE 0.1, %d within MSE 10, median MSE %.4f",
                          s.dumps, s.rendered, s.within01, s.within10, s.medianMse);
    if (times) std::snprintf(buf + n, sizeof buf - size_t(n), ", median time %.3f s", s.medianSeconds);
    return buf;
}

std::string compareJson(const CompareReport& r) {
    const CompareSummary s = summarize(r.rows);
    Json j;
    j["backend"] = r.backend;
    if (!r.accuracy.empty()) j["accuracy"] = r.accuracy;
    if (r.backend == "gl") {
        j["gl_mode"] = r.glMode;
        j["scale"] = r.scale;
    }
    if (!r.refBackend.empty()) j["ref_backend"] = r.refBackend;
    if (r.sharded) {
        Json& shard = j["shard"];
        shard["index"] = r.shard.index;
        shard["count"] = r.shard.count;
        shard["dumps"] = r.dumps;
    }
    Json& results = j["results"] = Json::array();
    for (const CompareRow& row : r.rows) {
        Json e;
        e["index"] = row.index;
        e["name"] = row.name;
        if (!row.dump.empty()) e["dump"] = row.dump;
        if (!row.reference.empty()) e["reference"] = row.reference;
        if (row.error.empty()) {
            e["mse"] = numberValue(row.mse);
            e["psnr"] = numberValue(row.psnr);
            if (r.times) e["seconds"] = numberValue(row.seconds);
        } else {
            e["error"] = row.error;
        }
        results.push_back(std::move(e));
    }
    j["median_mse"] = numberValue(s.medianMse);
    if (r.times) j["median_seconds"] = numberValue(s.medianSeconds);
    j["within_0_1"] = s.within01;
    j["within_10"] = s.within10;
    JsonLayout layout;
    layout.rowArrays = layout.emptyRowsOnTwoLines = {"results"};
    layout.sameLine = {"scale"};
    return jsonDocument(j, layout);
}

bool parseCompareJson(const std::string& text, CompareReport& out, std::string& err) {
    Json root;
    if (!parseJson(text, root, err)) return false;
    if (!root.is_object()) return err = "not a JSON object", false;
    out = CompareReport();
    const Json* backend = member(root, "backend");
    const Json* results = member(root, "results");
    if (!backend || !backend->is_string()) return err = "no \"backend\" string", false;
    if (!results || !results->is_array()) return err = "no \"results\" array", false;
    out.backend = backend->get<std::string>();
    out.times = member(root, "median_seconds") != nullptr;
    if (const Json* a = member(root, "accuracy")) {
        if (!a->is_string()) return err = "\"accuracy\" is not a string", false;
        out.accuracy = a->get<std::string>();
    }
    if (const Json* m = member(root, "gl_mode")) {
        if (!m->is_string()) return err = "\"gl_mode\" is not a string", false;
        out.glMode = m->get<std::string>();
    }
    if (const Json* sc = member(root, "scale")) {
        u64 v = 0;
        if (!wholeNumber(sc, v) || v < 1 || v > 8) return err = "\"scale\" is not a whole number from 1 to 8", false;
        out.scale = int(v);
    }
    if (const Json* rb = member(root, "ref_backend")) {
        if (!rb->is_string()) return err = "\"ref_backend\" is not a string", false;
        out.refBackend = rb->get<std::string>();
    }
    for (size_t i = 0; i < results->size(); ++i) {
        const Json& e = (*results)[i];
        const std::string where = "result " + std::to_string(i + 1);
        if (!e.is_object()) return err = where + " is not an object", false;
        CompareRow row;
        const Json* name = member(e, "name");
        if (!wholeNumber(member(e, "index"), row.index) || row.index == 0)
            return err = where + ": no \"index\" (files from ge2gl compare before sharding carry none)", false;
        if (!name || !name->is_string()) return err = where + ": no \"name\"", false;
        row.name = name->get<std::string>();
        for (auto [key, field] : {std::pair{"dump", &row.dump}, std::pair{"reference", &row.reference}})
            if (const Json* v = member(e, key)) {
                if (!v->is_string()) return err = where + ": \"" + key + "\" is not a string", false;
                *field = v->get<std::string>();
            }
        if (const Json* er = member(e, "error")) {
            if (!er->is_string()) return err = where + ": \"error\" is not a string", false;
            row.error = er->get<std::string>();
            if (row.error.empty()) row.error = "(empty error)";
        } else {
            const Json *mse = member(e, "mse"), *psnr = member(e, "psnr"), *sec = member(e, "seconds");
            if (!mse || !mse->is_number() || !psnr || !psnr->is_number())
                return err = where + ": needs \"mse\" and \"psnr\" numbers, or an \"error\"", false;
            if (out.times != (sec != nullptr))
                return err = where + (out.times ? ": no \"seconds\" although the file has \"median_seconds\""
                                                : ": \"seconds\" although the file has no \"median_seconds\""),
                       false;
            if (sec && !sec->is_number()) return err = where + ": \"seconds\" is not a number", false;
            row.mse = mse->get<double>(), row.psnr = psnr->get<double>(), row.seconds = sec ? sec->get<double>() : 0;
        }
        out.rows.push_back(row);
    }
    if (const Json* sh = member(root, "shard")) {
        if (!sh->is_object() || !wholeNumber(member(*sh, "index"), out.shard.index) ||
            !wholeNumber(member(*sh, "count"), out.shard.count) || !wholeNumber(member(*sh, "dumps"), out.dumps) ||
            out.shard.index < 1 || out.shard.index > out.shard.count)
            return err = "bad \"shard\" object (needs index, count, dumps with 1 <= index <= count)", false;
        out.sharded = true;
    } else {
        // An unsharded run: shard 1 of 1 with every dump.
        out.shard = Shard{};
        out.dumps = out.rows.size();
    }
    return true;
}

bool mergeReports(const std::vector<CompareReport>& reports, const std::vector<std::string>& files, CompareReport& out,
                  std::string& err) {
    if (reports.empty()) return err = "nothing to merge", false;
    const CompareReport& first = reports[0];
    const std::string shardOf = "/" + std::to_string(first.shard.count);
    std::map<u64, size_t> byShard;  // shard index -> file
    for (size_t f = 0; f < reports.size(); ++f) {
        const CompareReport& r = reports[f];
        const std::string& name = files[f];
        if (r.backend != first.backend)
            return err = name + " is a '" + r.backend + "' run, " + files[0] + " a '" + first.backend + "' run", false;
        if (r.shard.count != first.shard.count)
            return err = name + " is shard " + std::to_string(r.shard.index) + "/" + std::to_string(r.shard.count) +
                         ", " + files[0] + " shard " + std::to_string(first.shard.index) + shardOf + ": not one run",
                   false;
        if (r.dumps != first.dumps)
            return err = name + " belongs to a run of " + std::to_string(r.dumps) + " dumps, " + files[0] + " to one of " +
                         std::to_string(first.dumps),
                   false;
        if (r.glMode != first.glMode || r.scale != first.scale || r.refBackend != first.refBackend ||
            r.accuracy != first.accuracy)
            return err = name + " and " + files[0] +
                         " were rendered with different options (gl_mode, scale, ref_backend or accuracy)",
                   false;
        if (r.times != first.times)
            return err = "--json-no-times was given for " + (r.times ? files[0] : name) + " but not for " +
                         (r.times ? name : files[0]),
                   false;
        auto [it, fresh] = byShard.emplace(r.shard.index, f);
        if (!fresh)
            return err = "duplicate shard " + std::to_string(r.shard.index) + shardOf + ": " + files[it->second] +
                         " and " + name,
                   false;
    }
    std::string missing;
    for (u64 i = 1; i <= first.shard.count; ++i)
        if (!byShard.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i) + shardOf;
    if (!missing.empty())
        return err = "missing shard" + std::string(byShard.size() + 1 < first.shard.count ? "s " : " ") + missing + " (" +
                     std::to_string(byShard.size()) + " of " + std::to_string(first.shard.count) + " given)",
               false;
    out = CompareReport();
    out.backend = first.backend;
    out.accuracy = first.accuracy;
    out.glMode = first.glMode;
    out.scale = first.scale;
    out.refBackend = first.refBackend;
    out.dumps = first.dumps;
    out.times = first.times;
    std::vector<const CompareRow*> at(first.dumps + 1, nullptr);
    for (size_t f = 0; f < reports.size(); ++f) {
        const CompareReport& r = reports[f];
        for (const CompareRow& row : r.rows) {
            if (row.index > r.dumps || (row.index - 1) % r.shard.count != r.shard.index - 1)
                return err = files[f] + ": result " + std::to_string(row.index) + " (" + row.name +
                             ") does not belong to shard " + std::to_string(r.shard.index) + shardOf,
                       false;
            if (at[row.index]) return err = files[f] + ": result " + std::to_string(row.index) + " appears twice", false;
            at[row.index] = &row;
        }
    }
    for (u64 k = 1; k <= first.dumps; ++k) {
        if (!at[k]) {
            const u64 s = (k - 1) % first.shard.count + 1;
            return err = files[byShard[s]] + ": result " + std::to_string(k) + " of shard " + std::to_string(s) + shardOf +
                         " is missing (an incomplete file?)",
                   false;
        }
        out.rows.push_back(*at[k]);
    }
    return true;
}

// ---- progress ----

std::string progressText(size_t done, size_t total, double elapsed) {
    char buf[128];
    const double rate = elapsed > 0 ? double(done) / elapsed : 0;
    int n = std::snprintf(buf, sizeof buf, "%zu/%zu dumps", done, total);
    if (done > 0 && rate > 0) {
        const long eta = std::lround(double(total - done) / rate);
        n += std::snprintf(buf + n, sizeof buf - size_t(n), ", %.1f/s, ETA %ld:%02ld", rate, eta / 60, eta % 60);
    }
    return buf;
}

Progress::Progress(size_t total, std::FILE* out) : total_(total), out_(out), t0_(nowSeconds()) {
    on_ = total > 1 && out && ::isatty(::fileno(out));
}

void Progress::update(size_t done) {
    if (!on_) return;
    std::fprintf(out_, "\r\033[K%s", progressText(done, total_, nowSeconds() - t0_).c_str());
    std::fflush(out_);
    shown_ = true;
}

void Progress::clear() {
    if (!on_ || !shown_) return;
    std::fprintf(out_, "\r\033[K");
    std::fflush(out_);
    shown_ = false;
}

// ---- the commands ----

namespace {

bool writeText(const std::string& path, const std::string& text, std::string& err) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (f) f.write(text.data(), std::streamsize(text.size()));
    if (f) f.flush();
    if (!f) {
        err = "cannot write " + path + ": " + std::strerror(errno);
        return false;
    }
    return true;
}

}  // namespace

int runCompare(const CompareArgs& a) {
    const RenderOptions& opt = a.opt;
    if (a.refDir.empty() == a.refBackend.empty()) return fail("compare needs exactly one of --ref-dir or --ref-backend");
    if (!a.diffDir.empty()) {
        std::error_code ec;
        fs::create_directories(a.diffDir, ec);
    }
    const std::vector<IndexedDump> all = sortDumps(a.files);
    const std::vector<IndexedDump> mine = a.sharded ? shardDumps(all, a.shard) : all;
    CompareReport rep;
    rep.backend = opt.backend;
    rep.accuracy = opt.accuracy;
    rep.glMode = opt.glMode;
    rep.scale = opt.scale;
    rep.refBackend = a.refBackend;
    rep.sharded = a.sharded;
    rep.shard = a.shard;
    rep.dumps = all.size();
    rep.times = a.jsonTimes;
    int failures = 0;
    if (a.sharded)
        std::printf("shard %llu/%llu: %zu of %zu dumps\n", (unsigned long long)a.shard.index,
                    (unsigned long long)a.shard.count, mine.size(), all.size());
    std::printf("%-60s %12s %9s %8s\n", "dump", "MSE", "PSNR", "time s");
    std::fflush(stdout);
    Progress progress(mine.size());
    progress.update(0);
    for (size_t k = 0; k < mine.size(); ++k) {
        const std::string& path = mine[k].path;
        CompareRow row;
        row.index = mine[k].index;
        row.name = dumpName(path);
        row.dump = path;
        RenderOutput out;
        std::string err;
        Image ref;
        if (!renderDumpFile(path, opt, out, err)) {
            row.error = err;
        } else if (!a.refDir.empty()) {
            row.reference = (fs::path(a.refDir) / (row.name + "-soft.png")).string();
            if (!readImage(row.reference, ref, err)) row.error = err;
        } else {
            RenderOptions ro = opt;
            ro.backend = a.refBackend;
            RenderOutput refOut;
            if (!renderDumpFile(path, ro, refOut, err)) row.error = "reference: " + err;
            else ref = refOut.frame;
        }
        if (row.error.empty()) {
            row.mse = mseRGB(out.frame, ref);
            if (row.mse < 0) row.error = "reference image smaller than 480x272";
            row.psnr = psnrFromMse(row.mse);
            row.seconds = out.seconds;
            if (!a.diffDir.empty() && row.mse > 0) {
                std::string e2;
                writePng((fs::path(a.diffDir) / (row.name + "-diff.png")).string(), diffImage(out.frame, ref), e2);
                writePng((fs::path(a.diffDir) / (row.name + "-" + opt.backend + ".png")).string(), out.frame, e2);
            }
        }
        progress.clear();
        if (!row.error.empty()) {
            ++failures;
            std::printf("%-60s %12s  %s\n", row.name.c_str(), "ERROR", row.error.c_str());
        } else {
            if (a.maxMse >= 0 && row.mse > a.maxMse) ++failures;
            std::printf("%-60s %12.4f %9.2f %8.3f\n", row.name.c_str(), row.mse, row.psnr, row.seconds);
        }
        std::fflush(stdout);
        rep.rows.push_back(row);
        progress.update(k + 1);
    }
    progress.clear();
    std::printf("%s\n", summaryLine(summarize(rep.rows)).c_str());
    if (!a.jsonPath.empty()) {
        std::string err;
        if (!writeText(a.jsonPath, compareJson(rep), err)) return fail(err);
    }
    return failures ? 1 : 0;
}

int runMerge(const std::vector<std::string>& inputs, const std::string& output) {
    std::vector<CompareReport> reports;
    for (const auto& path : inputs) {
        std::ifstream f(path, std::ios::binary);
        if (!f) return fail("cannot read " + path + ": " + std::strerror(errno));
        std::stringstream ss;
        ss << f.rdbuf();
        CompareReport r;
        std::string err;
        if (!parseCompareJson(ss.str(), r, err)) return fail(path + ": " + err);
        reports.push_back(std::move(r));
    }
    CompareReport merged;
    std::string err;
    if (!mergeReports(reports, inputs, merged, err)) return fail(err);
    if (!writeText(output, compareJson(merged), err)) return fail(err);
    std::printf("%s\n", summaryLine(summarize(merged.rows), merged.times).c_str());
    return 0;
}

}  // namespace ge::tools
