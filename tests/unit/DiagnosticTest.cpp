// One message about the user's input (compiler/include/tidepool/Diagnostic.h): its GCC form with
// the unknown parts left out, severity names, and which lists hold an error.
#include "tidepool/Diagnostic.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tidepool {
namespace {

struct FormatCase {
    Diagnostic diagnostic;
    const char* expected;
};

TEST(DiagnosticTest, FormatLeavesOutTheUnknownParts) {
    const std::vector<FormatCase> cases = {
            {{Severity::kError, "a.fsh", 3, 7, "no", "water:FOG"},
             "a.fsh:3:7: error: no [water:FOG]"},
            {{Severity::kWarning, "a.fsh", 3, 0, "hm", ""}, "a.fsh:3: warning: hm"},
            {{Severity::kNote, "a.fsh", 0, 7, "see", ""}, "a.fsh: note: see"},
            {{Severity::kError, "", 3, 7, "bad flag", ""}, "error: bad flag"},
            {{Severity::kError, "", 0, 0, "x", "v"}, "error: x [v]"},
    };
    for (const FormatCase& c : cases) {
        EXPECT_EQ(FormatDiagnostic(c.diagnostic), c.expected);
    }
}

TEST(DiagnosticTest, SeverityNamesAreGccs) {
    EXPECT_STREQ(SeverityName(Severity::kError), "error");
    EXPECT_STREQ(SeverityName(Severity::kWarning), "warning");
    EXPECT_STREQ(SeverityName(Severity::kNote), "note");
}

TEST(DiagnosticTest, SeverityFromNameReadsBackEveryNameAndNothingElse) {
    for (Severity severity : {Severity::kError, Severity::kWarning, Severity::kNote}) {
        EXPECT_EQ(SeverityFromName(SeverityName(severity)), severity);
    }
    EXPECT_EQ(SeverityFromName("Error"), std::nullopt);
    EXPECT_EQ(SeverityFromName(""), std::nullopt);
    EXPECT_EQ(SeverityFromName("fatal"), std::nullopt);
}

TEST(DiagnosticTest, OnlyAnErrorMakesAListHaveErrors) {
    EXPECT_FALSE(HasErrors({}));
    std::vector<Diagnostic> diagnostics = {{Severity::kWarning, "a", 1, 1, "w", ""},
                                           {Severity::kNote, "a", 1, 1, "n", ""}};
    EXPECT_FALSE(HasErrors(diagnostics));
    diagnostics.push_back(MakeError("b", 2, 0, "e"));
    EXPECT_TRUE(HasErrors(diagnostics));
}

TEST(DiagnosticTest, MakeErrorIsAnErrorAtThePlaceGivenForNoVariant) {
    const Diagnostic d = MakeError("v.yaml", 4, 2, "unknown key");
    EXPECT_EQ(d.severity, Severity::kError);
    EXPECT_EQ(d.variant, "");
    EXPECT_EQ(FormatDiagnostic(d), "v.yaml:4:2: error: unknown key");
}

}  // namespace
}  // namespace tidepool
