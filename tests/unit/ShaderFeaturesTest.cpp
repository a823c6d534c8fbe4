// The shader feature table against what it names: the shipped variants.yaml declares every row's
// define in the row's programs and nothing the table lacks, water_uniform.fsh declares exactly
// the rows marked as uniform bools, and the lookups by enumerator and by name agree.
#include "tidepool/TextFile.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/ShaderFeatures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace tidepool::runner {
namespace {

const std::filesystem::path kSourceRoot = TIDEPOOL_SOURCE_ROOT;

class ShaderFeaturesTest : public ::testing::Test {
protected:
    void SetUp() override {
        ConfigResult loaded = LoadVariantConfig(kSourceRoot / "variants.yaml");
        ASSERT_TRUE(loaded.config.has_value());
        config_ = std::move(*loaded.config);
    }

    VariantConfig config_;
};

TEST_F(ShaderFeaturesTest, EveryRowIsDeclaredByItsProgramsInTheDefaultVariantsYaml) {
    for (const ShaderFeatureInfo& info : kShaderFeatures) {
        int programs = 0;
        for (std::string_view name : info.programs) {
            if (name.empty()) {
                continue;
            }
            ++programs;
            const ProgramConfig* program = config_.FindProgram(name);
            ASSERT_NE(program, nullptr) << info.define << ": no program " << name;
            const std::vector<std::string> declared = program->AllDefines();
            EXPECT_TRUE(std::find(declared.begin(), declared.end(), info.define) != declared.end())
                    << info.define << " is not a feature or axis value of " << name;
        }
        EXPECT_GT(programs, 0) << info.define << " names no program";
    }
}

TEST_F(ShaderFeaturesTest, EveryDefineOfTheRenderedProgramsHasARow) {
    std::set<std::string_view> programs;
    for (const ShaderFeatureInfo& info : kShaderFeatures) {
        programs.insert(info.programs.begin(), info.programs.end());
    }
    programs.erase("");
    EXPECT_EQ(programs, (std::set<std::string_view>{"water", "skybox", "model"}));
    for (std::string_view name : programs) {
        const ProgramConfig* program = config_.FindProgram(name);
        ASSERT_NE(program, nullptr) << name;
        for (const std::string& define : program->AllDefines()) {
            const std::optional<ShaderFeature> feature = FeatureFromDefine(define);
            ASSERT_TRUE(feature.has_value()) << name << " declares " << define << ", no row has it";
            const auto& listed = ShaderFeatureInfoOf(*feature).programs;
            EXPECT_TRUE(std::find(listed.begin(), listed.end(), name) != listed.end())
                    << define << "'s row does not list " << name;
        }
    }
}

TEST_F(ShaderFeaturesTest, UniformBoolRowsAreTheBoolsOfWaterUniform) {
    const TextFileRead shader = ReadShaderFile(kSourceRoot / "shaders" / "water_uniform.fsh");
    ASSERT_TRUE(shader.ok) << shader.error;
    std::size_t bools = 0;
    for (std::size_t at = shader.text.find("uniform bool "); at != std::string::npos;
         at = shader.text.find("uniform bool ", at + 1)) {
        ++bools;
    }
    std::size_t rows = 0;
    for (const ShaderFeatureInfo& info : kShaderFeatures) {
        if (!info.uniform_bool) {
            continue;
        }
        ++rows;
        const std::string declaration = "uniform bool " + UniformBoolName(info.define) + ";";
        EXPECT_NE(shader.text.find(declaration), std::string::npos) << declaration;
    }
    EXPECT_EQ(rows, 9U);  // the whitepaper's nine defines (INTERFACE.md)
    EXPECT_EQ(bools, rows);
}

TEST(ShaderFeaturesLookupTest, EnumeratorAndDefineNameRoundTrip) {
    std::set<std::string_view> defines;
    for (const ShaderFeatureInfo& info : kShaderFeatures) {
        EXPECT_EQ(&ShaderFeatureInfoOf(info.feature), &info);
        EXPECT_EQ(DefineName(info.feature), info.define);
        EXPECT_EQ(FeatureFromDefine(info.define), info.feature) << info.define;
        EXPECT_TRUE(IsValidDefineName(info.define)) << info.define;
        EXPECT_FALSE(info.what.empty()) << info.define;
        defines.insert(info.define);
    }
    EXPECT_EQ(defines.size(), kShaderFeatures.size()) << "a define name is in two rows";
}

TEST(ShaderFeaturesLookupTest, NameOutsideTheTableHasNoFeature) {
    EXPECT_EQ(FeatureFromDefine(""), std::nullopt);
    EXPECT_EQ(FeatureFromDefine("REFLECTION_PLANAR"), std::nullopt);  // the default adds none
    EXPECT_EQ(FeatureFromDefine("enable_fog"), std::nullopt);         // names are case-sensitive
    EXPECT_EQ(FeatureFromDefine("ENABLE_FOG "), std::nullopt);
    EXPECT_EQ(FeatureFromDefine("TP_NO_EYE_FLOOR"),
              std::nullopt);  // a stability guard, not a feature
}

TEST(ShaderFeaturesLookupTest, DefineNamesKeepTheGivenOrder) {
    EXPECT_EQ(DefineNames({ShaderFeature::kFog, ShaderFeature::kClipDiscard,
                           ShaderFeature::kDistortion}),
              (std::vector<std::string>{"ENABLE_FOG", "CLIP_DISCARD", "ENABLE_DISTORTION"}));
    EXPECT_TRUE(DefineNames({}).empty());
}

TEST(ShaderFeaturesLookupTest, ConfigurationHasAFeatureByItsDefine) {
    RenderConfiguration c;
    c.effects = {"ENABLE_FOG", "REFLECTION_FOURIER"};
    EXPECT_TRUE(c.Has(ShaderFeature::kFog));
    EXPECT_TRUE(c.Has(ShaderFeature::kReflectionFourier));
    EXPECT_FALSE(c.Has(ShaderFeature::kReflectionCubemap));
    EXPECT_FALSE(c.Has(ShaderFeature::kFogDepth));
}

}  // namespace
}  // namespace tidepool::runner
