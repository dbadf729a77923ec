// SPDX-License-Identifier: MIT
#include "tools/lib/json_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace ge::tools {

namespace {

// Non-UTF-8 bytes become U+FFFD: a file name in another encoding must not make the whole write
// throw (nlohmann's default), and what is written stays valid JSON that reads back.
std::string dumpScalar(const Json& v) { return v.dump(-1, ' ', false, Json::error_handler_t::replace); }

bool listed(const std::vector<std::string>& keys, const std::string& key) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

}  // namespace

Json numberValue(double v) {
    if (std::isnan(v)) return nullptr;
    if (std::isinf(v)) return v > 0 ? 999 : -999;
    // Below 2^53 every whole double is exactly an int64_t.
    if (v == std::trunc(v) && std::fabs(v) < 9007199254740992.0) return std::int64_t(v);
    return v;
}

Json number6Value(double v) {
    if (!std::isfinite(v)) return numberValue(v);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return numberValue(std::strtod(buf, nullptr));
}

std::string jsonOneLine(const Json& v) {
    std::string out;
    if (v.is_object()) {
        out = "{";
        for (auto it = v.begin(); it != v.end(); ++it)
            out += (it == v.begin() ? "" : ", ") + dumpScalar(Json(it.key())) + ": " + jsonOneLine(it.value());
        return out + "}";
    }
    if (v.is_array()) {
        out = "[";
        for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + jsonOneLine(v[i]);
        return out + "]";
    }
    return dumpScalar(v);
}

std::string numberText(double v) { return jsonOneLine(numberValue(v)); }

std::string jsonDocument(const Json& doc, const JsonLayout& layout) {
    std::string out = "{";
    bool first = true;
    for (auto it = doc.begin(); it != doc.end(); ++it) {
        const std::string& key = it.key();
        const Json& value = it.value();
        out += first ? "\n  " : listed(layout.sameLine, key) ? ", " : ",\n  ";
        first = false;
        out += dumpScalar(Json(key)) + ": ";
        const bool rows = value.is_array() && listed(layout.rowArrays, key) &&
                          (!value.empty() || listed(layout.emptyRowsOnTwoLines, key));
        if (!rows) {
            out += jsonOneLine(value);
            continue;
        }
        out += "[";
        for (size_t i = 0; i < value.size(); ++i) out += (i ? ",\n    " : "\n    ") + jsonOneLine(value[i]);
        out += "\n  ]";
    }
    return out + (first ? "}\n" : "\n}\n");
}

bool parseJson(const std::string& text, Json& out, std::string& err) {
    try {
        out = Json::parse(text);
        return true;
    } catch (const Json::parse_error& e) {
        // "[json.exception.parse_error.101] parse error at line 1, column 9: ..." less the tag.
        const std::string what = e.what();
        const size_t tag = what.find("] ");
        err = tag == std::string::npos ? what : what.substr(tag + 2);
        return false;
    }
}

}  // namespace ge::tools
