#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"

#include <gtest/gtest.h>

#include "TempDir.h"
#include <sys/stat.h>

namespace tidepool {
namespace {

using testing::TempDir;

// A folder with a minimal pair of shader files, so configurations can name real files.
class VariantConfigTest : public ::testing::Test {
protected:
    VariantConfigTest() {
        dir_.Write("s.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
        dir_.Write("s.fsh",
                   "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = "
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

TEST_F(VariantConfigTest, AnEmptyDocumentAfterTheFirstIsNoSecondDocument) {
    for (const char* ending : {"---\n", "...\n", "---\n...\n"}) {
        const ConfigResult result = Parse(std::string(kProgramHead) + ending);
        EXPECT_TRUE(result.config.has_value())
                << ending << Errors(std::string(kProgramHead) + ending);
    }
}

TEST_F(VariantConfigTest, AxisValueBecomesUpperCaseDefine) {
    Axis axis{"REFLECTION", {"planar", "cubeMap"}, {}};
    EXPECT_EQ(axis.DefineFor("planar"), "REFLECTION_PLANAR");
    EXPECT_EQ(axis.DefineFor("cubeMap"), "REFLECTION_CUBEMAP");
}

TEST_F(VariantConfigTest, AxisDefaultValueBecomesNoDefine) {
    Axis axis{"REFLECTION", {"planar", "cubemap", "fourier"}, SourceLocation{}, "planar"};
    EXPECT_EQ(axis.DefineFor("planar"), "");
    EXPECT_EQ(axis.DefineFor("cubemap"), "REFLECTION_CUBEMAP");
    EXPECT_EQ(axis.DefineFor("fourier"), "REFLECTION_FOURIER");
}

TEST_F(VariantConfigTest, AxisMapFormLoadsValuesAndDefaultAndListsNoDefineForTheDefault) {
    const std::string yaml = std::string(kProgramHead) +
                             "    features: [ENABLE_FOG]\n"
                             "    axes:\n"
                             "      QUALITY: [low, high]\n"
                             "      REFLECTION: { values: [planar, cubemap, fourier], default: "
                             "planar }\n"
                             "      MODE: { values: [fast, exact] }\n"
                             "    rules:\n"
                             "      - { if: REFLECTION_FOURIER, requires: ENABLE_FOG }\n";
    const ConfigResult result = Parse(yaml);
    ASSERT_TRUE(result.config.has_value()) << Errors(yaml);
    EXPECT_TRUE(result.diagnostics.empty());
    const ProgramConfig& p = result.config->programs.at(0);
    ASSERT_EQ(p.axes.size(), 3U);
    EXPECT_EQ(p.axes[0].default_value, "");
    const Axis& reflection = p.axes[1];
    EXPECT_EQ(reflection.name, "REFLECTION");
    EXPECT_EQ(reflection.values, (std::vector<std::string>{"planar", "cubemap", "fourier"}));
    EXPECT_EQ(reflection.default_value, "planar");
    EXPECT_EQ(reflection.where.line, 8);
    EXPECT_EQ(reflection.where.column, 7);
    // The map form without `default:` is the list form: every value adds a define.
    EXPECT_EQ(p.axes[2].values, (std::vector<std::string>{"fast", "exact"}));
    EXPECT_EQ(p.axes[2].default_value, "");
    EXPECT_EQ(p.AllDefines(), (std::vector<std::string>{"ENABLE_FOG", "QUALITY_LOW", "QUALITY_HIGH",
                                                        "REFLECTION_CUBEMAP", "REFLECTION_FOURIER",
                                                        "MODE_FAST", "MODE_EXACT"}));
}

// Adding an axis with a default to a program keeps the ids of the variants it had before.
TEST_F(VariantConfigTest, AxisWithDefaultKeepsTheIdsOfExistingVariants) {
    const std::string before = std::string(kProgramHead) + "    features: [ENABLE_FOG]\n";
    const std::string after =
            before +
            "    axes:\n"
            "      REFLECTION: { values: [planar, cubemap, fourier], default: planar }\n";
    const ConfigResult old_config = Parse(before);
    const ConfigResult new_config = Parse(after);
    ASSERT_TRUE(old_config.config.has_value());
    ASSERT_TRUE(new_config.config.has_value());
    EXPECT_EQ(CountCombinations(new_config.config->programs.at(0)), 6U);
    const ExpansionResult old_variants = ExpandVariants(*old_config.config, ExpansionOptions{});
    const ExpansionResult new_variants = ExpandVariants(*new_config.config, ExpansionOptions{});
    std::vector<std::string> old_ids;
    for (const Variant& v : old_variants.variants) {
        old_ids.push_back(v.Id());
    }
    std::vector<std::string> new_ids;
    for (const Variant& v : new_variants.variants) {
        new_ids.push_back(v.Id());
    }
    EXPECT_EQ(old_ids, (std::vector<std::string>{"p:", "p:ENABLE_FOG"}));
    EXPECT_EQ(new_ids,
              (std::vector<std::string>{"p:", "p:ENABLE_FOG", "p:ENABLE_FOG,REFLECTION_CUBEMAP",
                                        "p:ENABLE_FOG,REFLECTION_FOURIER", "p:REFLECTION_CUBEMAP",
                                        "p:REFLECTION_FOURIER"}));
}

TEST_F(VariantConfigTest, PresetThatChoosesNoValueOfAnAxisWithDefaultGetsTheDefault) {
    const ConfigResult result =
            Parse(std::string(kProgramHead) +
                  "    features: [ENABLE_FOG]\n"
                  "    axes:\n"
                  "      REFLECTION: { values: [planar, cubemap, fourier], default: planar }\n"
                  "presets:\n"
                  "  planar: { program: p, defines: [ENABLE_FOG] }\n"
                  "  cube: { program: p, defines: [ENABLE_FOG, REFLECTION_CUBEMAP] }\n");
    ASSERT_TRUE(result.config.has_value());
    EXPECT_TRUE(result.diagnostics.empty());
    const Preset* planar = result.config->FindPreset("planar");
    ASSERT_NE(planar, nullptr);
    EXPECT_EQ(MakeVariant(planar->program, planar->defines).Id(), "p:ENABLE_FOG");
}

TEST_F(VariantConfigTest, TargetsAcceptOptionalEs300) {
    const ConfigResult result = Parse("targets: [100, 300]\n" + std::string(kProgramHead));
    ASSERT_TRUE(result.config.has_value());
    EXPECT_EQ(result.config->targets,
              (std::vector<GlslTarget>{GlslTarget::kEs100, GlslTarget::kEs300}));
}

TEST_F(VariantConfigTest, TargetsAcceptWebGl1AndWebGl2) {
    const ConfigResult result =
            Parse("targets: [100, webgl1, webgl2]\n" + std::string(kProgramHead));
    ASSERT_TRUE(result.config.has_value());
    EXPECT_EQ(result.config->targets,
              (std::vector<GlslTarget>{GlslTarget::kEs100, GlslTarget::kWebGl1,
                                       GlslTarget::kWebGl2}));
    EXPECT_EQ(TargetName(GlslTarget::kWebGl1), "webgl1");
    EXPECT_EQ(TargetVersion(GlslTarget::kWebGl1), 100);
    EXPECT_EQ(VersionDirective(GlslTarget::kWebGl2), "#version 300 es");
}

TEST_F(VariantConfigTest, AWebGlTargetAloneStillNeedsTarget100) {
    const ConfigResult result = Parse("targets: [webgl1]\n" + std::string(kProgramHead));
    EXPECT_FALSE(result.config.has_value());
}

TEST(VariantConfigDefineNameTest, AcceptsIdentifiersAndRejectsReservedOrMalformedNames) {
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

class VariantConfigBadInputTest : public VariantConfigTest,
                                  public ::testing::WithParamInterface<BadInputCase> {};

TEST_P(VariantConfigBadInputTest, IsRejectedWithExactDiagnostic) {
    const ConfigResult result = Parse(GetParam().yaml);
    EXPECT_FALSE(result.config.has_value());
    EXPECT_EQ(Errors(GetParam().yaml), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
        Cases, VariantConfigBadInputTest,
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
                             std::string(kProgramHead) + "    features: [A]\n"
                                                         "    rules:\n"
                                                         "      - { if: A, requires: B }\n",
                             "v.yaml:7:9: error: rule names unknown feature 'B' in program 'p'; "
                             "known: A\n"},
                BadInputCase{"FeatureDeclaredTwice",
                             std::string(kProgramHead) + "    features: [A, B, A]\n",
                             "v.yaml:5:22: error: feature 'A' is declared twice in program 'p'; "
                             "remove one\n"},
                BadInputCase{"DuplicateMapKey", std::string(kProgramHead) + "    vertex: s.vsh\n",
                             "v.yaml:5:5: error: duplicate key 'vertex' (first written at line "
                             "3); remove one of them\n"},
                // yaml-cpp reads the first document alone: the second was dropped unread.
                BadInputCase{"SecondDocument", std::string(kProgramHead) + "---\nmax_variants: 4\n",
                             "v.yaml:6:1: error: a second YAML document starts here, after a "
                             "'---' line, and tidepool reads only the first: move its keys into "
                             "the first document and remove the '---'\n"},
                BadInputCase{"SecondDocumentAfterAnchors",
                             "x: &a 1\n" + std::string(kProgramHead) + "---\ny: &b 2\n",
                             "v.yaml:7:1: error: a second YAML document starts here, after a "
                             "'---' line, and tidepool reads only the first: move its keys into "
                             "the first document and remove the '---'\n"},
                BadInputCase{"InvalidDefineName",
                             std::string(kProgramHead) + "    features: [ENABLE-FOG]\n",
                             "v.yaml:5:16: error: 'ENABLE-FOG' is not a valid GLSL define name: "
                             "use letters, digits and _, start with a letter, no 'GL_' prefix "
                             "and no '__'\n"},
                BadInputCase{"PresetBreaksRule",
                             std::string(kProgramHead) + "    features: [A, B]\n"
                                                         "    rules: [{ if: B, requires: A }]\n"
                                                         "presets:\n"
                                                         "  bad: { program: p, defines: [B] }\n",
                             "v.yaml:8:3: error: preset 'bad' breaks rule 'B requires A' (line "
                             "6); change its defines\n"},
                BadInputCase{"MalformedRule",
                             std::string(kProgramHead) + "    features: [A, B]\n"
                                                         "    rules: [{ if: A }]\n",
                             "v.yaml:6:13: error: a rule is either `{if: A, requires: [B]}`, "
                             "`{if: A, excludes: [B]}` or `{exclude: [A, B]}`\n"},
                BadInputCase{"AxisMapWithUnknownKey",
                             std::string(kProgramHead) +
                                     "    axes:\n"
                                     "      REFLECTION: { values: [planar, cubemap], defualt: "
                                     "planar }\n",
                             "v.yaml:6:48: error: unknown key 'defualt' in axis 'REFLECTION'; "
                             "allowed keys: values, default\n"},
                BadInputCase{"AxisMapWithoutValues",
                             std::string(kProgramHead) + "    axes:\n"
                                                         "      REFLECTION: { default: planar }\n",
                             "v.yaml:6:7: error: axis 'REFLECTION' has no 'values'; write "
                             "`REFLECTION: { values: [a, b], default: a }`\n"},
                BadInputCase{"AxisDefaultIsNotOneOfItsValues",
                             std::string(kProgramHead) +
                                     "    axes:\n"
                                     "      REFLECTION: { values: [planar, cubemap], default: "
                                     "fourier }\n",
                             "v.yaml:6:57: error: the default 'fourier' of axis 'REFLECTION' is "
                             "not one of its values: planar, cubemap\n"},
                BadInputCase{"AxisMapWithOneValue",
                             std::string(kProgramHead) +
                                     "    axes:\n"
                                     "      REFLECTION: { values: [planar], default: planar }\n",
                             "v.yaml:6:7: error: axis 'REFLECTION' needs at least two values (a "
                             "single value is a feature that is always on)\n"},
                BadInputCase{"AxisListWithOneValue",
                             std::string(kProgramHead) + "    axes:\n"
                                                         "      QUALITY: [low]\n",
                             "v.yaml:6:7: error: axis 'QUALITY' needs at least two values (a "
                             "single value is a feature that is always on)\n"},
                BadInputCase{"RuleNamesTheDefineOfAnAxisDefault",
                             std::string(kProgramHead) +
                                     "    features: [A]\n"
                                     "    axes:\n"
                                     "      REFLECTION: { values: [planar, cubemap], default: "
                                     "planar }\n"
                                     "    rules:\n"
                                     "      - { if: A, requires: REFLECTION_PLANAR }\n",
                             "v.yaml:9:9: error: 'REFLECTION_PLANAR' is the default of axis "
                             "'REFLECTION' and adds no define; leave it out (a preset) or write "
                             "the rule over the other values\n"},
                BadInputCase{"PresetNamesTheDefineOfAnAxisDefault",
                             std::string(kProgramHead) +
                                     "    axes:\n"
                                     "      REFLECTION: { values: [planar, cubemap], default: "
                                     "planar }\n"
                                     "presets:\n"
                                     "  bad: { program: p, defines: [REFLECTION_PLANAR] }\n",
                             "v.yaml:8:3: error: 'REFLECTION_PLANAR' is the default of axis "
                             "'REFLECTION' and adds no define; leave it out (a preset) or write "
                             "the rule over the other values\n"},
                BadInputCase{"PresetChoosesTwoValuesOfAnAxisWithDefault",
                             std::string(kProgramHead) +
                                     "    axes:\n"
                                     "      REFLECTION: { values: [planar, cubemap, fourier], "
                                     "default: planar }\n"
                                     "presets:\n"
                                     "  bad: { program: p, defines: [REFLECTION_CUBEMAP, "
                                     "REFLECTION_FOURIER] }\n",
                             "v.yaml:8:3: error: preset 'bad' must choose at most one value of "
                             "axis 'REFLECTION' (it chose 2); choosing none means its default "
                             "'planar'\n"},
                BadInputCase{"PresetChoosesNoValueOfAnAxisWithoutDefault",
                             std::string(kProgramHead) + "    features: [A]\n"
                                                         "    axes:\n"
                                                         "      QUALITY: [low, high]\n"
                                                         "presets:\n"
                                                         "  bad: { program: p, defines: [A] }\n",
                             "v.yaml:9:3: error: preset 'bad' must choose exactly one value of "
                             "axis 'QUALITY' (it chose 0)\n"},
                BadInputCase{"TopLevelIsNotAMapping", "- programs\n",
                             "v.yaml:1:1: error: the top level must be a mapping with keys such "
                             "as `programs:`\n"},
                BadInputCase{"UnsupportedSchemaVersion", "version: 2\n" + std::string(kProgramHead),
                             "v.yaml:1:10: error: unsupported schema version 2; this tidepool "
                             "reads version 1\n"},
                BadInputCase{"VersionIsNotAnInteger", "version: one\n" + std::string(kProgramHead),
                             "v.yaml:1:10: error: version must be an integer\n"},
                BadInputCase{"NoProgramsSection", "targets: [100]\n",
                             "v.yaml:1:1: error: no `programs:` section; declare at least one "
                             "program with its vertex and fragment files\n"},
                BadInputCase{"ProgramsIsEmpty", "programs: {}\n",
                             "v.yaml:1:11: error: `programs:` is empty; declare at least one "
                             "program\n"},
                BadInputCase{"ProgramsIsNotAMapping", "programs: [p]\n",
                             "v.yaml:1:11: error: programs must be a mapping of keys to values\n"},
                BadInputCase{"ProgramNameIsNotAnIdentifier",
                             "programs:\n  my-water:\n    vertex: s.vsh\n    fragment: s.fsh\n",
                             "v.yaml:2:3: error: program name 'my-water' must be an identifier "
                             "(letters, digits, _)\n"},
                BadInputCase{"ProgramWithoutAFragmentShader",
                             "programs:\n  p:\n    vertex: s.vsh\n",
                             "v.yaml:2:3: error: program 'p' has no 'fragment' shader file; add "
                             "`fragment: shaders/FILE`\n"},
                BadInputCase{"ShaderPathIsAList",
                             "programs:\n  p:\n    vertex: [s.vsh]\n    fragment: s.fsh\n",
                             "v.yaml:3:13: error: program 'p' 'vertex' must be a single value, "
                             "not a list or mapping\n"},
                // yaml-cpp marks an empty value where the next token starts (here line 4, or
                // past the end of the file); the error belongs on the key's line.
                BadInputCase{"ShaderPathLeftEmptyBeforeAnotherKey",
                             "programs:\n  p:\n    vertex:\n    fragment: s.fsh\n",
                             "v.yaml:3:5: error: program 'p' 'vertex' has no value; write one "
                             "after its ':'\n"},
                BadInputCase{"ShaderPathLeftEmptyAtTheEndOfTheFile",
                             "programs:\n  p:\n    vertex: s.vsh\n    fragment:",
                             "v.yaml:4:5: error: program 'p' 'fragment' has no value; write one "
                             "after its ':'\n"},
                BadInputCase{"ProgramsLeftEmpty", "programs:\n",
                             "v.yaml:1:1: error: programs has no value; give it a mapping of keys "
                             "to values\n"},
                BadInputCase{"FeaturesAreNotAList", std::string(kProgramHead) + "    features: A\n",
                             "v.yaml:5:15: error: features must be a list of define names\n"},
                BadInputCase{
                        "AxisListsAValueTwice",
                        std::string(kProgramHead) + "    axes:\n      MODE: [fast, fast, exact]\n",
                        "v.yaml:6:13: error: axis 'MODE' lists value 'fast' twice\n"},
                BadInputCase{"RulesAreNotAList",
                             std::string(kProgramHead) +
                                     "    features: [A, B]\n    rules: { if: A, requires: B }\n",
                             "v.yaml:6:12: error: rules must be a list\n"},
                BadInputCase{"ExcludeCombinationOfOneDefine",
                             std::string(kProgramHead) +
                                     "    features: [A]\n    rules: [{ exclude: [A] }]\n",
                             "v.yaml:6:13: error: an `exclude:` combination needs at least two "
                             "defines; to forbid one define, remove it from the features\n"},
                BadInputCase{
                        "PresetWithoutProgram",
                        std::string(kProgramHead) + "presets:\n  x: { description: no program }\n",
                        "v.yaml:6:3: error: preset 'x' has no 'program'\n"},
                BadInputCase{"PresetNamesUnknownProgram",
                             std::string(kProgramHead) + "presets:\n  x: { program: q }\n",
                             "v.yaml:6:3: error: preset 'x' names unknown program 'q'; the "
                             "programs are p\n"},
                // Before, an empty name passed, and `render --preset x` said both "uses program
                // ''" and "unknown preset 'x'".
                BadInputCase{
                        "RuleExcludingItsOwnSubject",
                        std::string(kProgramHead) +
                                "    features: [A, B]\n    rules: [{ if: A, excludes: [B, A] }]\n",
                        "v.yaml:6:13: error: a rule names 'A' both in `if` and in "
                        "`excludes`, so it prunes every variant with it, as if it were not a "
                        "feature; name other defines there\n"},
                BadInputCase{"EmptyShaderPath",
                             "programs:\n  p:\n    vertex: ''\n    fragment: s.fsh\n",
                             "v.yaml:3:13: error: program 'p' 'vertex' is empty; give the shader "
                             "file's path, e.g. `vertex: shaders/FILE`\n"},
                BadInputCase{"PresetNamesAnEmptyProgram",
                             std::string(kProgramHead) + "presets:\n  x: { program: '' }\n",
                             "v.yaml:6:17: error: preset 'x' names no program: give the name of "
                             "one\n"},
                // The axis's defines start with its name: '' made "_A" of value a.
                BadInputCase{"AxisWithAnEmptyName",
                             std::string(kProgramHead) + "    axes:\n      '': [a, b]\n",
                             "v.yaml:6:7: error: an axis is named by an identifier (letters, "
                             "digits and '_', not starting with a digit), not ''\n"},
                BadInputCase{"AxisNamedByAList",
                             std::string(kProgramHead) + "    axes:\n      ? [x]\n      : [a, b]\n",
                             "v.yaml:6:9: error: an axis is named by an identifier (letters, "
                             "digits and '_', not starting with a digit), not a list or a "
                             "mapping\n"},
                // "300" and "300es" are one target: every variant was validated twice.
                BadInputCase{"TargetTwiceByTwoSpellings",
                             "targets: [100, 300, 300es]\n" + std::string(kProgramHead),
                             "v.yaml:1:10: error: targets names the target '300es' twice, by two "
                             "of its spellings; list it once\n"},
                BadInputCase{
                        "PresetUsesUnknownDefine",
                        std::string(kProgramHead) +
                                "    features: [A]\npresets:\n  x: { program: p, defines: [B] }\n",
                        "v.yaml:7:3: error: preset 'x' uses unknown define 'B' of program "
                        "'p'; known: A\n"},
                // The renderer dropped a runtime feature it did not know without a word, and a
                // name listed twice or a preset named "" or "bad name!" went through.
                BadInputCase{"PresetSwitchesOnAnUndeclaredRuntimeFeature",
                             std::string(kProgramHead) +
                                     "    features: [A]\npresets:\n  x: { program: p, "
                                     "runtime_features: [A, NOPE] }\n",
                             "v.yaml:7:3: error: preset 'x' switches on 'NOPE' in "
                             "runtime_features, which no program declares; runtime features are "
                             "the defines of the programs: A\n"},
                BadInputCase{"NameListedTwice",
                             std::string(kProgramHead) +
                                     "    features: [A, B]\npresets:\n  x: { program: p, "
                                     "defines: [B, A, B] }\n",
                             "v.yaml:7:36: error: 'B' is named twice in defines; remove one\n"},
                BadInputCase{"PresetNameIsNoIdentifier",
                             std::string(kProgramHead) +
                                     "    features: [A]\npresets:\n  \"bad name\": { program: p "
                                     "}\n",
                             "v.yaml:7:3: error: preset name 'bad name' must be an identifier "
                             "(letters, digits, _)\n"},
                BadInputCase{"PresetDefinesAreNotNames",
                             std::string(kProgramHead) + "    features: [A]\npresets:\n  x: { "
                                                         "program: p, defines: { A: 1 } }\n",
                             "v.yaml:7:29: error: defines must be a name or a list of names\n"},
                BadInputCase{
                        "RuntimeFeatureIsNotAName",
                        std::string(kProgramHead) +
                                "presets:\n  x: { program: p, runtime_features: [half-res] }\n",
                        "v.yaml:6:38: error: 'half-res' is not a valid feature name in "
                        "runtime_features\n"},
                BadInputCase{"PassesAreNotAMapping",
                             std::string(kProgramHead) +
                                     "presets:\n  x: { program: p, passes: [clip] }\n",
                             "v.yaml:6:28: error: passes must be a mapping of keys to values\n"},
                BadInputCase{
                        "PassSizeIsNotAPowerOfTwo",
                        std::string(kProgramHead) +
                                "presets:\n  x: { program: p, passes: { reflection_size: 300 } }\n",
                        "v.yaml:6:47: error: reflection_size must be a power of two from 1 "
                        "to 4096\n"},
                BadInputCase{
                        "PassSizeIsNotAnInteger",
                        std::string(kProgramHead) +
                                "presets:\n  x: { program: p, passes: { refraction_size: big } }\n",
                        "v.yaml:6:47: error: refraction_size must be an integer\n"},
                BadInputCase{
                        "PassSwitchIsNotTrueOrFalse",
                        std::string(kProgramHead) +
                                "presets:\n  x: { program: p, passes: { low_res_water: maybe } }\n",
                        "v.yaml:6:45: error: low_res_water must be true or false\n"},
                BadInputCase{"ClipIsNeitherObliqueNorDiscard",
                             std::string(kProgramHead) +
                                     "presets:\n  x: { program: p, passes: { clip: sideways } }\n",
                             "v.yaml:6:36: error: clip must be 'oblique' or 'discard', not "
                             "'sideways'\n"},
                BadInputCase{
                        "DesktopOnlyTargets", "targets: [330]\n" + std::string(kProgramHead),
                        "v.yaml:1:10: error: unknown GLSL ES target '330'; use 100, 300, webgl1 or "
                        "webgl2\n"
                        "v.yaml:1:10: error: targets must include 100 (GLSL ES 1.00 is the "
                        "shaders' own language)\n"}),
        [](const ::testing::TestParamInfo<BadInputCase>& case_info) {
            return case_info.param.name;
        });

TEST_F(VariantConfigTest, MaxVariantsOutOfRangeOrNotAWholeNumberIsRefusedAtItsLine) {
    for (const char* value : {"2147483647", "-1", "0", "18446744073709551616", "1e3", "16777217"}) {
        EXPECT_EQ(Errors("max_variants: " + std::string(value) + "\n" + kProgramHead),
                  "v.yaml:1:15: error: max_variants must be a whole number from 1 to 16777216 "
                  "(valid variants; above 65536 only with --allow-large-matrix), not '" +
                          std::string(value) + "'\n");
    }
}

TEST_F(VariantConfigTest, MaxVariantsAboveTheCeilingLoadsWithItsPlaceForExpansionToJudge) {
    const ConfigResult result = Parse("max_variants: 100000\n" + std::string(kProgramHead));
    ASSERT_TRUE(result.config.has_value()) << Errors("max_variants: 100000\n");
    EXPECT_EQ(result.config->max_variants, 100000U);
    EXPECT_EQ(result.config->max_variants_where.line, 1);
    EXPECT_EQ(result.config->max_variants_where.column, 15);
}

TEST_F(VariantConfigTest, MissingShaderFileNamesThePathAndWhereItWasLookedFor) {
    const std::string errors =
            Errors("programs:\n  p:\n    vertex: nope.vsh\n    fragment: s.fsh\n");
    EXPECT_EQ(errors, "v.yaml:3:13: error: vertex shader file 'nope.vsh' not found (looked for " +
                              (dir_.Path() / "nope.vsh").string() +
                              "); paths are relative to the folder of v.yaml\n");
}

TEST_F(VariantConfigTest, ShaderPathThatIsAFolderSaysSo) {
    std::filesystem::create_directories(dir_.Path() / "d.vsh");
    EXPECT_EQ(Errors("programs:\n  p:\n    vertex: d.vsh\n    fragment: s.fsh\n"),
              "v.yaml:3:13: error: vertex shader file 'd.vsh' is a folder (" +
                      (dir_.Path() / "d.vsh").string() + "), not a file\n");
}

TEST_F(VariantConfigTest, ShaderPathThatIsAFifoSaysSoWithoutOpeningIt) {
    ASSERT_EQ(::mkfifo((dir_.Path() / "pipe.fsh").c_str(), 0600), 0);
    EXPECT_EQ(Errors("programs:\n  p:\n    vertex: s.vsh\n    fragment: pipe.fsh\n"),
              "v.yaml:4:15: error: fragment shader file 'pipe.fsh' is not a regular file (" +
                      (dir_.Path() / "pipe.fsh").string() +
                      "); a FIFO or device cannot be validated\n");
}

// Before, a loop of links was reported as "not found".
TEST_F(VariantConfigTest, ShaderPathThatIsALoopOfLinksSaysSo) {
    std::filesystem::create_symlink("b.fsh", dir_.Path() / "a.fsh");
    std::filesystem::create_symlink("a.fsh", dir_.Path() / "b.fsh");
    EXPECT_EQ(Errors("programs:\n  p:\n    vertex: s.vsh\n    fragment: a.fsh\n"),
              "v.yaml:4:15: error: fragment shader file 'a.fsh' cannot be read (" +
                      (dir_.Path() / "a.fsh").string() + "): Too many levels of symbolic links\n");
}

TEST_F(VariantConfigTest, UnreadableFileIsAnErrorNamingIt) {
    const ConfigResult result = LoadVariantConfig(dir_.Path() / "missing.yaml");
    ASSERT_EQ(result.diagnostics.size(), 1U);
    EXPECT_EQ(FormatDiagnostic(result.diagnostics[0]),
              (dir_.Path() / "missing.yaml").string() +
                      ": error: cannot read the configuration file: no such file; check the path "
                      "or pass "
                      "--config PATH");
}

TEST(VariantConfigShippedFileTest, ShippedVariantsYamlLoadsWithTheWhitepaperPresets) {
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
