// stability.json's reader and writer: what the writer writes reads back as the same value, and a
// field of the wrong type or a foreign file is an error naming the file and the field.
#include "tidepool/stagefiles/StabilityFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "TempDir.h"

namespace tidepool::stagefiles {
namespace {

using nlohmann::json;
using tidepool::testing::TempDir;

StabilityFile OneOfEachStability() {
    StabilityFile file;
    file.environment = {{"backend", "egl"}, {"size", "64x48"}};
    file.cases = {{"grazing_fresnel", "cos near 0", "cpu", 0, 0, 0, 0.001, 0.01, true, "clamp",
                   "max |F - F_double|"},
                  {"camera_on_plane", "eye in the plane", "gl", 12, 3'000'000'000L, 1, 2.5, 0.0,
                   false, "offset the eye", "3 NaN channels"}};
    file.precision = {{"pow(1-c,5)", 1e-7, 0.002, 0.01, 0.05, 0, false, "ok"}};
    file.guards = {{"max(dot,0) (TP_NO_DOT_CLAMP)", 0.0, 1.0, true}};
    return file;
}

TEST(StabilityFileTest, WhatIsWrittenReadsBackAsTheSameValue) {
    TempDir dir;
    const StabilityFile file = OneOfEachStability();
    const std::filesystem::path path = dir.Write("stability.json", StabilityFileText(file));
    const ReadResult<StabilityFile> read = ReadStabilityFile(path);
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_EQ(read.failure, ReadFailure::kNone);
    EXPECT_EQ(*read.value, file);
    EXPECT_EQ(StabilityFileText(*read.value), StabilityFileText(file));
}

TEST(StabilityFileTest, TheTextIsIndentedWithAFinalNewline) {
    const std::string text = StabilityFileText(OneOfEachStability());
    EXPECT_EQ(text.rfind("{\n  \"", 0), 0u) << text;
    EXPECT_EQ(text.back(), '\n');
    const json j = json::parse(text);
    EXPECT_EQ(j["schema"], "tidepool.stability");
    EXPECT_EQ(j["version"], 1);
    EXPECT_EQ(j["cases"][1]["nan_count"], 3'000'000'000L);
    EXPECT_EQ(j["environment"]["backend"], "egl");
}

TEST(StabilityFileTest, NullNumbersReadAsNaN) {
    json j = json::parse(StabilityFileText(OneOfEachStability()));
    j["cases"][0]["max_error"] = nullptr;
    const ReadResult<StabilityFile> read = StabilityFileFromJson(j, "s.json");
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_TRUE(std::isnan(read.value->cases[0].max_error));
}

TEST(StabilityFileTest, AWronglyTypedFieldNamesTheFileAndTheField) {
    struct Case {
        const char* pointer;
        json value;
        const char* message;
    };
    const std::vector<Case> cases = {
            {"/cases/0/passed", "yes",
             "'cases[0].passed' has the wrong type (expected bool, found string)"},
            {"/cases/1/nan_count", "3",
             "'cases[1].nan_count' has the wrong type (expected number, found string)"},
            {"/precision/0/loses_precision", 0,
             "'precision[0].loses_precision' has the wrong type (expected bool, found number)"},
            {"/guards/0/tolerance", json::array(),
             "'guards[0].tolerance' has the wrong type (expected number, found array)"},
            {"/environment/size", 64,
             "'environment.size' has the wrong type (expected string, found number)"},
            {"/cases", json::object(), "'cases' has the wrong type (expected array, found object)"},
            {"/guards/0", "guard",
             "'guards[0]' has the wrong type (expected object, found string)"},
    };
    for (const Case& c : cases) {
        json j = json::parse(StabilityFileText(OneOfEachStability()));
        j[json::json_pointer(c.pointer)] = c.value;
        const ReadResult<StabilityFile> read = StabilityFileFromJson(j, "run/stability.json");
        EXPECT_FALSE(read.value) << c.pointer;
        EXPECT_EQ(read.failure, ReadFailure::kWrongType) << c.pointer;
        EXPECT_EQ(read.error, std::string("run/stability.json: ") + c.message);
    }
}

TEST(StabilityFileTest, AnotherSchemaOrVersionIsForeign) {
    json j = json::parse(StabilityFileText(OneOfEachStability()));
    j["version"] = "1";
    ReadResult<StabilityFile> read = StabilityFileFromJson(j, "s.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "s.json: version must be 1");
    read = StabilityFileFromJson(json::parse(R"({"name": "mine"})"), "s.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "s.json: schema is not 'tidepool.stability'");
}

}  // namespace
}  // namespace tidepool::stagefiles
