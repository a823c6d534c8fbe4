// Device limits (tidepool/DeviceLimits.h): the file format, each of its errors at its line and
// column, and the limits taking effect in validation, from both sides.
#include "tidepool/DeviceLimits.h"

#include <gtest/gtest.h>

#include "ShaderPairValidation.h"
#include "TempDir.h"

namespace tidepool {
namespace {

using testing::TempDir;

std::string Errors(const DeviceLimitsRead& read) {
    std::string text;
    for (const Diagnostic& d : read.diagnostics) {
        text += FormatDiagnostic(d) + "\n";
    }
    return text;
}

TEST(DeviceLimitsTest, ReadsNamesAndValuesWithCommentsAndBlankLines) {
    const DeviceLimitsRead read = ParseDeviceLimits(
            "# a mid-range phone\n"
            "\n"
            "MaxFragmentUniformVectors 224   // as reported by the driver\n"
            "MinProgramTexelOffset -8\n"
            "whileLoops 0\n",
            "phone.conf");
    ASSERT_TRUE(read.ok) << Errors(read);
    EXPECT_EQ(read.limits.Text(),
              "MaxFragmentUniformVectors 224\nMinProgramTexelOffset -8\nwhileLoops 0\n");
}

// Before, the suggestion measured the distance from every name to all of the word, and echoed
// it whole: a word of 1 MB took 5 s (10 MB, 47 s) and filled the terminal.
TEST(DeviceLimitsTest, AWordLongerThanAnyNameIsShownCutWithNoSuggestion) {
    const std::string word(1 << 20, 'M');
    const DeviceLimitsRead read = ParseDeviceLimits(word + " 4\n", "phone.conf");
    EXPECT_FALSE(read.ok);
    EXPECT_EQ(Errors(read), "phone.conf:1:1: error: unknown limit '" + std::string(64, 'M') +
                                    "...' (1048576 characters, longer than any limit name; the "
                                    "names are glslang's: `glslangValidator -c` prints them "
                                    "all)\n");
}

struct BadLimitsCase {
    const char* name;
    const char* text;
    const char* expected;
};

class DeviceLimitsBadInputTest : public ::testing::TestWithParam<BadLimitsCase> {};

TEST_P(DeviceLimitsBadInputTest, IsRefusedAtItsLineWithTheFix) {
    const DeviceLimitsRead read = ParseDeviceLimits(GetParam().text, "phone.conf");
    EXPECT_FALSE(read.ok);
    EXPECT_EQ(Errors(read), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
        Cases, DeviceLimitsBadInputTest,
        ::testing::Values(
                BadLimitsCase{"Misspelt", "MaxDrawBuffers 4\nMaxFragmentUniformVector 64\n",
                              "phone.conf:2:1: error: unknown limit 'MaxFragmentUniformVector'; "
                              "did you mean 'MaxFragmentUniformVectors'? (the names are "
                              "glslang's: `glslangValidator -c` prints them all)\n"},
                BadLimitsCase{"NoValue", "  MaxDrawBuffers\n",
                              "phone.conf:1:3: error: expected one limit as 'Name value' (as in "
                              "'MaxVertexUniformVectors 256'), found 1 words\n"},
                BadLimitsCase{"YamlStyle", "MaxDrawBuffers: 4\n",
                              "phone.conf:1:1: error: unknown limit 'MaxDrawBuffers:'; did you "
                              "mean 'MaxDrawBuffers'? (the names are glslang's: "
                              "`glslangValidator -c` prints them all)\n"},
                BadLimitsCase{"NotAWholeNumber", "MaxDrawBuffers 4.5\n",
                              "phone.conf:1:16: error: the value of 'MaxDrawBuffers' must be a "
                              "whole number from 0 to 2147483647, not '4.5'\n"},
                BadLimitsCase{"MinLimitNotAWholeNumber", "MinProgramTexelOffset 1e99\n",
                              "phone.conf:1:23: error: the value of 'MinProgramTexelOffset' must "
                              "be a whole number from -2147483648 to 2147483647, not '1e99'\n"},
                BadLimitsCase{"Twice", "MaxDrawBuffers 4\nMaxDrawBuffers 8\n",
                              "phone.conf:2:1: error: limit 'MaxDrawBuffers' is given twice; "
                              "keep one line\n"},
                BadLimitsCase{"Negative", "MaxDrawBuffers -1\n",
                              "phone.conf:1:16: error: 'MaxDrawBuffers' cannot be negative (-1); "
                              "only the Min... limits can\n"},
                BadLimitsCase{"SwitchNotBoolean", "whileLoops 2\n",
                              "phone.conf:1:12: error: 'whileLoops' is a switch: its value must "
                              "be 0 or 1, not 2\n"}),
        [](const ::testing::TestParamInfo<BadLimitsCase>& case_info) {
            return case_info.param.name;
        });

TEST(DeviceLimitsTest, AFileThatCannotBeReadIsOneErrorNamingIt) {
    TempDir dir;
    const std::string path = (dir.Path() / "missing.conf").string();
    const DeviceLimitsRead read = ReadDeviceLimits(path);
    EXPECT_FALSE(read.ok);
    ASSERT_EQ(read.diagnostics.size(), 1U);
    EXPECT_EQ(read.diagnostics[0].file, path);
    EXPECT_NE(read.diagnostics[0].message.find("cannot read the limits file"), std::string::npos);
}

// An editor's unseen byte-order mark was read as part of the first name ("unknown limit
// '\xEF\xBB\xBFMaxDrawBuffers'; did you mean 'MaxDrawBuffers'?").
TEST(DeviceLimitsTest, AByteOrderMarkBeforeTheFirstNameIsDropped) {
    TempDir dir;
    const std::string path = dir.Write("phone.conf", "\xEF\xBB\xBFMaxDrawBuffers 4\n").string();
    const DeviceLimitsRead read = ReadDeviceLimits(path);
    ASSERT_TRUE(read.ok) << Errors(read);
    EXPECT_EQ(read.limits.Text(), "MaxDrawBuffers 4\n");
}

// A fragment shader with 20 uniform vectors: more than the 16 every ES 2.0 device has (GLSL ES
// 1.00 §7.4), fewer than the 64 the device below reports.
constexpr const char* kTwentyUniformVectors =
        "#version 100\n"
        "precision mediump float;\n"
        "uniform vec4 palette[20];\n"
        "void main() { gl_FragColor = palette[0] + palette[19]; }\n";

bool Valid(const std::string& fragment, const DeviceLimits* limits, std::string* first_error) {
    ShaderFileOptions options;
    options.limits = limits;
    const testing::PairVerdict verdict = testing::ValidatePair(std::nullopt, fragment, options);
    *first_error = verdict.first_error;
    return verdict.valid;
}

TEST(DeviceLimitsTest, ADevicesLimitsReplaceTheEsMinimums) {
    std::string error;
    EXPECT_FALSE(Valid(kTwentyUniformVectors, nullptr, &error));
    EXPECT_EQ(error,
              "a.fsh:3:14: error: uniform 'palette' needs 20 uniform vectors, more than the 16 a "
              "fragment shader has (gl_MaxFragmentUniformVectors; GLSL ES 1.00 Appendix A §7, "
              "GLSL ES 3.00 §4.3.5)");
    const DeviceLimitsRead read = ParseDeviceLimits("MaxFragmentUniformVectors 64\n", "d.conf");
    ASSERT_TRUE(read.ok);
    EXPECT_TRUE(Valid(kTwentyUniformVectors, &read.limits, &error)) << error;
}

TEST(DeviceLimitsTest, ASmallerDeviceRejectsWhatTheMinimumsAllow) {
    const std::string needs_two_draw_buffers =
            "#version 100\n"
            "precision mediump float;\n"
            "float probe[gl_MaxDrawBuffers - 1];\n"
            "void main() { gl_FragColor = vec4(probe[0]); }\n";
    const DeviceLimitsRead four = ParseDeviceLimits("MaxDrawBuffers 4\n", "d.conf");
    const DeviceLimitsRead one = ParseDeviceLimits("MaxDrawBuffers 1\n", "d.conf");
    ASSERT_TRUE(four.ok && one.ok);
    std::string error;
    EXPECT_TRUE(Valid(needs_two_draw_buffers, &four.limits, &error)) << error;
    EXPECT_FALSE(Valid(needs_two_draw_buffers, &one.limits, &error));
    EXPECT_EQ(error, "a.fsh:3: error: '' : array size must be a positive integer");
}

}  // namespace
}  // namespace tidepool
