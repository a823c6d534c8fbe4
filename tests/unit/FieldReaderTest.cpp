// FieldReader, the stage-file readers' one type check: every kind of value it reads, the path
// it names, null numbers, absent and required fields, and that the first problem is kept.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "FieldReader.h"

namespace tidepool::stagefiles {
namespace {

using nlohmann::json;

struct Point {
    int x = 0;
    std::optional<double> y;
};

void ReadFields(FieldReader& r, const json& o, const std::string& path, Point* out) {
    r.Required(o, path, "x", &out->x);
    r.Field(o, path, "y", &out->y);
}

TEST(FieldReaderTest, ReadsScalarsListsMapsArraysAndStructs) {
    const json o = json::parse(R"({"s": "a", "b": true, "d": 1.5, "i": 7, "l": 3000000000,
        "list": [1, 2], "map": {"p": "q"}, "pair": [1, 2], "point": {"x": 1, "y": 2.5},
        "points": [{"x": 2}]})");
    FieldReader r;
    std::string s;
    bool b = false;
    double d = 0;
    int i = 0;
    long long l = 0;
    std::vector<int> list;
    std::map<std::string, std::string, std::less<>> map;
    std::array<double, 2> pair{};
    Point point;
    std::vector<Point> points;
    r.Field(o, "", "s", &s);
    r.Field(o, "", "b", &b);
    r.Field(o, "", "d", &d);
    r.Field(o, "", "i", &i);
    r.Field(o, "", "l", &l);
    r.Field(o, "", "list", &list);
    r.Field(o, "", "map", &map);
    r.Field(o, "", "pair", &pair);
    r.Field(o, "", "point", &point);
    r.Field(o, "", "points", &points);
    ASSERT_TRUE(r.Ok()) << r.Problem();
    EXPECT_EQ(r.Problem(), "");
    EXPECT_EQ(s, "a");
    EXPECT_TRUE(b);
    EXPECT_EQ(d, 1.5);
    EXPECT_EQ(i, 7);
    EXPECT_EQ(l, 3'000'000'000LL);
    EXPECT_EQ(list, (std::vector<int>{1, 2}));
    EXPECT_EQ(map.at("p"), "q");
    EXPECT_EQ(pair, (std::array<double, 2>{1, 2}));
    EXPECT_EQ(point.x, 1);
    EXPECT_EQ(point.y, 2.5);
    ASSERT_EQ(points.size(), 1U);
    EXPECT_FALSE(points[0].y);
}

// JSON has no NaN: writers write it as null, and a number read from null is NaN; an integer
// keeps its value.
TEST(FieldReaderTest, NullNumbersReadAsNaNAndLeaveIntegersAlone) {
    const json o = json::parse(R"({"d": null, "i": null})");
    FieldReader r;
    double d = 0;
    int i = 5;
    r.Field(o, "", "d", &d);
    r.Field(o, "", "i", &i);
    ASSERT_TRUE(r.Ok()) << r.Problem();
    EXPECT_TRUE(std::isnan(d));
    EXPECT_EQ(i, 5);
}

TEST(FieldReaderTest, AbsentFieldsKeepTheirValueAndRequiredOnesAreNamed) {
    const json o = json::parse(R"({"point": {"y": 1}})");
    FieldReader r;
    std::string s = "kept";
    r.Field(o, "", "s", &s);
    EXPECT_TRUE(r.Ok());
    EXPECT_EQ(s, "kept");
    Point point;
    r.Field(o, "", "point", &point);
    EXPECT_EQ(r.Failure(), ReadFailure::kMissingField);
    EXPECT_EQ(r.Problem(), "'point.x' is missing");
}

TEST(FieldReaderTest, TheFirstWrongTypeIsNamedWithItsPathAndKept) {
    const json o = json::parse(R"({"points": [{"x": 1}, {"x": "2"}], "b": 1})");
    FieldReader r;
    std::vector<Point> points;
    bool b = false;
    r.Field(o, "root", "points", &points);
    r.Field(o, "root", "b", &b);
    EXPECT_EQ(r.Failure(), ReadFailure::kWrongType);
    EXPECT_EQ(r.Problem(), "'root.points[1].x' has the wrong type (expected number, found string)");
    EXPECT_FALSE(b);  // nothing is read after the first problem
}

TEST(FieldReaderTest, AFixedSizeArrayOfAnotherLengthIsAWrongType) {
    FieldReader r;
    std::array<double, 3> eye{};
    r.Field(json::parse(R"({"eye": [1, 2]})"), "", "eye", &eye);
    EXPECT_EQ(r.Problem(), "'eye' has the wrong type (expected 3 items, found array)");
}

// The problem FieldReader records reading `text`'s "v" into a T ("" when none).
template <typename T>
std::string ProblemReading(const std::string& key, const std::string& text) {
    FieldReader r;
    T value{};
    r.Field(json::parse(text), "c", key, &value);
    EXPECT_EQ(r.Ok(), r.Failure() == ReadFailure::kNone);
    EXPECT_TRUE(r.Ok() || r.Failure() == ReadFailure::kBadValue) << r.Problem();
    return r.Problem();
}

TEST(FieldReaderTest, AnIntegerIsAWholeCountThatFitsItsType) {
    EXPECT_EQ(ProblemReading<int>("count", R"({"count": 3})"), "");
    EXPECT_EQ(ProblemReading<int>("count", R"({"count": 3.0})"), "");
    EXPECT_EQ(ProblemReading<int>("count", R"({"count": -3})"),
              "'c.count' is -3, which is not a count (a whole number from 0)");
    EXPECT_EQ(ProblemReading<int>("count", R"({"count": 2.5})"),
              "'c.count' is 2.5, which is not a count (a whole number from 0)");
    // Past the type: reading it would be undefined behaviour, not a large count.
    EXPECT_EQ(ProblemReading<int>("count", R"({"count": 1e30})"),
              "'c.count' is 1e+30, which is not a count (a whole number from 0)");
    EXPECT_EQ(ProblemReading<int>("count", R"({"count": 2147483648})"),
              "'c.count' is 2147483648, which is not a count (a whole number from 0)");
    EXPECT_EQ(ProblemReading<long long>("count", R"({"count": 3000000000})"), "");
    // A difference may be negative.
    EXPECT_EQ(ProblemReading<int>("passes_saved", R"({"passes_saved": -2})"), "");
}

TEST(FieldReaderTest, ADurationIsFromZeroToAnHour) {
    EXPECT_EQ(ProblemReading<double>("median_ms", R"({"median_ms": 0})"), "");
    EXPECT_EQ(ProblemReading<double>("median_ms", R"({"median_ms": 3600000})"), "");
    EXPECT_EQ(ProblemReading<double>("median_ms", R"({"median_ms": null})"), "");
    EXPECT_EQ(ProblemReading<double>("median_ms", R"({"median_ms": -5.0})"),
              "'c.median_ms' is -5.0, which is not a duration: from 0 to 3600000");
    EXPECT_EQ(ProblemReading<double>("wall_seconds", R"({"wall_seconds": 1e308})"),
              "'c.wall_seconds' is 1e+308, which is not a duration: from 0 to 3600000");
    // Items of a list, and values of a map, named for durations are durations too.
    EXPECT_EQ(ProblemReading<std::vector<std::vector<double>>>("samples_ms",
                                                               R"({"samples_ms": [[1, -1]]})"),
              "'c.samples_ms[0][1]' is -1, which is not a duration: from 0 to 3600000");
    EXPECT_EQ((ProblemReading<std::map<std::string, double, std::less<>>>(
                      "pass_ms", R"({"pass_ms": {"reflection": 4e6}})")),
              "'c.pass_ms.reflection' is 4000000.0, which is not a duration: from 0 to 3600000");
    // Other numbers may be negative.
    EXPECT_EQ(ProblemReading<double>("change_percent", R"({"change_percent": -30})"), "");
}

TEST(FieldReaderTest, FailKeepsOnlyTheFirstProblem) {
    FieldReader r;
    r.Fail(ReadFailure::kForeign, "first");
    r.Fail(ReadFailure::kWrongType, "second");
    EXPECT_EQ(r.Failure(), ReadFailure::kForeign);
    EXPECT_EQ(r.Problem(), "first");
}

TEST(FieldReaderTest, PathsJoinKeysAndIndices) {
    EXPECT_EQ(FieldReader::Join("", "a"), "a");
    EXPECT_EQ(FieldReader::Join("a", "b"), "a.b");
    EXPECT_EQ(FieldReader::Index("a", 3), "a[3]");
}

}  // namespace
}  // namespace tidepool::stagefiles
