#include "tidepool/VariantConfig.h"

#include <gtest/gtest.h>

#include "TempDir.h"
#include "tidepool/VariantExpander.h"

namespace tidepool {
namespace {

using testing::TempDir;

// A folder with a minimal pair of shader files, so configurations can name real files.
class VariantConfigTest : public ::testing::Test {
protected:
    VariantConfigTest() {
        dir_.Write("s.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
        dir_.Write("s.fsh", "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = "
                            "vec4(1.0); }\n");
    }
    ConfigResult Parse(const std::string& yaml) {
        return ParseVariantConfig(yaml, "v.yaml", dir_.Path());
    }
    // Every diagnostic, formatted, one per line.
    std::string Errors(const std::string& yaml) {
        std::string out;
        for (const Diagnostic& d : Parse(yaml).diagnostics) {
            out += FormatDiagnostic(d) + "\n";
        }
        return out;
    }
    TempDir dir_;
};

constexpr const char* kProgramHead =
        "programs:\n"
        "  p:\n"
        "    vertex: s.vsh\n"
        "    fragment: s.fsh\n";

TEST_F(VariantConfigTest, ValidConfigurationLoadsFeaturesAxesRulesAndPresets) {
    const ConfigResult result = Parse(std::string(kProgramHead) +
                                      "    features: [A, B]\n"
                                      "    axes:\n"
                                      "      MODE: [fast, exact]\n"
                                      "    rules:\n"
                                      "      - { if: B, requires: A, reason: why }\n"
                                      "      - { if: A, excludes: MODE_EXACT }\n"
                                      "      - { exclude: [B, MODE_FAST] }\n"
                                      "presets:\n"
                                      "  fast_a: { program: p, defines: [A, MODE_FAST] }\n");
    ASSERT_TRUE(result.config.has_value()) << result.diagnostics.size();
    const VariantConfig& config = *result.config;
    ASSERT_EQ(config.programs.size(), 1U);
    const ProgramConfig& p = config.programs[0];
    EXPECT_EQ(p.AllDefines(), (std::vector<std::string>{"A", "B", "MODE_FAST", "MODE_EXACT"}));
    ASSERT_EQ(p.rules.size(), 3U);
    EXPECT_EQ(p.rules[0].Describe(), "B requires A");
    EXPECT_EQ(p.rules[0].reason, "why");
    EXPECT_EQ(p.rules[0].where.line, 9);
    EXPECT_EQ(p.rules[1].Describe(), "A excludes MODE_EXACT");
    EXPECT_EQ(p.rules[2].Describe(), "excluded combination B, MODE_FAST");
    ASSERT_EQ(config.presets.size(), 1U);
    EXPECT_EQ(config.targets, std::vector<GlslTarget>{GlslTarget::kEs100});
}

TEST_F(VariantConfigTest, AxisValueBecomesUpperCaseDefine) {
    Axis axis{"REFLECTION", {"planar", "cubeMap"}, {}};
    EXPECT_EQ(axis.DefineFor("planar"), "REFLECTION_PLANAR");
    EXPECT_EQ(axis.DefineFor("cubeMap"), "REFLECTION_CUBEMAP");
}

TEST_F(VariantConfigTest, TargetsAcceptOptionalEs300) {
    const ConfigResult result = Parse("targets: [100, 300]\n" + std::string(kProgramHead));
    ASSERT_TRUE(result.config.has_value());
    EXPECT_EQ(result.config->targets,
              (std::vector<GlslTarget>{GlslTarget::kEs100, GlslTarget::kEs300}));
}

TEST(DefineNameTest, AcceptsIdentifiersAndRejectsReservedOrMalformedNames) {
    EXPECT_TRUE(IsValidDefineName("ENABLE_FOG"));
    EXPECT_TRUE(IsValidDefineName("_x1"));
    EXPECT_FALSE(IsValidDefineName(""));
    EXPECT_FALSE(IsValidDefineName("1FOG"));
    EXPECT_FALSE(IsValidDefineName("ENABLE-FOG"));
    EXPECT_FALSE(IsValidDefineName("GL_FOG"));
    EXPECT_FALSE(IsValidDefineName("MY__FOG"));
}

// Every bad input names the file, line and column, and explains the fix.
struct BadInputCase {
    const char* name;
    std::string yaml;
    std::string expected;  // the exact formatted diagnostics
};

class BadConfigTest : public VariantConfigTest,
                      public ::testing::WithParamInterface<BadInputCase> {};

TEST_P(BadConfigTest, IsRejectedWithExactDiagnostic) {
    const ConfigResult result = Parse(GetParam().yaml);
    EXPECT_FALSE(result.config.has_value());
    EXPECT_EQ(Errors(GetParam().yaml), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
        Cases, BadConfigTest,
        ::testing::Values(
                BadInputCase{"EmptyFile", "",
                             "v.yaml:1:1: error: the file is empty; it needs at least "
                             "`programs:` (see the variants.yaml schema in README.md)\n"},
                BadInputCase{"MalformedYaml", "programs:\n  p: [a, b\n  q: 1\n",
                             "v.yaml:3:4: error: malformed YAML: end of sequence flow not "
                             "found\n"},
                BadInputCase{"UnknownTopLevelKey", std::string(kProgramHead) + "varaints: 1\n",
                             "v.yaml:5:1: error: unknown key 'varaints' in the top level; "
                             "allowed keys: version, targets, max_variants, programs, presets, "
                             "description\n"},
                BadInputCase{"UnknownProgramKey", std::string(kProgramHead) + "    featurs: [A]\n",
                             "v.yaml:5:5: error: unknown key 'featurs' in program 'p'; allowed "
                             "keys: vertex, fragment, features, axes, rules, description\n"},
                BadInputCase{"RuleNamesUnknownFeature",
                             std::string(kProgramHead) +
                                     "    features: [A]\n"
                                     "    rules:\n"
                                     "      - { if: A, requires: B }\n",
                             "v.yaml:7:9: error: rule names unknown feature 'B' in program 'p'; "
                             "known: A\n"},
                BadInputCase{"FeatureDeclaredTwice",
                             std::string(kProgramHead) + "    features: [A, B, A]\n",
                             "v.yaml:5:22: error: feature 'A' is declared twice in program 'p'; "
                             "remove one\n"},
                BadInputCase{"DuplicateMapKey",
                             std::string(kProgramHead) + "    vertex: s.vsh\n",
                             "v.yaml:5:5: error: duplicate key 'vertex' (first written at line "
                             "3); remove one of them\n"},
                BadInputCase{"InvalidDefineName",
                             std::string(kProgramHead) + "    features: [ENABLE-FOG]\n",
                             "v.yaml:5:16: error: 'ENABLE-FOG' is not a valid GLSL define name: "
                             "use letters, digits and _, start with a letter, no 'GL_' prefix "
                             "and no '__'\n"},
                BadInputCase{"PresetBreaksRule",
                             std::string(kProgramHead) +
                                     "    features: [A, B]\n"
                                     "    rules: [{ if: B, requires: A }]\n"
                                     "presets:\n"
                                     "  bad: { program: p, defines: [B] }\n",
                             "v.yaml:8:3: error: preset 'bad' breaks rule 'B requires A' (line "
                             "6); change its defines\n"},
                BadInputCase{"MalformedRule",
                             std::string(kProgramHead) +
                                     "    features: [A, B]\n"
                                     "    rules: [{ if: A }]\n",
                             "v.yaml:6:13: error: a rule is either `{if: A, requires: [B]}`, "
                             "`{if: A, excludes: [B]}` or `{exclude: [A, B]}`\n"},
                BadInputCase{"DesktopOnlyTargets", "targets: [330]\n" + std::string(kProgramHead),
                             "v.yaml:1:10: error: unknown GLSL ES target '330'; use 100 or 300\n"
                             "v.yaml:1:10: error: targets must include 100 (GLSL ES 1.00 is the "
                             "shaders' own language)\n"}),
        [](const ::testing::TestParamInfo<BadInputCase>& case_info) { return case_info.param.name; });

TEST_F(VariantConfigTest, MissingShaderFileNamesThePathAndWhereItWasLookedFor) {
    const std::string errors =
            Errors("programs:\n  p:\n    vertex: nope.vsh\n    fragment: s.fsh\n");
    EXPECT_EQ(errors, "v.yaml:3:13: error: vertex shader file 'nope.vsh' not found (looked for " +
                              (dir_.Path() / "nope.vsh").string() +
                              "); paths are relative to the folder of v.yaml\n");
}

TEST_F(VariantConfigTest, UnreadableFileIsAnErrorNamingIt) {
    const ConfigResult result = LoadVariantConfig(dir_.Path() / "missing.yaml");
    ASSERT_EQ(result.diagnostics.size(), 1U);
    EXPECT_EQ(FormatDiagnostic(result.diagnostics[0]),
              (dir_.Path() / "missing.yaml").string() +
                      ": error: cannot read the configuration file; check the path or pass "
                      "--config PATH");
}

TEST(DefaultConfigTest, ShippedVariantsYamlLoadsWithTheWhitepaperPresets) {
    const ConfigResult result =
            LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
    ASSERT_TRUE(result.config.has_value());
    EXPECT_TRUE(result.diagnostics.empty());
    for (const char* preset : {"reflection_only", "reflection_water_colour",
                               "reflection_alpha_blend", "reflection_refraction", "full"}) {
        EXPECT_NE(result.config->FindPreset(preset), nullptr) << preset;
    }
    const Preset* full = result.config->FindPreset("full");
    EXPECT_EQ(MakeVariant(full->program, full->defines).Id(),
              "water:ENABLE_DISTORTION,ENABLE_FOG,ENABLE_FRESNEL,ENABLE_REFRACTION,"
              "ENABLE_SCALE_DISTORTION");
}

}  // namespace
}  // namespace tidepool
