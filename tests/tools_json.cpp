// SPDX-License-Identifier: MIT
// The tools' JSON (tools/lib/json_io.h): numbers, strings and the layout the files are written in,
// and `ge2gl merge` of two hand-written shard files compared byte for byte with the file it must
// write (the same bytes ge2gl wrote before its JSON went through nlohmann::json).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "tools/lib/batch.h"
#include "tools/lib/json_io.h"
#include "tests/tools_cli_run.h"

using namespace ge;
using tools::Json;
namespace fs = std::filesystem;

namespace {

std::string readText(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream f(p, std::ios::binary);
    f << text;
}

// Shard 1 of 2 of a five-dump gl run: escaped quotes and backslashes, \u escapes, an error row,
// a number with a trailing zero and one with an exponent.
const char* const kShard1 =
    R"({"backend": "gl", "gl_mode": "hw", "scale": 2, "ref_backend": "soft",
 "shard": {"index": 1, "count": 2, "dumps": 5},
 "results": [
  {"index": 1, "name": "a \"quoted\" name", "dump": "d/a.ppdmp", "mse": 0.1, "psnr": 58.13080360867910, "seconds": 0.25},
  {"index": 3, "name": "caf\u00e9 \u65e5\u672c", "dump": "d\\c.zip", "error": "cannot read d\\c.zip: No such file"},
  {"index": 5, "name": "e", "dump": "d/e.ppdmp", "mse": 65025, "psnr": 0, "seconds": 1.5e-05}
 ],
 "median_mse": 1, "median_seconds": 1, "within_0_1": 0, "within_10": 0}
)";
// Shard 2: members in another order, an index written as 4.0; its summary is recomputed anyway.
const char* const kShard2 =
    R"({"results": [{"psnr": 999, "mse": 0, "seconds": 0.3333333333333333, "dump": "d/b.ppdmp", "name": "b", "index": 2},
             {"index": 4.0, "name": "d", "dump": "d/d.ppdmp", "mse": 0.057426981209150324, "psnr": 60.53, "seconds": 12.5}],
 "shard": {"dumps": 5, "count": 2, "index": 2}, "ref_backend": "soft", "scale": 2, "gl_mode": "hw", "backend": "gl",
 "median_mse": 0, "median_seconds": 0, "within_0_1": 2, "within_10": 2}
)";
// What `ge2gl merge` writes for them.
const std::string kMerged =
    "{\n"
    "  \"backend\": \"gl\",\n"
    "  \"gl_mode\": \"hw\", \"scale\": 2,\n"
    "  \"ref_backend\": \"soft\",\n"
    "  \"results\": [\n"
    "    {\"index\": 1, \"name\": \"a \\\"quoted\\\" name\", \"dump\": \"d/a.ppdmp\", \"mse\": 0.1, \"psnr\": "
    "58.1308036086791, \"seconds\": 0.25},\n"
    "    {\"index\": 2, \"name\": \"b\", \"dump\": \"d/b.ppdmp\", \"mse\": 0, \"psnr\": 999, \"seconds\": "
    "0.3333333333333333},\n"
    "    {\"index\": 3, \"name\": \"caf\xc3\xa9 \xe6\x97\xa5\xe6\x9c\xac\", \"dump\": \"d\\\\c.zip\", \"error\": "
    "\"cannot read d\\\\c.zip: No such file\"},\n"
    "    {\"index\": 4, \"name\": \"d\", \"dump\": \"d/d.ppdmp\", \"mse\": 0.057426981209150324, \"psnr\": 60.53, "
    "\"seconds\": 12.5},\n"
    "    {\"index\": 5, \"name\": \"e\", \"dump\": \"d/e.ppdmp\", \"mse\": 65025, \"psnr\": 0, \"seconds\": 1.5e-05}\n"
    "  ],\n"
    "  \"median_mse\": 0.07871349060457516,\n"
    "  \"median_seconds\": 0.29166666666666663,\n"
    "  \"within_0_1\": 3,\n"
    "  \"within_10\": 3\n"
    "}\n";

}  // namespace

