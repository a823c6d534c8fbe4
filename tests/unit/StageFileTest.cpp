// What every stage file shares: reading a file as JSON (missing, corrupt), the one serialiser
// (bytes that are not UTF-8 never abort a writer), and the schema and version check every
// reader starts with.
#include "tidepool/stagefiles/StageFile.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "FieldReader.h"
#include "TempDir.h"
#include <sys/stat.h>

namespace tidepool::stagefiles {
namespace {

using nlohmann::json;
using tidepool::testing::TempDir;

struct Empty {};

void ReadFields(FieldReader& /*r*/, const json& /*o*/, const std::string& /*path*/,
                Empty* /*out*/) {}

TEST(StageFileTest, ReadJsonFileNamesAMissingOrCorruptFile) {
    TempDir dir;
    std::string error;
    EXPECT_FALSE(ReadJsonFile(dir.Path() / "none.json", &error));
    EXPECT_EQ(error, (dir.Path() / "none.json").string() + ": no such file");
    const std::filesystem::path corrupt = dir.Write("c.json", "{\"schema\": \"tid");
    EXPECT_FALSE(ReadJsonFile(corrupt, &error));
    EXPECT_EQ(error, corrupt.string() +
                             ":1:16: not valid JSON: syntax error while parsing value - invalid "
                             "string: missing closing quote; last read: '\"tid'");
    // The line and column of the byte where the text stops being JSON.
    EXPECT_FALSE(ReadJsonFile(dir.Write("l.json", "{\"a\": 1,\n  \"b\": ]}"), &error));
    EXPECT_EQ(error.substr(0, error.find(": not valid JSON")),
              (dir.Path() / "l.json").string() + ":2:8");
    const std::filesystem::path good = dir.Write("g.json", "{\"a\": [1]}");
    const std::optional<json> read = ReadJsonFile(good, &error);
    ASSERT_TRUE(read);
    EXPECT_EQ((*read)["a"][0], 1);
}

// Before, every one of these was "no such file", though the path was there.
TEST(StageFileTest, ReadJsonFileSaysWhatStandsWhereAFileShouldBe) {
    TempDir dir;
    std::string error;
    EXPECT_FALSE(ReadJsonFile(dir.Path(), &error));
    EXPECT_EQ(error, dir.Path().string() + ": is a folder, not a file");
    EXPECT_FALSE(ReadJsonFile("/dev/zero", &error));
    EXPECT_EQ(error, "/dev/zero: is a device, not a regular file");
    const std::filesystem::path pipe = dir.Path() / "pipe.json";
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    EXPECT_FALSE(ReadJsonFile(pipe, &error));  // without blocking
    EXPECT_EQ(error, pipe.string() + ": is a FIFO (named pipe), not a regular file");
    std::filesystem::create_symlink("b.json", dir.Path() / "a.json");
    std::filesystem::create_symlink("a.json", dir.Path() / "b.json");
    EXPECT_FALSE(ReadJsonFile(dir.Path() / "a.json", &error));
    EXPECT_EQ(error, (dir.Path() / "a.json").string() + ": Too many levels of symbolic links");
}

TEST(StageFileTest, JsonTextReplacesBytesThatAreNotUtf8) {
    const json value = {{"message", std::string("caf\xe9")}};
    EXPECT_EQ(JsonText(value), "{\"message\":\"caf\xef\xbf\xbd\"}");
    EXPECT_EQ(JsonText(json::parse(R"({"a":1})"), 2), "{\n  \"a\": 1\n}");
}

TEST(StageFileTest, ADocumentOfAnotherSchemaOrVersionIsForeign) {
    const json good = json::parse(R"({"schema": "s", "version": 1})");
    EXPECT_TRUE(ReadStageDocument<Empty>(good, "f", "s", 1).value);
    struct Case {
        const char* document;
        const char* error;
    };
    for (const Case& c : {Case{R"([1])", "f: schema is not 's'"},
                          Case{R"({"schema": "t", "version": 1})", "f: schema is not 's'"},
                          Case{R"({"schema": "s"})", "f: version must be 1"},
                          Case{R"({"schema": "s", "version": "1"})", "f: version must be 1"},
                          Case{R"({"schema": "s", "version": 2})", "f: version must be 1"}}) {
        const ReadResult<Empty> read =
                ReadStageDocument<Empty>(json::parse(c.document), "f", "s", 1);
        EXPECT_FALSE(read.value) << c.document;
        EXPECT_EQ(read.failure, ReadFailure::kForeign) << c.document;
        EXPECT_EQ(read.error, c.error) << c.document;
    }
    // Another key, for a file that carries its version under an older name.
    const ReadResult<Empty> old = ReadStageDocument<Empty>(
            json::parse(R"({"schema": "s", "old": 1})"), "f", "s", 1, "old");
    EXPECT_TRUE(old.value) << old.error;
}

}  // namespace
}  // namespace tidepool::stagefiles
