// The one wording of a stage file's type errors: the path, the type expected and the JSON type
// found, any number being "number" and the root "(the document)".
#include "tidepool/stagefiles/WrongTypeMessage.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tidepool::stagefiles {
namespace {

using nlohmann::json;

TEST(WrongTypeMessageTest, NamesThePathTheExpectedTypeAndTheJsonTypeFound) {
    struct Case {
        json found;
        const char* type;
    };
    const std::vector<Case> cases = {
            {nullptr, "null"},
            {true, "bool"},
            {1, "number"},
            {1U, "number"},
            {1.5, "number"},
            {"a", "string"},
            {json::array(), "array"},
            {json::object(), "object"},
    };
    for (const Case& c : cases) {
        EXPECT_EQ(WrongTypeMessage("a.b[0]", "bool", c.found),
                  std::string("'a.b[0]' has the wrong type (expected bool, found ") + c.type + ")");
    }
}

TEST(WrongTypeMessageTest, TheRootIsCalledTheDocument) {
    EXPECT_EQ(WrongTypeMessage("", "object", json::array()),
              "'(the document)' has the wrong type (expected object, found array)");
}

}  // namespace
}  // namespace tidepool::stagefiles
