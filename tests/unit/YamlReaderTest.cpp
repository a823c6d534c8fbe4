// The shared YAML reading layer, through both loaders that use it: hostile documents are refused
// with a position instead of crashing, hanging or reaching the JSON writers.
#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "TempDir.h"
#include "YamlReader.h"
namespace tidepool {
namespace {

using testing::TempDir;

std::string FormattedLines(const std::vector<Diagnostic>& diagnostics) {
    std::string out;
    for (const Diagnostic& d : diagnostics) {
        out += FormatDiagnostic(d) + "\n";
    }
    return out;
}

std::string ConfigErrors(const std::string& yaml) {
    const ConfigResult result = ParseVariantConfig(yaml, "v.yaml", ".");
    EXPECT_FALSE(result.config.has_value());
    return FormattedLines(result.diagnostics);
}

std::string SceneErrors(const std::string& yaml) {
    const SceneResult result = ParseSceneDescription(yaml, "s.yaml");
    EXPECT_FALSE(result.scene.has_value());
    return FormattedLines(result.diagnostics);
}

// 9 levels of 10 aliases each: 865 bytes that expand to a billion nodes.
std::string BillionLaughs() {
    std::string yaml = "a: &a [x, x, x, x, x, x, x, x, x, x]\n";
    for (char level = 'b'; level <= 'i'; ++level) {
        const std::string previous(1, static_cast<char>(level - 1));
        yaml += std::string(1, level) + ": &" + level + " [";
        for (int i = 0; i < 10; ++i) {
            yaml += (i == 0 ? "*" : ", *") + previous;
        }
        yaml += "]\n";
    }
    return yaml;
}

TEST(YamlReaderTest, AliasInsideItsOwnAnchorIsACycleErrorAtTheAlias) {
    EXPECT_EQ(ConfigErrors("programs:\n  p:\n    features: &loop [A, *loop]\n"),
              "v.yaml:3:25: error: alias '*loop' refers to the node that contains it, a cycle; "
              "an alias may only repeat a node that is complete\n");
    EXPECT_EQ(SceneErrors("target: &t {min_psnr_db: 30, again: *t}\n"),
              "s.yaml:1:37: error: alias '*t' refers to the node that contains it, a cycle; an "
              "alias may only repeat a node that is complete\n");
}

TEST(YamlReaderTest, AliasBombIsRefusedQuicklyAtTheAliasThatExceedsTheBound) {
    const auto start = std::chrono::steady_clock::now();
    const std::string errors = ConfigErrors(BillionLaughs());
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
    EXPECT_EQ(errors,
              "v.yaml:5:36: error: the document expands through its aliases to more "
              "than 100000 nodes; write the repeated parts out or use fewer nested "
              "aliases\n");
    EXPECT_EQ(SceneErrors(BillionLaughs()),
              "s.yaml:5:36: error: the document expands through its aliases to more than 100000 "
              "nodes; write the repeated parts out or use fewer nested aliases\n");
}

TEST(YamlReaderTest, AliasesOfCompleteNodesStillWork) {
    const SceneResult result = ParseSceneDescription(
            "water: &w {depth: 3}\ntarget: {min_psnr_db: 30}\ndescription: &d calm\n", "s.yaml");
    EXPECT_TRUE(result.scene.has_value()) << FormattedLines(result.diagnostics);
}

TEST(YamlReaderTest, NonUtf8ByteIsAnErrorAtItsLineAndColumn) {
    // Latin-1 'e acute' (0xE9) inside a preset description, after a two-byte UTF-8 character.
    EXPECT_EQ(ConfigErrors("programs: {}\npresets:\n  p: {description: \"\xC3\xA9t\xE9\"}\n"),
              "v.yaml:3:23: error: this byte is not UTF-8; YAML files are Unicode text: save "
              "the file as UTF-8\n");
    EXPECT_EQ(SceneErrors("description: caf\xE9\n"),
              "s.yaml:1:17: error: this byte is not UTF-8; YAML files are Unicode text: save the "
              "file as UTF-8\n");
}

TEST(YamlReaderTest, OverlongAndSurrogateEncodingsAreNotUtf8) {
    EXPECT_EQ(SceneErrors("a: \xC0\xAF\n"),
              "s.yaml:1:4: error: this byte is not UTF-8; YAML files are Unicode text: save the "
              "file as UTF-8\n");
    EXPECT_EQ(SceneErrors("a: \xED\xA0\x80\n"),
              "s.yaml:1:4: error: this byte is not UTF-8; YAML files are Unicode text: save the "
              "file as UTF-8\n");
}

TEST(YamlReaderTest, RepeatedKeyInAnAliasedMappingIsReportedOnce) {
    const ConfigResult result =
            ParseVariantConfig("x: &m {a: 1, a: 2}\ny: *m\nz: *m\nprograms: {}\n", "v.yaml", ".");
    EXPECT_EQ(FormattedLines(result.diagnostics).find("duplicate key 'a'"),
              FormattedLines(result.diagnostics).rfind("duplicate key 'a'"));
    EXPECT_NE(FormattedLines(result.diagnostics)
                      .find("v.yaml:1:14: error: duplicate key 'a' (first "
                            "written at line 1)"),
              std::string::npos);
}

// What YamlReader::Load says about `yaml`: whether it gave a node, then its diagnostics.
std::string LoadFindings(const std::string& yaml) {
    YamlReader reader("d.yaml");
    const bool loaded = reader.Load(yaml).has_value();
    return (loaded ? "loaded\n" : "refused\n") + FormattedLines(reader.Diagnostics());
}

// A document with no anchor is read in one parse and checked on its tree; one with an anchor
// through the event pass. Both must find the same: the document, then with an unused anchor
// added at its end (which moves nothing).
TEST(YamlReaderTest, DocumentWithoutAnchorsGetsTheSameFindingsAsTheEventCheck) {
    std::string long_list = "a: 1\nb: [";
    for (std::uint64_t i = 0; i <= kMaxYamlExpandedNodes; ++i) {
        long_list += "x, ";
    }
    long_list += "y]\nc: {d: 1, d: 2}\n";
    const std::vector<std::string> documents = {
            "a: 1\nb:\n  c: 2\n  c: 3\n  ~: x\n  : y\n  null: z\nd: [{e: 1, e: 2}, {f: 1}]\n"
            "? [g, {h: 1, h: 2}]\n: {i: 1, i: 2}\na: 4\n'a': 5\n",
            "programs:\n  p:\n    vertex: a.vsh\n    vertex: b.vsh\n",
            "- 1\n- {k: v, k: w}\n",
            long_list,
            "a: 1\n!!str a: 2\nb: !x [1]\n",
    };
    for (const std::string& yaml : documents) {
        SCOPED_TRACE(yaml.substr(0, 80));
        const std::string one_parse = LoadFindings(yaml);
        EXPECT_EQ(one_parse,
                  LoadFindings(yaml + (yaml[0] == '-' ? "- &unused 1\n" : "zz: &unused 1\n")))
                << "the tree check and the event check disagree";
        EXPECT_NE(one_parse.find(yaml == long_list ? "refused\nd.yaml:2:" : "duplicate key"),
                  std::string::npos)
                << one_parse;
    }
}

// yaml-cpp keeps a node's tag and ignores it when the node is read as a value: before tags were
// refused, `max_variants: !!str 16` was read as 16 and `!include` took the file name as text.
TEST(YamlReaderTest, ATaggedNodeIsRefusedAtItsTagWhileQuotingStillWorks) {
    const std::string program = "programs:\n  p:\n    vertex: a.vsh\n    fragment: a.fsh\n";
    EXPECT_EQ(ConfigErrors("max_variants: !!str 16\n" + program),
              "v.yaml:1:15: error: the YAML tag '!!str' would be ignored: tidepool reads each "
              "value by its key's type, and its files use no tags; remove it (to keep a value as "
              "text, quote it)\n");
    EXPECT_EQ(SceneErrors("water: !include other.yaml\n").substr(0, 40),
              "s.yaml:1:8: error: the YAML tag '!includ");
    // On a mapping, in an anchored document (the event pass), only the first is reported.
    const std::string anchored = "a: &x 1\nb: !<tag:example.com,2026:m> {c: 1}\nd: !!seq []\n";
    EXPECT_EQ(LoadFindings(anchored).substr(0, 64),
              "refused\nd.yaml:2:4: error: the YAML tag 'tag:example.com,2026:m'");
    EXPECT_EQ(LoadFindings(anchored).find("!!seq"), std::string::npos);
    // Quoted text and the non-specific `!` (which means text, as quotes do) are no tags.
    EXPECT_EQ(LoadFindings("a: \"16\"\nb: ! 16\nc: 'x'\nd: ~\ne: plain\n"), "loaded\n");
}

// yaml-cpp's own words were "unknown escape character" for a NUL byte and "bad file" for deep
// nesting; a long list without an alias was said to expand "through its aliases".
TEST(YamlReaderTest, NulByteDeepNestingAndAWrittenOutHugeListSayWhatTheyAre) {
    std::string nul = "description: \"\xC3\xA9t\xC3\xA9\"\nwater: 1";
    nul += '\0';
    nul += "\n";
    EXPECT_EQ(SceneErrors(nul),
              "s.yaml:2:9: error: a NUL byte, which YAML text may not hold: remove it (a file "
              "saved as UTF-16 has one in every other byte; save it as UTF-8)\n");
    const std::string flow = "programs: " + std::string(3000, '[') + std::string(3000, ']');
    // At the 500th '[' (column 11 + 499), not where yaml-cpp's scanner had read to (6011).
    EXPECT_EQ(ConfigErrors(flow).substr(0, 28), "v.yaml:1:510: error: the YAM");
    // A quoted '[' and one in a comment open nothing.
    EXPECT_EQ(ConfigErrors("a: \"[[\" # [[\nprograms: " + std::string(600, '[') +
                           std::string(600, ']'))
                      .substr(0, 13),
              "v.yaml:2:510:");
    std::string block = "programs:\n";
    for (int i = 1; i <= 1000; ++i) {
        block += std::string(2 * static_cast<std::size_t>(i), ' ') + "a:\n";
    }
    for (const std::string& yaml : {flow, block, "x: &x 1\n" + block}) {
        const std::string errors = ConfigErrors(yaml);
        EXPECT_NE(errors.find(" levels deep here, past what yaml-cpp reads, where a "
                              "configuration needs a few: look for an unclosed '[' or '{', or "
                              "indentation that keeps growing\n"),
                  std::string::npos)
                << errors;
    }
    std::string list = "programs: {}\nx:\n";
    for (std::uint64_t i = 0; i <= kMaxYamlExpandedNodes; ++i) {
        list += "  - 1\n";
    }
    EXPECT_EQ(ConfigErrors(list),
              "v.yaml:99998:5: error: the document holds more than 100000 nodes, where a "
              "configuration has a few hundred; check that this is the file meant\n");
}

// Found by the fuzzers in CI (2026-12-07): yaml-cpp's YAML::LoadAll, used for a while to find a
// second document, never ends on these texts (each further document reads as an empty one).
TEST(YamlReaderTest, TextsOnWhichYamlCppsLoadAllNeverEndsAreReadInTime) {
    const std::string scene =
            "# A\x17murky, shallothing below the surfqce can be seer# A high aerial view straight "
            "down onto the water off the island: the view angle barely\n"
            "# changes over the watera:\n"
            "  height: 60\n"
            " , so the Fresnel mix is almost constant. Schema: docs/SCENES.n: 1\n"
            "description: High aerial view looking steeply down o distance: 45n the water\n"
            "water:\n"
            "  depth: 20\n"
            "  fog_\n";
    const std::string config =
            "# tidepool's default variant matrix: the water, skybox and model shaders of the "
            "PowerVR\n"
            ", \"variants.yaml\".\n"
            "version: 1\n"
            "targets: [100]        # GLSL ES 1.00 (add 300 to validate every varian  tsa3.00 too)\n"
            "max_variants: 32768   # valid variants after pruning, all programs together (163 "
            "today)\n"
            "\n"
            "programs:\n"
            "  water:\n"
            "    description: The water plane; each feature is a #define code path.\n"
            "    vertex: shaders/water.vsh\n"
            "    fragment: shaders/water.fsh\n"
            "    features:\n"
            "      - ENABLE_DISTORTION     1   # two animated bump layers perturb the screen-space "
            "lookup\n"
            "      - ENABLE_SCALE_DISTORTION  # distortion divided by the eye distance\n"
            "      - ENABLE_REFRACTION        # refraction pass mixed with the reflection by a "
            "constant\n"
            "      - ENABLE_FRESNEL           # Schlick FrePnel mix instead of the constant\n"
            "      - FRESNEL_EXACT            # # tidepool's default varifuant matrix:ll die thel";
    const auto start = std::chrono::steady_clock::now();
    const SceneResult read_scene = ParseSceneDescription(scene, "s.yaml");
    const ConfigResult read_config = ParseVariantConfig(config, "v.yaml", ".");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
    EXPECT_FALSE(read_scene.scene.has_value());
    EXPECT_FALSE(read_config.config.has_value());
    EXPECT_FALSE(read_scene.diagnostics.empty());
    EXPECT_FALSE(read_config.diagnostics.empty());
}

TEST(YamlReaderTest, ConfigPathThatIsAFolderSaysSo) {
    TempDir dir;
    const ConfigResult result = LoadVariantConfig(dir.Path());
    EXPECT_EQ(FormattedLines(result.diagnostics),
              dir.Path().string() +
                      ": error: cannot read the configuration file: is a folder, "
                      "not a file; check the path or pass --config PATH\n");
    const SceneResult scene = LoadSceneDescription(dir.Path());
    EXPECT_EQ(FormattedLines(scene.diagnostics),
              dir.Path().string() +
                      ": error: cannot read the scene file: is a folder, not a "
                      "file; scenes live in scenes/NAME.yaml next to the "
                      "configuration\n");
}

}  // namespace
}  // namespace tidepool
