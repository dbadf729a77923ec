// SPDX-License-Identifier: MIT
// The JSON files of the tools (compare, merge, report, blame, bisect, fuzz), read and written with
// nlohmann::json.
//
// Writing keeps the layout these files have always had: one top-level member per line, small
// objects and arrays on one line with ", " and ": " between items, arrays of rows one row per line.
// nlohmann's own pretty printer puts every value on a line of its own, which would change every
// file the tools write and the bytes `ge2gl merge` must reproduce (batch.h). Every key, string and
// number in the text is nlohmann's dump() of it; json_io.cpp only decides where lines break.
//
// Numbers: nlohmann writes a double with digits that read back as the same double (Grisu2: the
// shortest such digits for all but about one double in a thousand, which get 17 digits), a whole
// double as "999.0", and an exponent only below 1e-4 or from 1e15 on. numberValue() stores whole
// doubles as integers, so 999 stays "999"; everything else keeps its value.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace ge::tools {

// Objects keep their members in the order they were set: the order the files are written in.
using Json = nlohmann::ordered_json;

// A double as the tools write it: a whole value (below 2^53) as an integer ("999", not "999.0"),
// infinity as 999 and minus infinity as -999 (the PSNR of identical pictures), NaN as null, the
// rest as the double itself.
Json numberValue(double v);
// The same after rounding v to 6 significant digits as C's %g does: what blame, bisect and fuzz
// have always written for their measurements (and what their tests and users read).
Json number6Value(double v);

// One value on one line: {"a": 1, "b": [2, "x"]}. Strings that are not UTF-8 (a file name in
// another encoding) have the bad bytes replaced by U+FFFD rather than failing the write.
std::string jsonOneLine(const Json& v);
// The text of a number as numberValue() writes it (report's sort keys: the same digits as the JSON).
std::string numberText(double v);

struct JsonLayout {
    // Top-level arrays written one element per line: "[\n    {...},\n    {...}\n  ]"; an empty one
    // as "[]". Other arrays and objects go on one line.
    std::vector<std::string> rowArrays;
    // Row arrays that keep two lines when empty ("[\n  ]"): compare's "results".
    std::vector<std::string> emptyRowsOnTwoLines;
    // Members that share the line of the member before them: compare's "scale" after "gl_mode".
    std::vector<std::string> sameLine;
};
// A top-level object: "{\n  \"key\": value,\n  ...\n}\n" laid out as `layout` says.
std::string jsonDocument(const Json& doc, const JsonLayout& layout = {});

// Parses a whole JSON text. On failure `err` is nlohmann's description with the line and column.
bool parseJson(const std::string& text, Json& out, std::string& err);

}  // namespace ge::tools
