// SPDX-License-Identifier: MIT
// Draw selection for `render`, `compare` and `bench` --skip / --only: comma-separated draw numbers
// and ranges ("3,10-12"), draws numbered from 1 as --replay-end counts them (tools/lib/draw_hook.h).
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hle/types.h"

namespace ge::tools {

// A set of draw numbers as sorted, merged, inclusive ranges.
class DrawSet {
public:
    bool contains(u64 draw) const;
    bool empty() const { return ranges_.empty(); }
    const std::vector<std::pair<u64, u64>>& ranges() const { return ranges_; }
    std::string text() const;  // canonical form: "3,10-12"
    void add(u64 first, u64 last);

private:
    std::vector<std::pair<u64, u64>> ranges_;
};

// Parses "N", "A-B" items separated by commas. Numbers are decimal digits only, from 1 to 2^40
// (the --replay-end limit), A <= B; no empty items, signs or spaces. On failure `err` says which
// item is wrong and why (without the option name).
bool parseDrawList(const std::string& text, DrawSet& out, std::string& err);

// The RenderOptions::keepDraw predicate for --skip SKIP and --only ONLY (nullopt = not given): a
// draw is kept when it is in ONLY (or ONLY is not given) and not in SKIP. Sets an empty function
// when neither is given (every draw kept, no hook). On a parse error returns false and sets `err`
// to a whole message naming the option ("--skip '3,x': ...").
bool makeDrawFilter(const std::optional<std::string>& skip, const std::optional<std::string>& only,
                    std::function<bool(u64)>& keep, std::string& err);

}  // namespace ge::tools
