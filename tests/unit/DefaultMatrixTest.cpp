// The shipped variants.yaml as a matrix: the seeds' techniques are in it, and its rules refuse
// the combinations that cannot work.
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "ExpandOneByOne.h"

namespace tidepool {
namespace {

class DefaultMatrixTest : public ::testing::Test {
protected:
    void SetUp() override {
        ConfigResult loaded =
                LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
        ASSERT_TRUE(loaded.config.has_value());
        config_ = std::move(*loaded.config);
        water_ = config_.FindProgram("water");
        ASSERT_NE(water_, nullptr);
        for (const Variant& v :
             ExpandVariants(config_, ExpansionOptions{config_.max_variants}).variants) {
            if (v.program == "water") {
                water_variants_.push_back(v);
            }
        }
    }

    // The rule that refuses `defines`, described, or "" when they are a valid water variant.
    std::string Refusal(const std::vector<std::string>& defines) const {
        std::vector<std::string> sorted = MakeVariant("water", defines).defines;
        const Rule* rule = FirstBrokenRule(*water_, sorted);
        return rule == nullptr ? "" : rule->Describe();
    }

    VariantConfig config_;
    const ProgramConfig* water_ = nullptr;
    std::vector<Variant> water_variants_;
};

TEST_F(DefaultMatrixTest, EveryReflectionTechniqueAndOpticIsInTheMatrix) {
    std::set<std::string> seen;
    int planar = 0;
    for (const Variant& v : water_variants_) {
        seen.insert(v.defines.begin(), v.defines.end());
        const bool cubemap = std::count(v.defines.begin(), v.defines.end(), "REFLECTION_CUBEMAP");
        const bool fourier = std::count(v.defines.begin(), v.defines.end(), "REFLECTION_FOURIER");
        EXPECT_FALSE(cubemap && fourier) << v.Id();
        planar += cubemap || fourier ? 0 : 1;
    }
    for (const char* define : {"REFLECTION_CUBEMAP", "REFLECTION_FOURIER", "ENABLE_EXTINCTION",
                               "ENABLE_SHORE_FOAM", "ENABLE_SOFT_SHORE", "ENABLE_SUN_SPECULAR"}) {
        EXPECT_TRUE(seen.count(define)) << define;
    }
    // planar is the axis default: no define, so the whitepaper's 54 variants keep their ids.
    EXPECT_EQ(seen.count("REFLECTION_PLANAR"), 0U);
    EXPECT_EQ(std::count_if(water_variants_.begin(), water_variants_.end(),
                            [](const Variant& v) { return v.Id() == "water:ENABLE_FOG"; }),
              1);
    EXPECT_EQ(planar, 54 + 15);  // + every subset of the four optics on the full effect
    EXPECT_EQ(water_variants_.size(), 54U + 15U + 2U * 36U);
}

TEST_F(DefaultMatrixTest, DepthOpticsWithoutTheRefractionDepthAreRefused) {
    for (const char* optic : {"ENABLE_EXTINCTION", "ENABLE_SHORE_FOAM", "ENABLE_SOFT_SHORE"}) {
        EXPECT_EQ(Refusal({optic, "ENABLE_DISTORTION", "ENABLE_FOG"}),
                  std::string(optic) + " requires ENABLE_REFRACTION")
                << optic;
    }
    EXPECT_EQ(Refusal({"ENABLE_SUN_SPECULAR", "ENABLE_REFRACTION"}),
              "ENABLE_SUN_SPECULAR requires ENABLE_FRESNEL");
    // With what they need, they are accepted on the full effect.
    EXPECT_EQ(Refusal({"ENABLE_REFRACTION", "ENABLE_FRESNEL", "ENABLE_DISTORTION",
                       "ENABLE_SCALE_DISTORTION", "ENABLE_FOG", "ENABLE_EXTINCTION",
                       "ENABLE_SHORE_FOAM", "ENABLE_SOFT_SHORE", "ENABLE_SUN_SPECULAR"}),
              "");
}

TEST_F(DefaultMatrixTest, ReflectionAxisValuesNeverCombineAndPresetsNameThem) {
    // The expander takes exactly one axis value; a hand-written pair is not a variant.
    const Axis* reflection = nullptr;
    for (const Axis& axis : water_->axes) {
        if (axis.name == "REFLECTION") {
            reflection = &axis;
        }
    }
    ASSERT_NE(reflection, nullptr);
    EXPECT_EQ(reflection->values, (std::vector<std::string>{"planar", "cubemap", "fourier"}));
    for (const char* preset :
         {"cubemap_reflection", "fourier_reflection", "full_cubemap_reflection",
          "full_fourier_reflection", "full_depth_optics"}) {
        const Preset* p = config_.FindPreset(preset);
        ASSERT_NE(p, nullptr) << preset;
        const Variant v = MakeVariant(p->program, p->defines);
        EXPECT_TRUE(std::count(water_variants_.begin(), water_variants_.end(), v)) << preset;
    }
}

TEST_F(DefaultMatrixTest, PrunedCountsPerRuleMatchEveryCombinationCheckedOneByOne) {
    const ExpansionResult expansion =
            ExpandVariants(config_, ExpansionOptions{config_.max_variants});
    ASSERT_TRUE(expansion.diagnostics.empty());
    EXPECT_EQ(expansion.variants.size(), 163U);
    EXPECT_EQ(expansion.pruned_total, 24435U);
    std::size_t row = 0;
    for (const ProgramConfig& program : config_.programs) {
        const std::vector<std::uint64_t> expected = testing::ExpandOneByOne(program).counts;
        for (std::size_t r = 0; r < program.rules.size(); ++r, ++row) {
            ASSERT_LT(row, expansion.pruned_by_rule.size());
            EXPECT_EQ(expansion.pruned_by_rule[row].program, program.name);
            EXPECT_EQ(expansion.pruned_by_rule[row].count, expected[r])
                    << program.rules[r].Describe();
        }
    }
    EXPECT_EQ(row, expansion.pruned_by_rule.size());
}
}  // namespace
}  // namespace tidepool
