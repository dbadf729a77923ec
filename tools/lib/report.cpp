// SPDX-License-Identifier: MIT
// `ge2gl report`: see report.h. The page is written by hand (no template engine): every text from
// a dump, a path or a state summary goes through html() first.
#include "tools/lib/report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "tools/lib/batch.h"
#include "tools/lib/blame.h"
#include "tools/lib/image.h"
#include "tools/lib/json_io.h"

namespace fs = std::filesystem;

namespace ge::tools {

bool mseChanged(double before, double after) {
    const double d = std::fabs(after - before);
    return d > 1e-4 && d > 0.01 * std::max(before, after);
}

namespace {

int fail(const std::string& msg) {
    std::fprintf(stderr, "ge2gl: %s\n", msg.c_str());
    return 1;
}

std::string html(const std::string& s) {
    std::string o;
    o.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '&': o += "&amp;"; break;
            case '<': o += "&lt;"; break;
            case '>': o += "&gt;"; break;
            case '"': o += "&quot;"; break;
            case '\'': o += "&#39;"; break;
            default: o += c;
        }
    }
    return o;
}

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// One run from its file, or from its shards' files (joined as `ge2gl merge` does).
bool loadRun(const std::vector<std::string>& files, CompareReport& out, std::string& err) {
    std::vector<CompareReport> reports;
    for (const auto& path : files) {
        std::ifstream f(path, std::ios::binary);
        if (!f) return err = "cannot read " + path + ": " + std::strerror(errno), false;
        std::stringstream ss;
        ss << f.rdbuf();
        CompareReport r;
        if (!parseCompareJson(ss.str(), r, err)) return err = path + ": " + err, false;
        reports.push_back(std::move(r));
    }
    if (reports.size() == 1 && !reports[0].sharded) {
        out = std::move(reports[0]);
        return true;
    }
    return mergeReports(reports, files, out, err);
}

// What one dump's section shows.
struct DumpPage {
    const CompareRow* row = nullptr;
    std::string error;  // the run's error, or why it could not be rendered again
    bool pictures = false;
    double reMse = -1;  // MSE of this render (the run's may come from an older build)
    BlameResult blame;
};

void renderPage(const CompareReport& run, const ReportArgs& a, const CompareRow& row, const fs::path& imgDir,
                DumpPage& page) {
    page.row = &row;
    if (!row.error.empty()) {
        page.error = row.error;
        return;
    }
    if (row.dump.empty()) {
        page.error = "the results carry no \"dump\" path (written by an older ge2gl compare): run compare again";
        return;
    }
    RenderOptions ro = a.render;
    ro.backend = run.backend;
    if (!run.accuracy.empty()) ro.accuracy = run.accuracy;  // the run's profile; --accuracy for older files
    ro.glMode = run.glMode;
    ro.scale = run.scale;
    dump::Dump d;
    std::string err;
    if (!dump::loadDump(row.dump, d, err)) {
        page.error = err;
        return;
    }
    BlameOptions bo;
    bo.top = a.top;
    if (!run.refBackend.empty()) bo.refBackend = run.refBackend;
    else bo.refPng = row.reference;
    // Blame replays at scale 1; at render scale N the pictures come from the scaled render
    // box-downsampled, as compare measured it.
    RenderOptions blameRo = ro;
    blameRo.scale = 1;
    if (!blameDump(d, blameRo, bo, page.blame, err)) {
        page.error = err;
        return;
    }
    Image frame = page.blame.frame;
    if (ro.scale > 1) {
        RenderOutput out;
        if (!renderDump(d, ro, out, err)) {
            page.error = err;
            return;
        }
        frame = out.frame;
    }
    // The part of the reference that is compared (PPSSPP's references may be 512 wide).
    Image ref;
    ref.width = 480, ref.height = 272;
    ref.rgba.assign(size_t(480) * 272, 0xFF000000u);
    for (int y = 0; y < 272 && y < page.blame.reference.height; ++y)
        for (int x = 0; x < 480 && x < page.blame.reference.width; ++x) ref.rgba[size_t(y) * 480 + x] = page.blame.reference.at(x, y);
    page.reMse = mseRGB(frame, ref);
    const std::string stem = "d" + std::to_string(row.index);
    const std::pair<const char*, Image> pics[] = {{"ref", ref},
                                                  {"render", frame},
                                                  {"heat", heatImage(frame, ref)},
                                                  {"blame", blamePicture(page.blame, a.top)}};
    for (const auto& [kind, img] : pics)
        if (!writePng((imgDir / (stem + "-" + kind + ".png")).string(), img, err)) {
            page.error = err;
            return;
        }
    page.pictures = true;
}