TEST(Json, NumbersKeepTheirFormAndValue) {
    EXPECT_EQ(tools::numberText(0.1), "0.1");
    EXPECT_EQ(tools::numberText(999.0), "999");  // not nlohmann's "999.0"
    EXPECT_EQ(tools::numberText(0.0), "0");
    EXPECT_EQ(tools::numberText(65025.0), "65025");
    EXPECT_EQ(tools::numberText(-3.0), "-3");
    EXPECT_EQ(tools::numberText(1.5e-5), "1.5e-05");
    EXPECT_EQ(tools::numberText(0.00012), "0.00012");
    EXPECT_EQ(tools::numberText(1.0 / 3), "0.3333333333333333");
    EXPECT_EQ(tools::numberText(std::numeric_limits<double>::infinity()), "999");  // PSNR of identical pictures
    EXPECT_EQ(tools::numberText(-std::numeric_limits<double>::infinity()), "-999");
    EXPECT_EQ(tools::numberText(std::nan("")), "null");
    EXPECT_TRUE(tools::numberValue(999.0).is_number_integer());
    EXPECT_TRUE(tools::numberValue(0.5).is_number_float());
    // Every value reads back as the same double, whatever digits nlohmann chose.
    for (double v : {0.1, 1.0 / 3, 1.5e-5, 0.057426981209150324, 4.349126838235295, 2.202882187327315, 1e300,
                     -2.5e-300, 123456789.125, 9007199254740993.0, 1e22}) {
        const std::string s = tools::numberText(v);
        EXPECT_EQ(std::stod(s), v) << s;
        Json back;
        std::string err;
        ASSERT_TRUE(tools::parseJson(s, back, err)) << err;
        EXPECT_EQ(back.get<double>(), v) << s;
    }
    // Six significant digits, as C's %g: blame, bisect and fuzz.
    EXPECT_EQ(tools::jsonOneLine(tools::number6Value(0.01064389297385621)), "0.0106439");
    EXPECT_EQ(tools::jsonOneLine(tools::number6Value(8.169934640522876e-05)), "8.16993e-05");
    EXPECT_EQ(tools::jsonOneLine(tools::number6Value(0.50251889168765743)), "0.502519");
    EXPECT_EQ(tools::jsonOneLine(tools::number6Value(4.0)), "4");
    EXPECT_EQ(tools::jsonOneLine(tools::number6Value(1.92754321)), "1.92754");
    EXPECT_EQ(tools::jsonOneLine(tools::number6Value(12345.678)), "12345.7");
}

TEST(Json, StringsAreEscapedAndReadBack) {
    EXPECT_EQ(tools::jsonOneLine(Json("a\"b\\c\nd/e")), "\"a\\\"b\\\\c\\nd/e\"");
    EXPECT_EQ(tools::jsonOneLine(Json(std::string("x\x01y", 3))), "\"x\\u0001y\"");
    EXPECT_EQ(tools::jsonOneLine(Json("caf\xc3\xa9")), "\"caf\xc3\xa9\"");  // UTF-8 as it is
    // A byte that is not UTF-8 (a Latin-1 file name) becomes U+FFFD instead of failing the write.
    EXPECT_EQ(tools::jsonOneLine(Json("caf\xe9.zip")), "\"caf\xef\xbf\xbd.zip\"");
    const std::string tricky = "tab\there \"q\" back\\slash \x7f end";
    Json back;
    std::string err;
    ASSERT_TRUE(tools::parseJson(tools::jsonOneLine(Json(tricky)), back, err)) << err;
    EXPECT_EQ(back.get<std::string>(), tricky);
}

TEST(Json, DocumentLayout) {
    Json j;
    j["name"] = "x";
    j["mode"] = "hw";
    j["scale"] = 2;
    j["box"] = {1, 2, -3, 4};
    j["inner"]["a"] = 1;
    j["inner"]["b"] = Json::array({"s", 2.5});
    j["rows"] = Json::array();
    j["rows"].push_back(Json{{"k", 1}});
    j["rows"].push_back(Json{{"k", 2}, {"v", nullptr}});
    j["none"] = Json::array();
    j["kept"] = Json::array();
    j["flag"] = false;
    tools::JsonLayout layout;
    layout.rowArrays = {"rows", "none", "kept"};
    layout.emptyRowsOnTwoLines = {"kept"};
    layout.sameLine = {"scale"};
    EXPECT_EQ(tools::jsonDocument(j, layout),
              "{\n"
              "  \"name\": \"x\",\n"
              "  \"mode\": \"hw\", \"scale\": 2,\n"
              "  \"box\": [1, 2, -3, 4],\n"
              "  \"inner\": {\"a\": 1, \"b\": [\"s\", 2.5]},\n"
              "  \"rows\": [\n"
              "    {\"k\": 1},\n"
              "    {\"k\": 2, \"v\": null}\n"
              "  ],\n"
              "  \"none\": [],\n"
              "  \"kept\": [\n"
              "  ],\n"
              "  \"flag\": false\n"
              "}\n");
    // Without a layout every member is on one line.
    EXPECT_EQ(tools::jsonDocument(Json{{"rows", {Json{{"k", 1}}}}}), "{\n  \"rows\": [{\"k\": 1}]\n}\n");
    EXPECT_EQ(tools::jsonDocument(Json::object()), "{}\n");
}

