// SPDX-License-Identifier: MIT
// Batch runs of `ge2gl compare`: the command itself, its JSON results, sharding (--shard i/n) and
// `ge2gl merge` of shard results, and the progress line on a terminal.
//
// Order and shards: compare runs its dumps in name order — sorted by NAME (the file name without
// .zip/.ppdmp, byte-wise), then by the whole path — whatever order they were given in, and numbers
// them 1..N in that order ("index" in the JSON). Shard i of n takes the dumps whose index k has
// (k - 1) mod n == i - 1: every n-th dump starting with the i-th. Every shard must be given the
// same dump list; the split then depends only on the names, not on the order a shell expands them.
//
// JSON (--json FILE), one result per dump in index order:
//   {
//     "backend": "soft",
//     "gl_mode": "hw", "scale": 2,                              only for backend gl
//     "ref_backend": "soft",                                    only with --ref-backend
//     "shard": {"index": 2, "count": 4, "dumps": 20},          only with --shard
//     "results": [
//       {"index": 1, "name": "NAME", "dump": "PATH", "reference": "PNG",
//        "mse": 0.25, "psnr": 54.2, "seconds": 0.31},
//       {"index": 2, "name": "NAME", "dump": "PATH", "error": "why"},
//       ...
//     ],
//     "median_mse": 0.25,
//     "median_seconds": 0.31,                                    not with --json-no-times
//     "within_0_1": 0,
//     "within_10": 1
//   }
// Written and read with nlohmann::json in the layout above (tools/lib/json_io.h). Numbers are
// written in a form that reads back as the same double (whole values without ".0"), so `merge`
// can recompute the summary exactly and writes what it read; a PSNR of infinity (identical
// pictures) is written as 999.
// "seconds" and "median_seconds" are left out with --json-no-times: the rest of the file is then
// the same from run to run, and merged shards are byte-identical to one unsharded run.
// "dump" is the dump's path and "reference" the reference picture's (with --ref-dir), both as
// given on the command line: with "gl_mode", "scale" and "ref_backend" they let `ge2gl report`
// render each dump again the same way (tools/lib/report.h). Files without them still parse.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "tools/lib/render.h"

namespace ge::tools {

struct Shard {
    u64 index = 1, count = 1;  // 1-based: shard `index` of `count`
};
// "i/n" with 1 <= i <= n <= 100000, decimal digits only. `err` says why not (no option name).
bool parseShard(const std::string& text, Shard& out, std::string& err);

struct IndexedDump {
    u64 index;  // 1-based position in name order
    std::string path;
};
// All dumps in name order, numbered; then the ones shard `s` takes.
std::vector<IndexedDump> sortDumps(const std::vector<std::string>& paths);
std::vector<IndexedDump> shardDumps(const std::vector<IndexedDump>& sorted, const Shard& s);

struct CompareRow {
    u64 index = 0;
    std::string name, error;  // error empty: rendered and compared
    std::string dump, reference;  // paths as given ("reference" empty with --ref-backend)
    double mse = -1, psnr = 0, seconds = 0;
};

struct CompareReport {
    std::string backend;
    // --accuracy (geometry/accuracy_profile.h names); empty when read from a file written before
    // the profiles existed (its renders followed neither profile exactly).
    std::string accuracy;
    std::string glMode = "exact";  // written for backend gl only
    int scale = 1;                 // written for backend gl only
    std::string refBackend;        // --ref-backend, empty with --ref-dir
    bool sharded = false;  // writes the "shard" object
    Shard shard;
    u64 dumps = 0;         // dumps in the whole run (all shards)
    bool times = true;     // "seconds", "median_seconds"
    std::vector<CompareRow> rows;
};

struct CompareSummary {
    size_t dumps = 0, rendered = 0;
    int within01 = 0, within10 = 0;
    double medianMse = 0, medianSeconds = 0;
};
CompareSummary summarize(const std::vector<CompareRow>& rows);
// "summary: 20 dumps, 20 rendered, 12 within MSE 0.1, ..." (no newline); the median time only
// with `times`.
std::string summaryLine(const CompareSummary& s, bool times = true);

std::string compareJson(const CompareReport& r);
// Reads what compareJson writes (any whitespace, any key order). `err` names what is wrong: a
// missing or mistyped member, or nlohmann's parse error with its line and column.
bool parseCompareJson(const std::string& text, CompareReport& out, std::string& err);

// Joins shard reports (files[i] names reports[i] in messages) into the report an unsharded run
// writes: checks that they come from one run (same backend, shard count, dump count, times or
// not), that every shard 1..n is there exactly once and that each holds exactly its dumps.
bool mergeReports(const std::vector<CompareReport>& reports, const std::vector<std::string>& files, CompareReport& out,
                  std::string& err);

// A progress line on a terminal: "  7/20 dumps, 3.1/s, ETA 0:04", rewritten in place with \r.
std::string progressText(size_t done, size_t total, double elapsedSeconds);
class Progress {
public:
    // Draws only when `out` is a terminal and there is more than one item.
    Progress(size_t total, std::FILE* out = stderr);
    ~Progress() { clear(); }
    void update(size_t done);  // redraws the line
    void clear();              // erases it (before other output to the terminal)

private:
    size_t total_;
    std::FILE* out_;
    bool on_, shown_ = false;
    double t0_;
};

struct CompareArgs {
    std::vector<std::string> files;
    RenderOptions opt;  // keepDraw applies to the rendered side and to a --ref-backend render
    std::string refDir, refBackend, jsonPath, diffDir;
    double maxMse = -1;  // < 0: none
    bool sharded = false;
    Shard shard;
    bool jsonTimes = true;
};
// `ge2gl compare`: prints the table and the summary, writes the JSON; 1 when a dump fails or
// exceeds maxMse, or on a usage or output error (one "ge2gl: " line on stderr).
int runCompare(const CompareArgs& a);
// `ge2gl merge`: reads the shard files, writes the merged JSON to `output`, prints the summary.
// 1 (one "ge2gl: " line) on unreadable files, shards from different runs, missing or duplicate shards.
int runMerge(const std::vector<std::string>& inputs, const std::string& output);

}  // namespace ge::tools
