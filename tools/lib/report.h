// SPDX-License-Identifier: MIT
// `ge2gl report`: a static HTML page of a `ge2gl compare --json` run (accuracy tools).
//
// Input: the JSON of one compare run, or the --json files of its shards (joined as `ge2gl merge`
// joins them); optionally a second run (--before) to compare with. Each dump of the run is rendered
// again the way the run rendered it (the JSON's "dump", "backend", "gl_mode", "scale" and
// "reference" or "ref_backend": tools/lib/batch.h) and blamed against its reference
// (tools/lib/blame.h), so the page shows what the run measured, with the run's MSE, PSNR and time.
//
// Output, all inside DIR (no server, no network: a folder that opens from disk or a CI artifact):
//   DIR/index.html   summary (counts, medians), the table of dumps sortable by any column (a click
//                    on its heading; `#sort=COLUMN-asc|desc` in the address sorts on load), the
//                    before/after comparison with --before, then per dump: reference, render,
//                    heat map (image.h heatImage, with its legend) and the blame picture, and the
//                    blame table (the top draws owning the differing pixels, their share of the
//                    squared error, bounding box, description and state summary);
//   DIR/img/dN-{ref,render,heat,blame}.png   N: the dump's index in the run (names may hold any
//                    character; the index is unique within a run).
// The page needs no script to be read; the script only sorts and marks, once the images have
// loaded, <body data-images-loaded="N" data-images-total="M"> (what the browser test checks).
//
// Before/after: dumps are matched by name. A dump counts as changed when its MSE moved by more
// than 1e-4 and by more than 1% of the larger of the two values (renders that differ by a few
// pixels in one run and not the other are not noise: any move past those bounds is listed).
#pragma once
#include <string>
#include <vector>

#include "tools/lib/render.h"

namespace ge::tools {

struct ReportArgs {
    std::vector<std::string> runFiles;     // one run, or its shards
    std::vector<std::string> beforeFiles;  // --before: the run to compare with (or its shards); may be empty
    std::string outDir;                    // -o
    std::string title;                     // --title; default: "ge2gl report: BACKEND"
    int top = 10;                          // blame rows per dump
    RenderOptions render;                  // threads, context, replay timing; backend/gl mode/scale come from the run
};

// MSE moved past the bounds above.
bool mseChanged(double before, double after);

// The whole subcommand: writes DIR, prints the page's size and the generation time. 0 on
// success; 1 (one "ge2gl: " line) when the JSON cannot be read or DIR cannot be written. A dump
// that cannot be rendered again is shown on the page with its error, not a failure of the command.
int runReport(const ReportArgs& a);

}  // namespace ge::tools