TEST(Json, ParseErrorsSayWhere) {
    Json j;
    std::string err;
    EXPECT_FALSE(tools::parseJson("{\"backend\": \"soft\",\n \"results\": [}", j, err));
    EXPECT_NE(err.find("line 2, column"), std::string::npos) << err;
    EXPECT_EQ(err.find("[json.exception"), std::string::npos) << err;
    for (const char* bad : {"", "{", "[1,]", "{\"a\": 01}", "{\"a\": 1} x", "{'a': 1}", "{\"a\": \"\\x\"}", "nan"}) {
        err.clear();
        EXPECT_FALSE(tools::parseJson(bad, j, err)) << bad;
        EXPECT_FALSE(err.empty()) << bad;
    }
    // Deep nesting is an error-free parse, not a stack overflow (nlohmann's parser is iterative).
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_TRUE(tools::parseJson(deep, j, err)) << err;
}

TEST(Json, CompareFilesAreCheckedMemberByMember) {
    tools::CompareReport r;
    std::string err;
    auto refused = [&](const std::string& text, const std::string& why) {
        err.clear();
        EXPECT_FALSE(tools::parseCompareJson(text, r, err)) << text;
        EXPECT_NE(err.find(why), std::string::npos) << text << ": " << err;
    };
    refused("[1]", "not a JSON object");
    refused("{\"backend\": 3, \"results\": []}", "no \"backend\" string");
    refused("{\"backend\": \"soft\"}", "no \"results\" array");
    refused("{\"backend\": \"soft\", \"results\": [{\"index\": -1, \"name\": \"a\", \"mse\": 0, \"psnr\": 0}]}", "no \"index\"");
    refused("{\"backend\": \"soft\", \"results\": [{\"index\": 1.5, \"name\": \"a\", \"mse\": 0, \"psnr\": 0}]}", "no \"index\"");
    refused("{\"backend\": \"soft\", \"results\": [{\"index\": 1, \"name\": \"a\", \"mse\": \"0\", \"psnr\": 0}]}",
            "needs \"mse\" and \"psnr\" numbers");
    refused("{\"backend\": \"soft\", \"results\": [{\"index\": 1, \"name\": \"a\", \"mse\": 0, \"psnr\": 0, \"seconds\": 1}]}",
            "\"seconds\" although the file has no \"median_seconds\"");
    refused("{\"backend\": \"gl\", \"scale\": 9, \"results\": []}", "\"scale\" is not a whole number from 1 to 8");
    refused("{\"backend\": \"soft\", \"shard\": {\"index\": 3, \"count\": 2, \"dumps\": 4}, \"results\": []}",
            "bad \"shard\" object");
    refused("{\"backend\": \"soft\", \"results\": [", "parse error at line 1");
    // An empty error keeps the row an error row.
    ASSERT_TRUE(tools::parseCompareJson("{\"backend\": \"soft\", \"results\": [{\"index\": 1, \"name\": \"a\", \"error\": \"\"}]}", r,
                                        err))
        << err;
    ASSERT_EQ(r.rows.size(), 1u);
    EXPECT_EQ(r.rows[0].error, "(empty error)");
    EXPECT_EQ(r.dumps, 1u);
    EXPECT_FALSE(r.sharded);
}