std::string colourHex(u32 abgr) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", abgr & 0xFF, (abgr >> 8) & 0xFF, (abgr >> 16) & 0xFF);
    return buf;
}

const char* kStyle = R"(
body { font: 14px/1.4 system-ui, sans-serif; margin: 1.5em; color: #222; background: #fff; }
h1 { font-size: 1.5em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccc; } h3 { margin-bottom: .3em; }
table { border-collapse: collapse; margin: .5em 0; }
th, td { padding: 2px 8px; border-bottom: 1px solid #e4e4e4; text-align: left; vertical-align: top; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }
table.sortable th { cursor: pointer; user-select: none; background: #f3f3f3; }
table.sortable th[aria-sort=ascending]::after { content: " \25B2"; }
table.sortable th[aria-sort=descending]::after { content: " \25BC"; }
.better { color: #11772d; } .worse { color: #b3261e; } .err { color: #b3261e; }
.pics { display: flex; flex-wrap: wrap; gap: 8px; }
figure { margin: 0; } figcaption { font-size: .85em; color: #555; }
img { image-rendering: pixelated; border: 1px solid #ccc; }
.state { font-size: .8em; color: #555; max-width: 60em; }
.legend span { display: inline-block; width: 2.2em; text-align: center; font-size: .75em; color: #000; }
.meta { color: #555; }
)";

const char* kScript = R"(
(function () {
  function key(td, type) {
    var v = td.getAttribute('data-v');
    if (type === 'num') { var n = parseFloat(v); return isNaN(n) ? Infinity : n; }
    return (v === null ? td.textContent : v).toLowerCase();
  }
  function sortBy(table, col, dir) {
    var heads = table.tHead.rows[0].cells, idx = -1, type = 'num';
    for (var i = 0; i < heads.length; i++)
      if (heads[i].getAttribute('data-col') === col) { idx = i; type = heads[i].getAttribute('data-type'); }
    if (idx < 0) return;
    var body = table.tBodies[0], rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (a, b) {
      var x = key(a.cells[idx], type), y = key(b.cells[idx], type);
      var c = x < y ? -1 : x > y ? 1 : 0;
      if (dir === 'desc') c = -c;
      return c !== 0 ? c : key(a.cells[0], 'num') - key(b.cells[0], 'num');
    });
    rows.forEach(function (r) { body.appendChild(r); });
    for (var j = 0; j < heads.length; j++) heads[j].removeAttribute('aria-sort');
    heads[idx].setAttribute('aria-sort', dir === 'desc' ? 'descending' : 'ascending');
    table.setAttribute('data-sorted', col + '-' + dir);
  }
  var tables = document.querySelectorAll('table.sortable');
  Array.prototype.forEach.call(tables, function (t) {
    Array.prototype.forEach.call(t.tHead.rows[0].cells, function (th) {
      th.addEventListener('click', function () {
        sortBy(t, th.getAttribute('data-col'), th.getAttribute('aria-sort') === 'ascending' ? 'desc' : 'asc');
      });
    });
  });
  var m = /^#sort=([a-z_]+)-(asc|desc)$/.exec(location.hash);
  if (m) Array.prototype.forEach.call(tables, function (t) { sortBy(t, m[1], m[2]); });
  window.addEventListener('load', function () {
    var n = 0, imgs = document.images;
    for (var i = 0; i < imgs.length; i++) if (imgs[i].complete && imgs[i].naturalWidth > 0) n++;
    document.body.setAttribute('data-images-loaded', n);
    document.body.setAttribute('data-images-total', imgs.length);
  });
})();
)";

struct Change {
    std::string name, verdict;  // better | worse | same | new | gone | fixed | broken | error
    double before = -1, after = -1;
};

std::vector<Change> compareRuns(const CompareReport& before, const CompareReport& after) {
    std::map<std::string, const CompareRow*> old;
    for (const CompareRow& r : before.rows) old[r.name] = &r;
    std::vector<Change> out;
    for (const CompareRow& r : after.rows) {
        Change c;
        c.name = r.name;
        c.after = r.error.empty() ? r.mse : -1;
        auto it = old.find(r.name);
        if (it == old.end()) {
            c.verdict = "new";
        } else {
            const CompareRow& o = *it->second;
            c.before = o.error.empty() ? o.mse : -1;
            if (!o.error.empty() && !r.error.empty()) c.verdict = "error";
            else if (!o.error.empty()) c.verdict = "fixed";
            else if (!r.error.empty()) c.verdict = "broken";
            else if (!mseChanged(o.mse, r.mse)) c.verdict = "same";
            else c.verdict = r.mse < o.mse ? "better" : "worse";
            old.erase(it);
        }
        out.push_back(c);
    }
    for (const auto& [name, row] : old) {
        Change c;
        c.name = name;
        c.verdict = "gone";
        c.before = row->error.empty() ? row->mse : -1;
        out.push_back(c);
    }
    return out;
}

std::string mseCell(double v) { return v < 0 ? "<td class=\"n\" data-v=\"\">–</td>" : "<td class=\"n\" data-v=\"" + numberText(v) + "\">" + fmt("%.4f", v) + "</td>"; }

void writeComparison(std::ostringstream& h, const CompareReport& before, const CompareReport& after) {
    const std::vector<Change> changes = compareRuns(before, after);
    std::map<std::string, int> count;
    for (const Change& c : changes) ++count[c.verdict];
    h << "<section id=\"comparison\"><h2>Before and after</h2>\n<p id=\"change-counts\">";
    const char* order[] = {"better", "worse", "same", "fixed", "broken", "error", "new", "gone"};
    bool first = true;
    for (const char* v : order)
        if (count[v]) {
            h << (first ? "" : ", ") << "<span class=\"" << v << "\">" << count[v] << " " << v << "</span>";
            first = false;
        }
    h << ". A dump counts as better or worse when its MSE moved by more than 0.0001 and more than 1% of the "
         "larger value.</p>\n";
    h << "<table id=\"changes\" class=\"sortable\"><thead><tr><th data-col=\"name\" data-type=\"text\">dump</th>"
         "<th class=\"n\" data-col=\"before\" data-type=\"num\">MSE before</th>"
         "<th class=\"n\" data-col=\"after\" data-type=\"num\">MSE after</th>"
         "<th class=\"n\" data-col=\"delta\" data-type=\"num\">change</th>"
         "<th data-col=\"verdict\" data-type=\"text\">verdict</th></tr></thead><tbody>\n";
    for (const Change& c : changes) {
        if (c.verdict == "same") continue;
        h << "<tr data-verdict=\"" << c.verdict << "\"><td data-v=\"" << html(c.name) << "\">" << html(c.name) << "</td>"
          << mseCell(c.before) << mseCell(c.after);
        if (c.before >= 0 && c.after >= 0)
            h << "<td class=\"n\" data-v=\"" << numberText(c.after - c.before) << "\">" << fmt("%+.4f", c.after - c.before)
              << "</td>";
        else h << "<td class=\"n\" data-v=\"\">–</td>";
        h << "<td class=\"" << c.verdict << "\">" << c.verdict << "</td></tr>\n";
    }
    h << "</tbody></table></section>\n";
}

void writeDumpSection(std::ostringstream& h, const DumpPage& p, int top) {
    const CompareRow& r = *p.row;
    const std::string id = "d" + std::to_string(r.index);
    h << "<section class=\"dump\" id=\"" << id << "\"><h3>" << r.index << ". " << html(r.name) << "</h3>\n";
    if (!r.error.empty()) {
        h << "<p class=\"err\">error: " << html(r.error) << "</p></section>\n";
        return;
    }
    h << "<p>MSE " << fmt("%.4f", r.mse) << ", PSNR " << (r.psnr >= 999 ? std::string("∞") : fmt("%.2f", r.psnr)) << " dB";
    if (r.seconds > 0) h << ", " << fmt("%.3f", r.seconds) << " s";
    if (p.pictures) {
        h << "; " << p.blame.differing << " differing pixels, " << p.blame.draws << " draws";
        if (std::fabs(p.reMse - r.mse) > 1e-9) h << " <span class=\"err\">(this render: MSE " << fmt("%.4f", p.reMse) << ")</span>";
    }
    h << "</p>\n";
    if (!p.error.empty()) {
        h << "<p class=\"err\">not shown: " << html(p.error) << "</p></section>\n";
        return;
    }
    if (!p.blame.warning.empty()) h << "<p class=\"err\">warning: " << html(p.blame.warning) << "</p>\n";
    h << "<div class=\"pics\">";
    const char* captions[][2] = {{"ref", "reference"},
                                 {"render", "render"},
                                 {"heat", "difference heat map"},
                                 {"blame", "blame: the top draws' differing pixels"}};
    for (const auto& c : captions)
        h << "<figure><img src=\"img/" << id << "-" << c[0] << ".png\" width=\"480\" height=\"272\" alt=\"" << c[1]
          << "\"><figcaption>" << c[1] << "</figcaption></figure>";
    h << "</div>\n";
    if (p.blame.owners.empty()) {
        h << "<p>No differing pixels.</p></section>\n";
        return;
    }
    h << "<table class=\"blame\"><thead><tr><th class=\"n\">rank</th><th class=\"n\">draw</th><th>what</th>"
         "<th class=\"n\">pixels</th><th class=\"n\">share</th><th class=\"n\">MSE part</th><th>bbox</th></tr></thead><tbody>\n";
    for (int i = 0; i < int(p.blame.owners.size()) && i < top; ++i) {
        const BlameOwner& o = p.blame.owners[size_t(i)];
        char bbox[64];
        std::snprintf(bbox, sizeof bbox, "(%d,%d)–(%d,%d)", o.x0, o.y0, o.x1, o.y1);
        h << "<tr><td class=\"n\">" << i + 1 << "</td><td class=\"n\">" << o.info.draw << "</td><td>"
          << html(o.info.draw ? drawDescription(o.info) : "not a draw (initial VRAM, transfers, CPU copies)");
        if (o.info.draw) h << "<div class=\"state\">" << html(o.info.state) << "</div>";
        h << "</td><td class=\"n\">" << o.pixels << "</td><td class=\"n\">" << fmt("%.1f%%", 100 * o.share)
          << "</td><td class=\"n\">" << fmt("%.4f", o.mse) << "</td><td>" << bbox << "</td></tr>\n";
    }
    if (p.blame.owners.size() > size_t(top))
        h << "<tr><td colspan=\"7\">… and " << p.blame.owners.size() - size_t(top) << " more draws</td></tr>\n";
    h << "</tbody></table></section>\n";
}

u64 folderBytes(const fs::path& dir) {
    u64 n = 0;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
        if (it->is_regular_file(ec)) n += it->file_size(ec);
    return n;
}

}  // namespace

int runReport(const ReportArgs& a) {
    const auto t0 = std::chrono::steady_clock::now();
    CompareReport run, before;
    std::string err;
    if (!loadRun(a.runFiles, run, err)) return fail(err);
    const bool withBefore = !a.beforeFiles.empty();
    if (withBefore && !loadRun(a.beforeFiles, before, err)) return fail("--before: " + err);
    const fs::path dir = a.outDir, imgDir = dir / "img";
    std::error_code ec;
    fs::create_directories(imgDir, ec);
    if (ec) return fail("cannot create " + imgDir.string() + ": " + ec.message());

    std::vector<DumpPage> pages(run.rows.size());
    Progress progress(run.rows.size());
    progress.update(0);
    for (size_t i = 0; i < run.rows.size(); ++i) {
        renderPage(run, a, run.rows[i], imgDir, pages[i]);
        progress.update(i + 1);
    }
    progress.clear();

    const CompareSummary s = summarize(run.rows);
    std::string how = run.backend;
    if (run.backend == "gl") how += " (" + run.glMode + (run.scale > 1 ? ", scale " + std::to_string(run.scale) : "") + ")";
    if (!run.accuracy.empty()) how += ", accuracy " + run.accuracy;
    how += run.refBackend.empty() ? " against reference pictures" : " against the " + run.refBackend + " backend";
    const std::string title = a.title.empty() ? "ge2gl report: " + how : a.title;

    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << html(title) << "</title>\n<style>"
      << kStyle << "</style></head>\n<body data-images-loaded=\"0\" data-images-total=\"0\">\n<h1>" << html(title) << "</h1>\n";
    h << "<p class=\"meta\">" << html(how) << "; written by ge2gl report from " << html(a.runFiles.front())
      << (a.runFiles.size() > 1 ? " and " + std::to_string(a.runFiles.size() - 1) + " more shard files" : "") << "</p>\n";
    h << "<table id=\"summary\"><tbody>\n<tr><th>dumps</th><td class=\"n\">" << s.dumps << "</td></tr>\n<tr><th>rendered</th><td class=\"n\">"
      << s.rendered << "</td></tr>\n<tr><th>errors</th><td class=\"n\">" << s.dumps - s.rendered
      << "</td></tr>\n<tr><th>within MSE 0.1</th><td class=\"n\">" << s.within01 << "</td></tr>\n<tr><th>within MSE 10</th><td class=\"n\">"
      << s.within10 << "</td></tr>\n<tr><th>median MSE</th><td class=\"n\">" << fmt("%.4f", s.medianMse) << "</td></tr>\n";
    if (run.times) h << "<tr><th>median time</th><td class=\"n\">" << fmt("%.3f", s.medianSeconds) << " s</td></tr>\n";
    h << "</tbody></table>\n";
    if (withBefore) writeComparison(h, before, run);

    std::map<std::string, const CompareRow*> old;
    if (withBefore)
        for (const CompareRow& r : before.rows) old[r.name] = &r;
    h << "<h2>Dumps</h2>\n<p>Click a heading to sort; a dump's name leads to its pictures and blame table.</p>\n";
    h << "<table id=\"dumps\" class=\"sortable\"><thead><tr><th class=\"n\" data-col=\"index\" data-type=\"num\">#</th>"
         "<th data-col=\"name\" data-type=\"text\">dump</th><th class=\"n\" data-col=\"mse\" data-type=\"num\">MSE</th>"
         "<th class=\"n\" data-col=\"psnr\" data-type=\"num\">PSNR</th>";
    if (run.times) h << "<th class=\"n\" data-col=\"time\" data-type=\"num\">time s</th>";
    if (withBefore)
        h << "<th class=\"n\" data-col=\"before\" data-type=\"num\">MSE before</th><th class=\"n\" data-col=\"delta\" "
             "data-type=\"num\">change</th>";
    h << "<th class=\"n\" data-col=\"pixels\" data-type=\"num\">differing pixels</th>"
         "<th data-col=\"top\" data-type=\"text\">largest owner</th></tr></thead><tbody>\n";
    for (const DumpPage& p : pages) {
        const CompareRow& r = *p.row;
        const bool ok = r.error.empty();
        h << "<tr data-index=\"" << r.index << "\"><td class=\"n\" data-v=\"" << r.index << "\">" << r.index << "</td><td data-v=\""
          << html(r.name) << "\"><a href=\"#d" << r.index << "\">" << html(r.name) << "</a></td>";
        if (ok)
            h << mseCell(r.mse) << "<td class=\"n\" data-v=\"" << numberText(r.psnr) << "\">"
              << (r.psnr >= 999 ? std::string("∞") : fmt("%.2f", r.psnr)) << "</td>";
        else h << "<td class=\"n err\" data-v=\"\">error</td><td class=\"n\" data-v=\"\">–</td>";
        if (run.times)
            h << (ok ? "<td class=\"n\" data-v=\"" + numberText(r.seconds) + "\">" + fmt("%.3f", r.seconds) + "</td>"
                     : std::string("<td class=\"n\" data-v=\"\">–</td>"));
        if (withBefore) {
            auto it = old.find(r.name);
            const double b = it != old.end() && it->second->error.empty() ? it->second->mse : -1;
            h << mseCell(b);
            if (b >= 0 && ok) {
                const char* cls = !mseChanged(b, r.mse) ? "" : r.mse < b ? " better" : " worse";
                h << "<td class=\"n" << cls << "\" data-v=\"" << numberText(r.mse - b) << "\">" << fmt("%+.4f", r.mse - b) << "</td>";
            } else {
                h << "<td class=\"n\" data-v=\"\">–</td>";
            }
        }
        if (p.pictures) {
            h << "<td class=\"n\" data-v=\"" << p.blame.differing << "\">" << p.blame.differing << "</td><td>";
            if (!p.blame.owners.empty()) {
                const BlameOwner& o = p.blame.owners[0];
                h << (o.info.draw ? "draw " + std::to_string(o.info.draw) : std::string("not a draw")) << " ("
                  << fmt("%.0f%%", 100 * o.share) << ")";
            }
            h << "</td>";
        } else {
            h << "<td class=\"n\" data-v=\"\">–</td><td class=\"err\">" << html(p.error) << "</td>";
        }
        h << "</tr>\n";
    }
    h << "</tbody></table>\n";

    h << "<h2>Pictures and blame</h2>\n<p class=\"legend\">Heat map: unchanged pixels dimmed grey; a differing pixel "
         "coloured by its largest channel difference: ";
    for (int d : {1, 2, 4, 8, 16, 32, 64, 128, 255})
        h << "<span style=\"background:" << colourHex(heatColour(d)) << "\">" << d << "</span>";
    h << ". Blame: the render dimmed, each of the top " << a.top
      << " draws' differing pixels in its own colour with its bounding box, other differing pixels white.</p>\n";
    for (const DumpPage& p : pages) writeDumpSection(h, p, a.top);
    h << "<script>" << kScript << "</script>\n</body></html>\n";

    const fs::path index = dir / "index.html";
    {
        std::ofstream f(index, std::ios::binary | std::ios::trunc);
        const std::string text = h.str();
        f.write(text.data(), std::streamsize(text.size()));
        f.flush();
        if (!f) return fail("cannot write " + index.string() + ": " + std::strerror(errno));
    }
    size_t shown = 0;
    for (const DumpPage& p : pages) shown += p.pictures;
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("report: %s — %zu dumps, %zu with pictures; %.1f KiB in %s; generated in %.2f s\n", index.string().c_str(),
                pages.size(), shown, double(folderBytes(dir)) / 1024.0, dir.string().c_str(), secs);
    for (const DumpPage& p : pages)
        if (!p.error.empty() && p.row->error.empty())
            std::fprintf(stderr, "ge2gl: warning: %s: %s\n", p.row->name.c_str(), p.error.c_str());
    return 0;
}

}  // namespace ge::tools
