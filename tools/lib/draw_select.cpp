// SPDX-License-Identifier: MIT
#include "tools/lib/draw_select.h"

#include <algorithm>
#include <memory>

namespace ge::tools {

namespace {

constexpr u64 kMaxDraw = u64(1) << 40;

// Decimal digits only, 1..kMaxDraw.
bool parseNumber(const std::string& s, u64& v) {
    if (s.empty() || s.size() > 13 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    v = std::stoull(s);
    return v >= 1 && v <= kMaxDraw;
}

}  // namespace

bool DrawSet::contains(u64 draw) const {
    auto it = std::upper_bound(ranges_.begin(), ranges_.end(), draw,
                               [](u64 d, const std::pair<u64, u64>& r) { return d < r.first; });
    return it != ranges_.begin() && draw <= std::prev(it)->second;
}

void DrawSet::add(u64 first, u64 last) {
    ranges_.emplace_back(first, last);
    std::sort(ranges_.begin(), ranges_.end());
    std::vector<std::pair<u64, u64>> merged;
    for (const auto& r : ranges_) {
        if (!merged.empty() && r.first <= merged.back().second + 1) merged.back().second = std::max(merged.back().second, r.second);
        else merged.push_back(r);
    }
    ranges_ = std::move(merged);
}

std::string DrawSet::text() const {
    std::string s;
    for (const auto& [a, b] : ranges_) {
        if (!s.empty()) s += ',';
        s += std::to_string(a);
        if (b != a) s += '-' + std::to_string(b);
    }
    return s;
}

bool parseDrawList(const std::string& text, DrawSet& out, std::string& err) {
    out = DrawSet();
    if (text.empty()) {
        err = "empty list (give draw numbers and ranges such as 3,10-12)";
        return false;
    }
    size_t pos = 0;
    while (true) {
        const size_t comma = text.find(',', pos);
        const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
        const std::string why = " (items are N or A-B, draws numbered from 1 to " + std::to_string(kMaxDraw) + ")";
        if (item.empty()) {
            err = "empty item" + why;
            return false;
        }
        const size_t dash = item.find('-');
        u64 a = 0, b = 0;
        if (dash == std::string::npos) {
            if (!parseNumber(item, a)) {
                err = "'" + item + "' is not a draw number" + why;
                return false;
            }
            b = a;
        } else {
            if (!parseNumber(item.substr(0, dash), a) || !parseNumber(item.substr(dash + 1), b)) {
                err = "'" + item + "' is not a draw range" + why;
                return false;
            }
            if (b < a) {
                err = "range '" + item + "' ends before it starts";
                return false;
            }
        }
        out.add(a, b);
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    return true;
}

bool makeDrawFilter(const std::optional<std::string>& skip, const std::optional<std::string>& only,
                    std::function<bool(u64)>& keep, std::string& err) {
    keep = nullptr;
    if (!skip && !only) return true;
    auto skipSet = std::make_shared<DrawSet>(), onlySet = std::make_shared<DrawSet>();
    std::string why;
    if (skip && !parseDrawList(*skip, *skipSet, why)) {
        err = "--skip '" + *skip + "': " + why;
        return false;
    }
    if (only && !parseDrawList(*only, *onlySet, why)) {
        err = "--only '" + *only + "': " + why;
        return false;
    }
    const bool haveOnly = only.has_value();
    keep = [skipSet, onlySet, haveOnly](u64 draw) {
        return (!haveOnly || onlySet->contains(draw)) && !skipSet->contains(draw);
    };
    return true;
}

}  // namespace ge::tools