// Two shard files merged by the library and by `ge2gl merge`: exactly kMerged.
TEST(Json, MergeOfShardFilesGivesTheseBytes) {
    std::vector<tools::CompareReport> shards(2);
    std::string err;
    ASSERT_TRUE(tools::parseCompareJson(kShard2, shards[0], err)) << err;
    ASSERT_TRUE(tools::parseCompareJson(kShard1, shards[1], err)) << err;
    EXPECT_EQ(shards[1].rows[1].name, "caf\xc3\xa9 \xe6\x97\xa5\xe6\x9c\xac");
    EXPECT_EQ(shards[1].rows[1].error, "cannot read d\\c.zip: No such file");
    EXPECT_EQ(shards[0].rows[1].index, 4u);
    tools::CompareReport merged;
    ASSERT_TRUE(tools::mergeReports(shards, {"s2.json", "s1.json"}, merged, err)) << err;
    EXPECT_EQ(tools::compareJson(merged), kMerged);
    // What merge writes reads back to the same report and writes the same bytes again.
    tools::CompareReport again;
    ASSERT_TRUE(tools::parseCompareJson(kMerged, again, err)) << err;
    EXPECT_EQ(tools::compareJson(again), kMerged);

    const fs::path t = fs::temp_directory_path() / ("ge2gl_json_merge_" + std::to_string(::getpid()));
    fs::remove_all(t);
    fs::create_directories(t);
    writeText(t / "s1.json", kShard1);
    writeText(t / "s2.json", kShard2);
    const auto r = clitest::runCli("merge " + clitest::quote((t / "s2.json").string()) + " " +
                                   clitest::quote((t / "s1.json").string()) + " -o " + clitest::quote((t / "m.json").string()));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out, "summary: 5 dumps, 4 rendered, 3 within MSE 0.1, 3 within MSE 10, median MSE 0.0787, median time 0.292 s\n");
    EXPECT_EQ(readText(t / "m.json"), kMerged);
    // A file that is not JSON: one line naming the file and where the text goes wrong.
    writeText(t / "bad.json", "{\"backend\": \"gl\",\n\"results\": [}\n");
    const auto bad = clitest::runCli("merge " + clitest::quote((t / "bad.json").string()) + " -o " +
                                     clitest::quote((t / "x.json").string()));
    EXPECT_EQ(bad.code, 1) << bad.out;
    EXPECT_EQ(bad.out.rfind("ge2gl: " + (t / "bad.json").string() + ": parse error at line 2, column 13", 0), 0u) << bad.out;
    EXPECT_FALSE(fs::exists(t / "x.json"));
    fs::remove_all(t);
}

// compare's --accuracy is recorded as "accuracy" (after "backend"), read back, and carried by
// merge; shards of different profiles are not one run. Files written before the profiles have
// no "accuracy" and read back with an empty one.
TEST(Json, CompareRecordsTheAccuracyProfile) {
    tools::CompareReport r;
    r.backend = "soft";
    r.accuracy = "ppsspp";
    tools::CompareRow row;
    row.index = 1, row.name = "a", row.mse = 0, row.psnr = 0;
    r.rows.push_back(row);
    r.times = false;
    const std::string text = tools::compareJson(r);
    EXPECT_NE(text.find("\"backend\": \"soft\",\n  \"accuracy\": \"ppsspp\""), std::string::npos) << text;
    tools::CompareReport back;
    std::string err;
    ASSERT_TRUE(tools::parseCompareJson(text, back, err)) << err;
    EXPECT_EQ(back.accuracy, "ppsspp");
    EXPECT_EQ(tools::compareJson(back), text);
    ASSERT_TRUE(tools::parseCompareJson("{\"backend\": \"soft\", \"results\": []}", back, err)) << err;
    EXPECT_EQ(back.accuracy, "");
    EXPECT_FALSE(tools::parseCompareJson("{\"backend\": \"soft\", \"accuracy\": 1, \"results\": []}", back, err));
    EXPECT_NE(err.find("\"accuracy\" is not a string"), std::string::npos) << err;

    std::vector<tools::CompareReport> shards(2, r);
    for (int i = 0; i < 2; ++i) {
        shards[size_t(i)].sharded = true;
        shards[size_t(i)].shard.index = u64(i + 1);
        shards[size_t(i)].shard.count = 2;
        shards[size_t(i)].dumps = 2;
        shards[size_t(i)].rows[0].index = u64(i + 1);
    }
    tools::CompareReport merged;
    ASSERT_TRUE(tools::mergeReports(shards, {"s1.json", "s2.json"}, merged, err)) << err;
    EXPECT_EQ(merged.accuracy, "ppsspp");
    shards[1].accuracy = "psp";
    EXPECT_FALSE(tools::mergeReports(shards, {"s1.json", "s2.json"}, merged, err));
    EXPECT_NE(err.find("accuracy"), std::string::npos) << err;
}
