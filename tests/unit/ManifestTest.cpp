#include "tidepool/Manifest.h"

#include <gtest/gtest.h>

namespace tidepool {
namespace {

TEST(ManifestTest, JsonTextReplacesBytesThatAreNotUtf8InsteadOfThrowing) {
    // A glslang diagnostic quoting a Latin-1 identifier of a shader: nlohmann's own dump throws
    // type_error.316 on it, which used to abort the writers.
    const Diagnostic quoted = MakeError("w.fsh", 3, 5, "'caf\xE9' : undeclared identifier");
    const nlohmann::json json = ToJson(quoted);
    EXPECT_THROW(static_cast<void>(json.dump()), nlohmann::json::type_error);
    const std::string text = JsonText(json);
    EXPECT_NE(text.find("'caf\xEF\xBF\xBD' : undeclared identifier"), std::string::npos) << text;
    EXPECT_TRUE(nlohmann::json::accept(text));
}

}  // namespace
}  // namespace tidepool
