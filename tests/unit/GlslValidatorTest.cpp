#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/base/CacheBundle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "NestedStructs.h"
#include "TempDir.h"

namespace tidepool {
namespace {

using testing::TempDir;

constexpr const char* kVertex =
        "#version 100\n"
        "attribute highp vec4 inVertex;\n"
        "varying mediump vec2 uv;\n"
        "void main() {\n"
        "    uv = inVertex.xy;\n"
        "    gl_Position = inVertex;\n"
        "}\n";

// ENABLE_FOG is tested only here, so the vertex program must be shared across it.
constexpr const char* kFragment =
        "#version 100\n"
        "precision mediump float;\n"
        "varying mediump vec2 uv;\n"
        "uniform lowp vec3 FogColour;\n"
        "void main() {\n"
        "    vec3 colour = vec3(uv, 0.5);\n"
        "#ifdef ENABLE_FOG\n"
        "    colour = mix(colour, FogColour, 0.5);\n"
        "#endif\n"
        "    gl_FragColor = vec4(colour, 1.0);\n"
        "}\n";

VariantConfig ConfigIn(const TempDir& dir, const std::string& vertex_name,
                       const std::string& fragment_name, std::vector<std::string> features) {
    VariantConfig config;
    config.path = "v.yaml";
    config.base_dir = dir.Path();
    config.targets = {GlslTarget::kEs100};
    ProgramConfig program;
    program.name = "p";
    program.vertex_path = vertex_name;
    program.fragment_path = fragment_name;
    for (std::string& f : features) {
        program.features.push_back(Feature{std::move(f), {}});
    }
    config.programs.push_back(program);
    return config;
}

ValidationReport ValidateAll(const VariantConfig& config, int jobs = 1,
                             base::ContentCache* cache = nullptr) {
    const ExpansionResult expansion = ExpandVariants(config, ExpansionOptions{config.max_variants});
    ValidationOptions options;
    options.jobs = jobs;
    options.targets = config.targets;
    options.cache = cache;
    return ValidateVariants(config, expansion.variants, options);
}

std::vector<std::string> FormattedEach(const std::vector<Diagnostic>& diagnostics) {
    std::vector<std::string> out;
    for (const Diagnostic& d : diagnostics) {
        out.push_back(FormatDiagnostic(d));
    }
    return out;
}

TEST(GlslValidatorTest, DefineOnlyTheFragmentTestsSharesOneVertexProgram) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    dir.Write("a.fsh", kFragment);
    const ValidationReport report = ValidateAll(ConfigIn(dir, "a.vsh", "a.fsh", {"ENABLE_FOG"}));
    ASSERT_EQ(report.verdicts.size(), 2U);
    EXPECT_TRUE(report.verdicts[0].valid);
    EXPECT_TRUE(report.verdicts[1].valid);
    EXPECT_EQ(report.verdicts[0].vertex_hash, report.verdicts[1].vertex_hash);
    EXPECT_NE(report.verdicts[0].fragment_hash, report.verdicts[1].fragment_hash);
    EXPECT_EQ(report.stage_slots, 4);
    EXPECT_EQ(report.stage_programs.size(), 3U);  // one vertex, two fragment
    EXPECT_EQ(report.SharedStageSlots(), 1);
    EXPECT_EQ(report.links, 2);
}

TEST(GlslValidatorTest, DefineNoStageTestsSharesBothStages) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    dir.Write("a.fsh", kFragment);
    const ValidationReport report = ValidateAll(ConfigIn(dir, "a.vsh", "a.fsh", {"UNUSED"}));
    ASSERT_EQ(report.verdicts.size(), 2U);
    EXPECT_EQ(report.stage_programs.size(), 2U);
    EXPECT_EQ(report.links, 1);
}

TEST(GlslValidatorTest, ErrorInDefineGatedBlockIsReportedAtTheUsersLineWithVariantId) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    std::string broken = kFragment;
    broken.replace(broken.find("FogColour, 0.5"), 9, "FogColor ");  // line 8
    dir.Write("a.fsh", broken);
    const ValidationReport report = ValidateAll(ConfigIn(dir, "a.vsh", "a.fsh", {"ENABLE_FOG"}));
    ASSERT_EQ(report.verdicts.size(), 2U);
    EXPECT_TRUE(report.verdicts[0].valid);  // p: (the block is inactive)
    EXPECT_FALSE(report.verdicts[1].valid);
    EXPECT_EQ(FormattedEach(report.verdicts[1].diagnostics),
              std::vector<std::string>{
                      "a.fsh:8:26: error: 'FogColor' : undeclared identifier [p:ENABLE_FOG]"});
}

TEST(GlslValidatorTest, VerdictsAlreadyKnownAreReusedAndOnlyTheMissingAreValidated) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    dir.Write("a.fsh", kFragment);
    const VariantConfig config = ConfigIn(dir, "a.vsh", "a.fsh", {"ENABLE_FOG"});
    const ExpansionResult expansion = ExpandVariants(config, ExpansionOptions{config.max_variants});
    ASSERT_EQ(expansion.variants.size(), 2U);
    // A known verdict unlike what glslang would say, so that reuse shows.
    ValidationReport known;
    VariantVerdict marked;
    marked.variant = expansion.variants[0];
    marked.target = GlslTarget::kEs100;
    marked.valid = false;
    marked.vertex_hash = "known";
    known.verdicts.push_back(marked);
    const ValidationReport report =
            ValidateVariants(config, expansion.variants, ValidationOptions{}, known);
    ASSERT_EQ(report.verdicts.size(), 2U);
    EXPECT_EQ(report.verdicts[0].variant, expansion.variants[0]);
    EXPECT_EQ(report.verdicts[0].vertex_hash, "known");
    EXPECT_FALSE(report.verdicts[0].valid);
    EXPECT_EQ(report.verdicts[1].variant, expansion.variants[1]);
    EXPECT_TRUE(report.verdicts[1].valid);
    EXPECT_EQ(report.stage_slots, 2);  // only the missing variant's two stages were validated
    EXPECT_EQ(report.links, 1);
    ASSERT_NE(report.Find(expansion.variants[1], GlslTarget::kEs100), nullptr);
    EXPECT_EQ(report.Find(expansion.variants[1], GlslTarget::kEs300), nullptr);
}

TEST(GlslValidatorTest, ValidationWithSeveralJobsGivesTheSameVerdicts) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    dir.Write("a.fsh", kFragment);
    const VariantConfig config = ConfigIn(dir, "a.vsh", "a.fsh", {"ENABLE_FOG", "X", "Y"});
    const ValidationReport one = ValidateAll(config, 1);
    const ValidationReport four = ValidateAll(config, 4);
    ASSERT_EQ(one.verdicts.size(), four.verdicts.size());
    for (std::size_t i = 0; i < one.verdicts.size(); ++i) {
        EXPECT_EQ(one.verdicts[i].variant.Id(), four.verdicts[i].variant.Id());
        EXPECT_EQ(one.verdicts[i].fragment_hash, four.verdicts[i].fragment_hash);
        EXPECT_EQ(one.verdicts[i].valid, four.verdicts[i].valid);
    }
}

// Everything a report says about its variants, as text, to compare two reports whole (without
// `costs`, all but the stage programs' costs).
std::vector<std::string> Described(const ValidationReport& report, bool costs = true) {
    std::vector<std::string> lines{"slots " + std::to_string(report.stage_slots) + " programs " +
                                   std::to_string(report.stage_programs.size()) + " links " +
                                   std::to_string(report.links)};
    for (const VariantVerdict& verdict : report.verdicts) {
        lines.push_back(verdict.variant.Id() + (verdict.valid ? " valid " : " invalid ") +
                        verdict.vertex_hash + " " + verdict.fragment_hash);
        for (const std::string& d : FormattedEach(verdict.diagnostics)) {
            lines.push_back(d);
        }
    }
    for (const StageProgram& program : report.stage_programs) {
        lines.push_back(program.file + " " + program.hash +
                        (program.valid ? " valid " : " invalid ") +
                        (costs ? ToJson(program.cost).dump() : ""));
    }
    return lines;
}

// A matrix with a stage error in one variant, a link error in another and valid ones: every
// kind of result the cache keeps.
VariantConfig MixedConfig(const TempDir& dir) {
    dir.Write("m.vsh",
              "#version 100\nuniform highp float k;\nattribute vec4 p;\n"
              "void main() { gl_Position = p * k; }\n");
    // MISMATCH: k's precision differs from the vertex stage's (a link error); BROKEN: an
    // undeclared name at line 7 (a stage error).
    dir.Write("m.fsh",
              "#version 100\nprecision mediump float;\n#ifdef MISMATCH\nuniform mediump float k;\n"
              "#endif\n#ifdef BROKEN\nfloat b = oops;\n#endif\n"
              "void main() {\n  gl_FragColor = vec4(1.0);\n#ifdef MISMATCH\n  gl_FragColor *= k;\n"
              "#endif\n}\n");
    return ConfigIn(dir, "m.vsh", "m.fsh", {"BROKEN", "MISMATCH"});
}

TEST(GlslValidatorTest, CacheHitGivesTheSameReportAsAMiss) {
    TempDir dir;
    const VariantConfig config = MixedConfig(dir);
    const ValidationReport uncached = ValidateAll(config);
    base::ContentCache cache(dir.Path() / "cache");
    const ValidationReport cold = ValidateAll(config, 2, &cache);
    const base::ContentCacheStats after_cold = cache.Stats();
    EXPECT_EQ(after_cold.hits, 0U);
    EXPECT_GT(after_cold.stored, 0U);
    const ValidationReport warm = ValidateAll(config, 2, &cache);
    const base::ContentCacheStats after_warm = cache.Stats();
    EXPECT_EQ(after_warm.misses, after_cold.misses) << "the warm run missed";
    EXPECT_EQ(after_warm.stored, after_cold.stored) << "the warm run stored";
    EXPECT_GT(after_warm.hits, 0U);
    EXPECT_EQ(Described(cold), Described(uncached));
    EXPECT_EQ(Described(warm), Described(uncached));
    // The mixed matrix really has each kind: a stage error and a link error.
    EXPECT_EQ(uncached.InvalidCount(), 3);
}

TEST(GlslValidatorTest, WarmUpTheCallerStartedGivesTheSameReport) {
    TempDir dir;
    VariantConfig config = MixedConfig(dir);
    config.targets = {GlslTarget::kEs100, GlslTarget::kEs300};
    const ValidationReport own = ValidateAll(config, 2);
    // The caller's warm-up covers 1.00 only: validation warms 3.00 itself before it forks.
    GlslangWarmUp warm_up({GlslTarget::kEs100});
    const ExpansionResult expansion = ExpandVariants(config, ExpansionOptions{config.max_variants});
    ValidationOptions options;
    options.jobs = 2;
    options.targets = config.targets;
    options.warm_up = &warm_up;
    const ValidationReport given = ValidateVariants(config, expansion.variants, options);
    EXPECT_EQ(Described(given), Described(own));
    EXPECT_EQ(given.verdicts.size(), 8U);  // 4 variants, 2 targets
    EXPECT_EQ(warm_up.Finish(), std::vector<GlslTarget>{GlslTarget::kEs100});  // idempotent
}

ValidationReport ValidateWithoutCosts(const VariantConfig& config,
                                      base::ContentCache* cache = nullptr) {
    const ExpansionResult expansion = ExpandVariants(config, ExpansionOptions{config.max_variants});
    ValidationOptions options;
    options.jobs = 2;
    options.targets = config.targets;
    options.cache = cache;
    options.static_costs = false;
    return ValidateVariants(config, expansion.variants, options);
}

TEST(GlslValidatorTest, ValidationWithoutCostsGivesTheSameVerdictsAndNoCosts) {
    TempDir dir;
    const VariantConfig config = MixedConfig(dir);
    const ValidationReport with = ValidateAll(config, 2);
    const ValidationReport without = ValidateWithoutCosts(config);
    EXPECT_EQ(Described(without, false), Described(with, false));
    int costed = 0;
    for (std::size_t i = 0; i < with.stage_programs.size(); ++i) {
        costed += with.stage_programs[i].cost.TotalOps() > 0 ? 1 : 0;
        EXPECT_EQ(without.stage_programs[i].cost.TotalOps(), 0) << i;
    }
    EXPECT_GT(costed, 0);  // so the check above can fail
}

TEST(GlslValidatorTest, CachedStageWithoutCostDoesNotAnswerAValidationThatWantsOne) {
    TempDir dir;
    const VariantConfig config = MixedConfig(dir);
    const ValidationReport uncached = ValidateAll(config, 2);
    base::ContentCache cache(dir.Path() / "cache");
    static_cast<void>(ValidateWithoutCosts(config, &cache));
    const std::uint64_t stored_without = cache.Stats().stored;
    // The stages are parsed again for their costs, and their entries replaced.
    const ValidationReport with = ValidateAll(config, 2, &cache);
    EXPECT_EQ(Described(with), Described(uncached));
    EXPECT_GT(cache.Stats().stored, stored_without);
    // Entries with a cost answer a validation that wants none: nothing is stored again.
    const std::uint64_t stored_with = cache.Stats().stored;
    const ValidationReport again = ValidateWithoutCosts(config, &cache);
    EXPECT_EQ(Described(again, false), Described(uncached, false));
    EXPECT_EQ(cache.Stats().stored, stored_with);
}

TEST(GlslValidatorTest, CorruptCacheEntryIsIgnoredAndRewritten) {
    TempDir dir;
    const VariantConfig config = MixedConfig(dir);
    base::ContentCache cache(dir.Path() / "cache");
    const ValidationReport cold = ValidateAll(config, 1, &cache);
    std::vector<std::filesystem::path> entries;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.Path() / "cache")) {
        if (entry.is_regular_file()) {
            entries.push_back(entry.path());
        }
    }
    ASSERT_FALSE(entries.empty());
    for (const std::filesystem::path& path : entries) {
        // The same length, one byte of the payload changed: only the checksum can tell.
        std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
        file.seekp(-1, std::ios::end);
        file.put('\x7f');
    }
    base::ContentCache reopened(dir.Path() / "cache");
    const ValidationReport damaged = ValidateAll(config, 1, &reopened);
    // Every stage entry is read and found corrupt; link entries are not even read, since their
    // stages are recomputed, and are rewritten all the same.
    EXPECT_GT(reopened.Stats().corrupt, 0U);
    EXPECT_EQ(reopened.Stats().hits, 0U);
    EXPECT_EQ(Described(damaged), Described(cold));
    base::ContentCache again(dir.Path() / "cache");
    const ValidationReport rewritten = ValidateAll(config, 1, &again);
    EXPECT_EQ(again.Stats().corrupt, 0U);
    EXPECT_EQ(again.Stats().misses, 0U);
    EXPECT_EQ(Described(rewritten), Described(cold));
}

TEST(GlslValidatorTest, CachedResultThatDoesNotDecodeIsIgnoredAndRewritten) {
    TempDir dir;
    const VariantConfig config = MixedConfig(dir);
    const std::filesystem::path folder = dir.Path() / "cache";
    base::ContentCache cache(folder);
    const ValidationReport cold = ValidateAll(config, 1, &cache);
    // Every stage and link result of the bundle loses its second half, and the bundle is stored
    // again: its checksum is right, so only the results' own reading can tell. (What the first
    // halves would give, read leniently, is not what the run found: a link without its verdict,
    // stages without their diagnostics or costs.)
    std::size_t cut = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        const std::string key = entry.path().filename().string();
        const auto payload = entry.is_regular_file() ? cache.Load(key) : std::nullopt;
        if (auto bundle = payload ? base::CacheBundle::Decode(*payload) : std::nullopt) {
            for (auto& [result_key, result] : *bundle) {
                result.resize(result.size() / 2);
                ++cut;
            }
            cache.Store(key, base::CacheBundle::Encode(*bundle));
        }
    }
    ASSERT_GT(cut, 4U);  // 2 vertex and fragment programs at least, and links
    base::ContentCache reopened(folder);
    const ValidationReport damaged = ValidateAll(config, 1, &reopened);
    EXPECT_EQ(reopened.Stats().corrupt, 0U);
    EXPECT_EQ(Described(damaged), Described(cold));
    base::ContentCache again(folder);
    const ValidationReport rewritten = ValidateAll(config, 1, &again);
    EXPECT_EQ(again.Stats().misses, 0U);
    EXPECT_EQ(Described(rewritten), Described(cold));
}

// The results a run kept: every entry of the bundle the cache folder holds.
std::size_t BundledResults(const std::filesystem::path& folder) {
    base::ContentCache cache(folder);
    std::size_t most = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) {
            if (const auto payload = cache.Load(entry.path().filename().string())) {
                if (const auto bundle = base::CacheBundle::Decode(*payload)) {
                    most = std::max(most, bundle->size());
                }
            }
        }
    }
    return most;
}

TEST(GlslValidatorTest, DefineNamedOnlyInACommentDoesNotSplitPreprocessingButCodeAfterOneDoes) {
    TempDir dir;
    // FOO appears in the vertex stage only in comments; in the fragment stage BAR is used on
    // the line a block comment ends on and FOO after a line comment's line.
    dir.Write("c.vsh",
              "#version 100\n// FOO: nothing here\n/* FOO\n FOO */\nattribute vec4 p;\n"
              "void main() { gl_Position = p; }\n");
    dir.Write("c.fsh",
              "#version 100\nprecision mediump float; // FOO\n/* FOO */ float f() {\n"
              "#ifdef FOO\n  return oops;\n#endif\n  return 1.0;\n}\n"
              "void main() { gl_FragColor = vec4(f()); }\n");
    const VariantConfig config = ConfigIn(dir, "c.vsh", "c.fsh", {"FOO"});
    base::ContentCache cache(dir.Path() / "cache");
    const ValidationReport report = ValidateAll(config, 1, &cache);
    EXPECT_EQ(Described(report), Described(ValidateAll(config)));
    EXPECT_EQ(report.InvalidCount(), 1) << "FOO in the fragment stage's code was missed";
    // One vertex group (FOO only in its comments), two fragment groups and the one link of the
    // variant whose stages are valid; a vertex group per variant would make it five.
    EXPECT_EQ(BundledResults(dir.Path() / "cache"), 4U);
}

TEST(GlslValidatorTest, EditedShaderMissesTheCacheAndIsValidatedAgain) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    dir.Write("a.fsh", kFragment);
    const VariantConfig config = ConfigIn(dir, "a.vsh", "a.fsh", {"ENABLE_FOG"});
    base::ContentCache cache(dir.Path() / "cache");
    ASSERT_EQ(ValidateAll(config, 1, &cache).InvalidCount(), 0);
    std::string broken = kFragment;
    broken.replace(broken.find("FogColour, 0.5"), 9, "FogColor ");
    dir.Write("a.fsh", broken);
    const ValidationReport edited = ValidateAll(config, 1, &cache);
    EXPECT_EQ(Described(edited), Described(ValidateAll(config)));
    EXPECT_EQ(edited.InvalidCount(), 1);
}

TEST(GlslValidatorTest, InterfaceMismatchIsCaughtOnlyAtLinkTime) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    // Same uniform, different precision in the two stages: each stage alone is valid.
    dir.Write("u.vsh",
              "#version 100\nuniform highp float k;\nattribute vec4 p;\n"
              "void main() { gl_Position = p * k; }\n");
    dir.Write("u.fsh",
              "#version 100\nprecision mediump float;\nuniform mediump float k;\n"
              "void main() { gl_FragColor = vec4(k); }\n");
    const ValidationReport report = ValidateAll(ConfigIn(dir, "u.vsh", "u.fsh", {}));
    ASSERT_EQ(report.verdicts.size(), 1U);
    EXPECT_TRUE(report.stage_programs[0].valid);
    EXPECT_TRUE(report.stage_programs[1].valid);
    EXPECT_FALSE(report.verdicts[0].valid);
    ASSERT_FALSE(report.verdicts[0].diagnostics.empty());
    // At the fragment stage's declaration, in one message.
    const Diagnostic& first = report.verdicts[0].diagnostics[0];
    EXPECT_EQ(std::filesystem::path(first.file).filename(), "u.fsh");
    EXPECT_EQ(first.line, 3);
    EXPECT_EQ(first.column, 23);
    EXPECT_EQ(first.message.rfind("uniform 'k' is mediump here but highp in the vertex shader", 0),
              0U)
            << first.message;
}

// The verdicts' names ("a.vert+b.frag") and validity, in order, with the folder left out.
std::string LinkedAs(const ValidationReport& report, const std::string& folder) {
    std::string out;
    for (const VariantVerdict& v : report.verdicts) {
        std::string name = v.variant.program;
        for (std::size_t at; (at = name.find(folder)) != std::string::npos;) {
            name.erase(at, folder.size());
        }
        out += name + (v.valid ? " valid\n" : " INVALID\n");
    }
    return out;
}

// A vertex file given with several fragment files is linked with each (before, each file was
// checked alone, and a fragment stage the vertex stage cannot feed was called valid); with several
// of both, the files of the same name pair up, and the rest are linked alone.
TEST(GlslValidatorTest, FilesAreLinkedWithTheFilesOfTheOtherStageTheyGoWith) {
    TempDir dir;
    auto vertex = [](const char* type) {
        return std::string("#version 100\nattribute vec4 p;\nvarying ") + type +
               " uv;\nvoid main() { uv = " + type + "(0.5); gl_Position = p; }\n";
    };
    auto fragment = [](const char* type) {
        return std::string("#version 100\nprecision mediump float;\nvarying ") + type +
               " uv;\nvoid main() { gl_FragColor = vec4(uv.x); }\n";
    };
    dir.Write("a.vert", vertex("vec2"));
    dir.Write("b.frag", fragment("vec2"));
    dir.Write("c.frag", fragment("vec3"));
    dir.Write("c.vert", vertex("vec3"));
    const std::string folder = dir.Path().string() + "/";
    auto file = [&](const char* name, Stage stage) { return ShaderFile{folder + name, stage}; };
    EXPECT_EQ(LinkedAs(ValidateShaderFiles(
                               {file("a.vert", Stage::kVertex), file("b.frag", Stage::kFragment),
                                file("c.frag", Stage::kFragment)},
                               {}),
                       folder),
              "a.vert+b.frag valid\na.vert+c.frag INVALID\n");
    EXPECT_EQ(LinkedAs(ValidateShaderFiles(
                               {file("a.vert", Stage::kVertex), file("c.vert", Stage::kVertex),
                                file("b.frag", Stage::kFragment), file("c.frag", Stage::kFragment)},
                               {}),
                       folder),
              "c.vert+c.frag valid\na.vert valid\nb.frag valid\n");
}

TEST(GlslValidatorTest, RecursionInOneStageIsACompileErrorOfThatStage) {
    TempDir dir;
    dir.Write("r.frag",
              "#version 100\nprecision mediump float;\nfloat g(float x);\n"
              "float f(float x) { return g(x); }\nfloat g(float x) { return f(x); }\n"
              "void main() { gl_FragColor = vec4(f(1.0)); }\n");
    const ValidationReport report = ValidateShaderFiles(
            {ShaderFile{(dir.Path() / "r.frag").string(), Stage::kFragment}}, {});
    ASSERT_EQ(report.verdicts.size(), 1U);
    // GLSL ES 1.00 §6.1: glslang 12 reports it only when linking; tidepool when compiling.
    EXPECT_FALSE(report.stage_programs[0].valid);
    EXPECT_FALSE(report.verdicts[0].valid);
    ASSERT_FALSE(report.verdicts[0].diagnostics.empty());
    EXPECT_NE(report.verdicts[0].diagnostics[0].message.find("is called recursively"),
              std::string::npos);
}

TEST(GlslValidatorTest, DesktopVersionIsAnErrorAtLineOne) {
    TempDir dir;
    const std::string path = dir.Write("d.frag", "#version 330\nvoid main() {}\n").string();
    const ValidationReport report = ValidateShaderFiles({ShaderFile{path, Stage::kFragment}}, {});
    ASSERT_EQ(report.verdicts.size(), 1U);
    EXPECT_FALSE(report.verdicts[0].valid);
    EXPECT_EQ(FormattedEach(report.verdicts[0].diagnostics),
              std::vector<std::string>{path + ":1:1: error: '#version 330' is desktop GLSL; "
                                              "tidepool validates GLSL ES: use '#version 100' or "
                                              "'#version 300 es'"});
}

TEST(GlslValidatorTest, DesktopVersionAfterACommentIsAnErrorAtItsLine) {
    // Comments may come before #version (GLSL ES 1.00 and 3.00 §3.4), and glslang then takes a
    // desktop version as desktop GLSL and accepts the shader; a #version 100 there stays valid.
    TempDir dir;
    const std::string desktop = dir.Write("d.vert",
                                          "// licence\n#version 120\nattribute vec4 p;\n"
                                          "void main() { gl_Position = p; }\n")
                                        .string();
    const ValidationReport refused = ValidateShaderFiles({ShaderFile{desktop, Stage::kVertex}}, {});
    ASSERT_EQ(refused.verdicts.size(), 1U);
    EXPECT_EQ(FormattedEach(refused.verdicts[0].diagnostics),
              std::vector<std::string>{desktop + ":2:1: error: '#version 120' is desktop GLSL; "
                                                 "tidepool validates GLSL ES: use '#version 100' "
                                                 "or '#version 300 es'"});
    const std::string es100 = dir.Write("e.vert",
                                        "/* licence */\n#version 100\nattribute vec4 p;\n"
                                        "void main() { gl_Position = p; }\n")
                                      .string();
    const ValidationReport accepted = ValidateShaderFiles({ShaderFile{es100, Stage::kVertex}}, {});
    ASSERT_EQ(accepted.verdicts.size(), 1U);
    EXPECT_TRUE(accepted.verdicts[0].valid);
}

TEST(GlslValidatorTest, PlainVertexAndFragmentFilesAreLinkedTogether) {
    TempDir dir;
    const std::string vs = dir.Write("a.vert", kVertex).string();
    // The fragment reads a varying the vertex stage declares with another type.
    const std::string fs = dir.Write("a.frag",
                                     "#version 100\nprecision mediump float;\n"
                                     "varying mediump vec3 uv;\n"
                                     "void main() { gl_FragColor = vec4(uv, 1.0); }\n")
                                   .string();
    const ValidationReport report = ValidateShaderFiles(
            {ShaderFile{vs, Stage::kVertex}, ShaderFile{fs, Stage::kFragment}}, {});
    ASSERT_EQ(report.verdicts.size(), 1U);
    EXPECT_FALSE(report.verdicts[0].valid);
    EXPECT_EQ(report.links, 1);
}

// Described, with each step's status, which plain files report on their own (a link not run).
std::vector<std::string> DescribedWithSteps(const ValidationReport& report) {
    std::vector<std::string> lines = Described(report);
    for (const VariantVerdict& verdict : report.verdicts) {
        for (const auto& [name, step] : verdict.NamedSteps()) {
            lines.push_back(std::string(name) + " " + StepStatusName(step->status) + " " +
                            std::to_string(step->diagnostics.size()));
        }
    }
    return lines;
}

// Plain files of each kind the cache keeps: a valid pair, a pair with a link error, a pair with
// a stage error (no link) and three files validated one by one.
std::vector<std::vector<ShaderFile>> PlainFileRuns(const TempDir& dir) {
    const std::string vs = dir.Write("p.vert", kVertex).string();
    const std::string fs = dir.Write("p.frag", kFragment).string();
    const std::string mismatch = dir.Write("m.frag",
                                           "#version 100\nprecision mediump float;\n"
                                           "varying mediump vec3 uv;\n"
                                           "void main() { gl_FragColor = vec4(uv, 1.0); }\n")
                                         .string();
    const std::string broken = dir.Write("b.frag",
                                         "#version 100\nprecision mediump float;\n"
                                         "void main() { gl_FragColor = vec4(oops); }\n")
                                       .string();
    return {{{vs, Stage::kVertex}, {fs, Stage::kFragment}},
            {{vs, Stage::kVertex}, {mismatch, Stage::kFragment}},
            {{vs, Stage::kVertex}, {broken, Stage::kFragment}},
            {{fs, Stage::kFragment}, {broken, Stage::kFragment}, {vs, Stage::kVertex}}};
}

TEST(GlslValidatorTest, PlainFileCacheHitGivesTheSameReportAsAMiss) {
    TempDir dir;
    base::ContentCache cache(dir.Path() / "cache");
    ShaderFileOptions cached;
    cached.cache = &cache;
    for (const std::vector<ShaderFile>& files : PlainFileRuns(dir)) {
        SCOPED_TRACE(files.back().path);
        const ValidationReport uncached = ValidateShaderFiles(files, {});
        const ValidationReport cold = ValidateShaderFiles(files, {}, cached);
        const base::ContentCacheStats after_cold = cache.Stats();
        EXPECT_GT(after_cold.stored, 0U);
        const ValidationReport warm = ValidateShaderFiles(files, {}, cached);
        const base::ContentCacheStats after_warm = cache.Stats();
        EXPECT_EQ(after_warm.misses, after_cold.misses) << "the warm run missed";
        EXPECT_EQ(after_warm.stored, after_cold.stored) << "the warm run stored";
        EXPECT_GT(after_warm.hits, after_cold.hits);
        EXPECT_EQ(DescribedWithSteps(cold), DescribedWithSteps(uncached));
        EXPECT_EQ(DescribedWithSteps(warm), DescribedWithSteps(uncached));
    }
    // The runs really have each kind of result.
    const std::vector<std::vector<ShaderFile>> runs = PlainFileRuns(dir);
    EXPECT_TRUE(ValidateShaderFiles(runs[0], {}).verdicts[0].valid);
    EXPECT_EQ(ValidateShaderFiles(runs[1], {}).verdicts[0].link.status, StepStatus::kInvalid);
    EXPECT_EQ(ValidateShaderFiles(runs[2], {}).verdicts[0].link.status, StepStatus::kNotRun);
}

TEST(GlslValidatorTest, PlainFileDefineValuesAndTargetsAreKeptApartInTheCache) {
    TempDir dir;
    // N=1 reaches an undeclared name; any other value does not. KEEP is never mentioned.
    const std::string path = dir.Write("n.frag",
                                       "#version 100\nprecision mediump float;\n"
                                       "void main() {\n#if N == 1\n  gl_FragColor = oops;\n"
                                       "#else\n  gl_FragColor = vec4(1.0);\n#endif\n}\n")
                                     .string();
    const std::vector<ShaderFile> files{{path, Stage::kFragment}};
    base::ContentCache cache(dir.Path() / "cache");
    ShaderFileOptions cached;
    cached.cache = &cache;
    ShaderFileOptions webgl = cached;
    webgl.target = GlslTarget::kWebGl1;
    for (int pass = 0; pass < 2; ++pass) {
        for (const std::vector<std::string>& defines : std::vector<std::vector<std::string>>{
                     {"N=1"}, {"N=2"}, {"N=1", "KEEP"}, {"N"}, {"N=2", "Z=/*"}, {"N=2", "Z=08"}}) {
            // Z is never mentioned either, but glslang refuses its value in the preamble.
            SCOPED_TRACE(defines.front());
            EXPECT_EQ(DescribedWithSteps(ValidateShaderFiles(files, defines, cached)),
                      DescribedWithSteps(ValidateShaderFiles(files, defines)));
        }
        // A while loop: GLSL ES 1.00 allows it, WebGL 1's Appendix A (glslang's limits, so
        // decided by glslang, not before it) does not.
        const std::string loop = dir.Write("w.frag",
                                           "#version 100\nprecision mediump float;\nvoid main() {\n"
                                           "  float x = 0.0;\n  while (x < 1.0) { x += 0.5; }\n"
                                           "  gl_FragColor = vec4(x);\n}\n")
                                         .string();
        const std::vector<ShaderFile> webgl_files{{loop, Stage::kFragment}};
        EXPECT_TRUE(ValidateShaderFiles(webgl_files, {}, cached).verdicts[0].valid);
        EXPECT_FALSE(ValidateShaderFiles(webgl_files, {}, webgl).verdicts[0].valid);
    }
    EXPECT_FALSE(ValidateShaderFiles(files, {"N=1"}, cached).verdicts[0].valid);
    EXPECT_TRUE(ValidateShaderFiles(files, {"N=2"}, cached).verdicts[0].valid);
    EXPECT_GT(cache.Stats().hits, 0U);
}

TEST(GlslValidatorTest, CorruptPlainFileCacheEntryIsIgnoredAndRewritten) {
    TempDir dir;
    const std::vector<ShaderFile> files = PlainFileRuns(dir)[1];
    base::ContentCache cache(dir.Path() / "cache");
    ShaderFileOptions cached;
    cached.cache = &cache;
    const ValidationReport cold = ValidateShaderFiles(files, {}, cached);
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.Path() / "cache")) {
        if (entry.is_regular_file()) {
            std::fstream file(entry.path(), std::ios::binary | std::ios::in | std::ios::out);
            file.seekp(-1, std::ios::end);
            file.put('\x7f');
        }
    }
    base::ContentCache reopened(dir.Path() / "cache");
    cached.cache = &reopened;
    const ValidationReport damaged = ValidateShaderFiles(files, {}, cached);
    EXPECT_GT(reopened.Stats().corrupt, 0U);
    EXPECT_EQ(reopened.Stats().hits, 0U);
    EXPECT_EQ(DescribedWithSteps(damaged), DescribedWithSteps(cold));
    base::ContentCache again(dir.Path() / "cache");
    cached.cache = &again;
    const ValidationReport rewritten = ValidateShaderFiles(files, {}, cached);
    EXPECT_EQ(again.Stats().corrupt, 0U);
    EXPECT_EQ(again.Stats().misses, 0U);
    EXPECT_EQ(DescribedWithSteps(rewritten), DescribedWithSteps(cold));
}

TEST(GlslValidatorTest, Es300TargetCompilesThe100SourceUnchangedAndKeepsLines) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    std::string broken = kFragment;
    broken.replace(broken.find("FogColour, 0.5"), 9, "FogColor ");
    dir.Write("a.fsh", broken);
    VariantConfig config = ConfigIn(dir, "a.vsh", "a.fsh", {"ENABLE_FOG"});
    config.targets = {GlslTarget::kEs100, GlslTarget::kEs300};
    const ValidationReport report = ValidateAll(config);
    ASSERT_EQ(report.verdicts.size(), 4U);
    EXPECT_TRUE(report.verdicts[2].valid)
            << (report.verdicts[2].diagnostics.empty() ? ""
                                                       : report.verdicts[2].diagnostics[0].message);
    EXPECT_EQ(report.verdicts[3].target, GlslTarget::kEs300);
    ASSERT_FALSE(report.verdicts[3].diagnostics.empty());
    EXPECT_EQ(report.verdicts[3].diagnostics[0].line, 8);
}

TEST(GlslValidatorTest, StageFromExtensionKnowsTheCommonSuffixes) {
    Stage stage = Stage::kFragment;
    EXPECT_TRUE(StageFromExtension("x/water.vsh", &stage));
    EXPECT_EQ(stage, Stage::kVertex);
    EXPECT_TRUE(StageFromExtension("a.frag", &stage));
    EXPECT_EQ(stage, Stage::kFragment);
    EXPECT_FALSE(StageFromExtension("a.glsl", &stage));
}

// ---- Hostile shaders (issue 15) -----------------------------------------------------------------

// A public conformance case that makes glslang 12 dereference a null pointer while expanding a
// macro; here only when CRASH is defined, so the other variant of the matrix stays valid.
constexpr const char* kCrashingFragment =
        "#version 100\n"
        "precision mediump float;\n"
        "#ifdef CRASH\n"
        "#define m(a)\n"
        "#define a m((a)\n"
        "a)\n"
        "#endif\n"
        "void main() { gl_FragColor = vec4(1.0); }\n";

// Validates kCrashingFragment, with `comment` after its #version line, with and without CRASH:
// the variant without it valid, the other an internal compiler error of `step`.
void ExpectCrashingVariantAlone(const std::string& comment, const std::string& step) {
    TempDir dir;
    dir.Write("a.vsh", kVertex);
    std::string fragment = kCrashingFragment;
    fragment.insert(fragment.find('\n') + 1, comment);
    dir.Write("a.fsh", fragment);
    const ValidationReport report = ValidateAll(ConfigIn(dir, "a.vsh", "a.fsh", {"CRASH"}), 2);
    ASSERT_EQ(report.verdicts.size(), 2U);
    EXPECT_TRUE(report.verdicts[0].valid) << FormattedEach(report.verdicts[0].diagnostics)[0];
    EXPECT_FALSE(report.verdicts[1].valid);
    ASSERT_EQ(report.verdicts[1].diagnostics.size(), 1U);
    const std::string message = FormatDiagnostic(report.verdicts[1].diagnostics[0]);
    // "(signal 11 ...)" in a plain build; under AddressSanitizer the worker reports the fault and
    // exits with a status instead.
    EXPECT_EQ(message.rfind("a.fsh: error: internal compiler error: glslang crashed (", 0), 0U)
            << message;
    EXPECT_NE(message.find("while " + step +
                           " this stage; the shader may be valid or not, and the run went on "
                           "without it [p:CRASH]"),
              std::string::npos)
            << message;
}

TEST(GlslValidatorTest, StageThatCrashesGlslangIsAnInternalErrorAndOtherVariantsAreValidated) {
    // The define walk groups this file's variants, so the crash comes in the stage's parse.
    ExpectCrashingVariantAlone("", "parsing");
}

TEST(GlslValidatorTest, StageThatCrashesGlslangsPreprocessorWhileGroupedIsAnInternalError) {
    // A `\` (even in a comment) keeps the define walk out of the file: its variants are grouped
    // by their preprocessed text, and the crash comes in that preprocessing.
    ExpectCrashingVariantAlone("// C:\\shaders\\a.fsh\n", "preprocessing");
}

// `#define M0 M1 M1` ... 40 levels deep: 2^40 tokens once expanded, used on line 43, column 3.
std::string MacroBomb() {
    std::string bomb = "#version 100\n";
    for (int level = 0; level < 40; ++level) {
        bomb += "#define M" + std::to_string(level) + " M" + std::to_string(level + 1) + " M" +
                std::to_string(level + 1) + "\n";
    }
    return bomb + "void main() {\n  M0;\n}\n";
}

// `#define M0 (M1+M1)` ... `#define M40 1`: 2^40 tokens once expanded, then `condition` on line
// 44 (an #if's expression, M0 at column 5 in `#if M0`).
std::string MacroBombInACondition(const std::string& condition) {
    std::string bomb = "#version 100\nprecision mediump float;\n";
    for (int level = 0; level < 40; ++level) {
        const std::string next = std::to_string(level + 1);
        bomb.append("#define M").append(std::to_string(level)).append(" (M").append(next);
        bomb.append("+M").append(next).append(")\n");
    }
    return bomb + "#define M40 1\n" + condition +
           "\n#endif\nvoid main() { gl_FragColor = vec4(1.0); }\n";
}

// Only what the preprocessor expands counts: the name `defined` asks about is not expanded.
TEST(GlslValidatorTest, AMacroBombNamedAfterDefinedIsNotExpanded) {
    TempDir dir;
    const std::string path =
            dir.Write("a.fsh", MacroBombInACondition("#if defined(M0) && defined M1")).string();
    const ValidationReport report = ValidateShaderFiles({{path, Stage::kFragment}}, {});
    ASSERT_EQ(report.verdicts.size(), 1U);
    EXPECT_TRUE(report.verdicts[0].valid);
}

std::string Repeated(const std::string& text, int times) {
    std::string all;
    for (int i = 0; i < times; ++i) {
        all += text;
    }
    return all;
}

// `#define F0(x) x x`, `#define F1(x) F0(F0(x))` ... 30 levels: 4^29 × 2 copies of the argument
// of F29, used on line 32, column 25 with its argument spread over two lines.
std::string FunctionLikeMacroBomb() {
    std::string bomb = "#version 100\n#define F0(x) x x\n";
    for (int level = 1; level < 30; ++level) {
        bomb += "#define F" + std::to_string(level) + "(x) F" + std::to_string(level - 1) + "(F" +
                std::to_string(level - 1) + "(x))\n";
    }
    return bomb + "void main() { float f = F29(\n1.0); }\n";
}

TEST(GlslValidatorTest, ByteOrderMarkIsAcceptedAndLinesStayRight) {
    TempDir dir;
    const std::string path = dir.Write("bom.vsh",
                                       "\xEF\xBB\xBF#version 100\nattribute vec4 p;\n"
                                       "void main() { gl_Position = oops; }\n")
                                     .string();
    const ValidationReport report = ValidateShaderFiles({{path, Stage::kVertex}}, {});
    ASSERT_EQ(report.verdicts.size(), 1U);
    ASSERT_FALSE(report.verdicts[0].diagnostics.empty());
    EXPECT_EQ(FormatDiagnostic(report.verdicts[0].diagnostics[0]),
              path + ":3:29: error: 'oops' : undeclared identifier");
}

struct PlainFileCase {
    const char* why;
    const char* vertex;
    std::string fragment;
    std::string expected;  // the first diagnostic, with the folder left out
};

class GlslValidatorPlainFileTest : public ::testing::TestWithParam<PlainFileCase> {};

TEST_P(GlslValidatorPlainFileTest, IsAnErrorAtTheRightPlace) {
    const PlainFileCase& c = GetParam();
    TempDir dir;
    std::vector<ShaderFile> files;
    if (c.vertex != nullptr) {
        files.push_back({dir.Write("a.vsh", c.vertex).string(), Stage::kVertex});
    }
    files.push_back({dir.Write("a.fsh", c.fragment).string(), Stage::kFragment});
    const ValidationReport report = ValidateShaderFiles(files, {});
    ASSERT_EQ(report.verdicts.size(), 1U) << c.why;
    EXPECT_FALSE(report.verdicts[0].valid) << c.why;
    ASSERT_FALSE(report.verdicts[0].diagnostics.empty()) << c.why;
    std::string message = FormatDiagnostic(report.verdicts[0].diagnostics[0]);
    const std::string folder = dir.Path().string() + "/";
    for (std::size_t at = message.find(folder); at != std::string::npos;
         at = message.find(folder)) {
        message.erase(at, folder.size());
    }
    EXPECT_EQ(message, c.expected) << c.why;
}

INSTANTIATE_TEST_SUITE_P(
        Table, GlslValidatorPlainFileTest,
        ::testing::Values(
                PlainFileCase{"NUL byte", nullptr,
                              std::string("#version 100\nprecision mediump float;\nvoid main() "
                                          "{ \0 }\n",
                                          56),
                              "a.fsh:3:15: error: NUL byte in the shader source; GLSL ES source "
                              "is text (GLSL ES §3.1) and glslang would stop reading here"},
                PlainFileCase{"uniform array larger than the stage's uniform vectors", nullptr,
                              "#version 100\nprecision mediump float;\nuniform vec4 big[17];\n"
                              "void main() { gl_FragColor = big[0]; }\n",
                              "a.fsh:3:14: error: uniform 'big' needs 17 uniform vectors, more "
                              "than the 16 a fragment shader has (gl_MaxFragmentUniformVectors; "
                              "GLSL ES 1.00 Appendix A §7, GLSL ES 3.00 §4.3.5)"},
                // Before, the count of vectors overflowed a long long (undefined behaviour),
                // and this uniform of 4 × 2^62 vectors passed as valid.
                PlainFileCase{"uniform whose vectors overflow a 64-bit count", nullptr,
                              "#version 100\nprecision mediump float;\n"
                              "struct S1 { vec4 a[2147483647]; };\n"
                              "struct S2 { S1 b[2147483647]; };\nstruct S3 { S2 c[4]; };\n"
                              "uniform S3 u;\nvoid main() { gl_FragColor = u.c[0].b[0].a[0]; }\n",
                              "a.fsh:6:12: error: uniform 'u' needs over 1099511627775 uniform "
                              "vectors, more than the 16 a fragment shader has "
                              "(gl_MaxFragmentUniformVectors; GLSL ES 1.00 Appendix A §7, "
                              "GLSL ES 3.00 §4.3.5)"},
                // Before, the count walked every member anew, 2^59 of them: past the 20 s limit.
                // Declared through a macro, out of the source guard's sight (below); unused, since
                // glslang's own walks of a member access are as slow.
                PlainFileCase{"59 structures, each holding the one before twice", nullptr,
                              "#version 100\nprecision mediump float;\n" +
                                      testing::DoublingStructsByMacro(59) +
                                      "uniform S59 u;\n"
                                      "void main() { gl_FragColor = vec4(1.0); }\n",
                              "a.fsh:63:13: error: uniform 'u' needs over 1099511627775 uniform "
                              "vectors, more than the 16 a fragment shader has "
                              "(gl_MaxFragmentUniformVectors; GLSL ES 1.00 Appendix A §7, "
                              "GLSL ES 3.00 §4.3.5)"},
                // Before, glslang walked it for 2^17 steps at every question about its type,
                // 2^40 for 40 levels: past the 20 s limit.
                PlainFileCase{"structures holding 2^17 members once expanded, refused before "
                              "glslang runs",
                              nullptr,
                              "#version 100\nprecision mediump float;\n" +
                                      testing::DoublingStructs(40) +
                                      "void main() {\n    S40 deep;\n"
                                      "    gl_FragColor = vec4(1.0);\n}\n",
                              "a.fsh:19:8: error: struct 'S17' holds more than 65536 members once "
                              "the structures in it are expanded, the most tidepool lets glslang "
                              "walk (glslang walks a structure's members anew for every question "
                              "it asks of a type); hold fewer structures in one another, or use "
                              "arrays"},
                PlainFileCase{"1.00 vertex with 3.00 fragment", kVertex,
                              "#version 300 es\nprecision mediump float;\nin vec2 uv;\nout vec4 "
                              "c;\nvoid main() { c = vec4(uv, 0.0, 1.0); }\n",
                              "a.fsh: error: cannot link a '#version 300 es' fragment shader "
                              "with the '#version 100' vertex shader a.vsh; both stages of a "
                              "program must use the same GLSL ES version (GLSL ES 3.00 §3.3)"},
                PlainFileCase{"varying the vertex stage never declares", kVertex,
                              "#version 100\nprecision mediump float;\nvarying mediump vec2 uv;\n"
                              "varying mediump vec3 normal;\nvoid main() { gl_FragColor = "
                              "vec4(normal, 1.0); }\n",
                              "a.fsh:5:35: error: 'normal' is read by the fragment shader but "
                              "the vertex shader a.vsh does not declare it; declare it there as a "
                              "varying (GLSL ES 1.00 §4.3.5, GLSL ES 3.00 §4.3.4)"},
                PlainFileCase{
                        "macro bomb, refused before glslang runs", nullptr, MacroBomb(),
                        "a.fsh:43:3: error: macro 'M0' expands to more than 131072 tokens "
                        "(a macro bomb); tidepool refuses shaders that large: write repeated code "
                        "as functions and loops rather than macros, or split the shader"},
                // Before, only code lines were measured: 40 levels in an #if ran glslang's
                // preprocessor past the 20 s limit.
                PlainFileCase{
                        "macro bomb in an #if, refused before glslang runs", nullptr,
                        MacroBombInACondition("#if M0"),
                        "a.fsh:44:5: error: macro 'M0' expands to more than 131072 tokens "
                        "(a macro bomb); tidepool refuses shaders that large: write repeated code "
                        "as functions and loops rather than macros, or split the shader"},
                PlainFileCase{
                        "100,000 nested invocations, refused without a stack overflow", nullptr,
                        "#version 100\n#define F(x) x\nvoid main() { float f = " +
                                Repeated("F(", 100000) + "1.0" + Repeated(")", 100000) + "; }\n",
                        "a.fsh:3:25: error: macro 'F' expands to more than 131072 "
                        "tokens (a macro bomb); tidepool refuses shaders that large: write "
                        "repeated code as functions and loops rather than macros, or split the "
                        "shader"},
                // Before, glslang's "'' :  memory exhausted" alone.
                PlainFileCase{"20,000 nested parentheses in an expression", nullptr,
                              "#version 300 es\nprecision mediump float;\nout vec4 c;\n"
                              "void main() {\n    float x = " +
                                      Repeated("(", 20000) + "1.0" + Repeated(")", 20000) +
                                      ";\n    c = vec4(x);\n}\n",
                              "a.fsh:5: error: an expression nests deeper than glslang's parser "
                              "can follow (its stack holds 10000 states, about one for each "
                              "open parenthesis; glslang says only 'memory exhausted'): write "
                              "it with fewer nested parentheses, or split it into several "
                              "statements"},
                PlainFileCase{"function-like macro bomb, refused before glslang runs", nullptr,
                              FunctionLikeMacroBomb(),
                              "a.fsh:32:25: error: macro 'F29' expands to more than 131072 "
                              "tokens (a macro bomb); tidepool refuses shaders that large: write "
                              "repeated code as functions and loops rather than macros, or "
                              "split the shader"},
                PlainFileCase{"uniform clash, at the fragment stage's declaration, in one message",
                              "#version 100\nuniform vec2 u;\nvoid main() { gl_Position = "
                              "vec4(u, 0.0, 1.0); }\n",
                              "#version 100\nprecision mediump float;\nuniform vec3 u;\nvoid "
                              "main() { gl_FragColor = vec4(u, 1.0); }\n",
                              "a.fsh:3:14: error: uniform 'u' is vec3 here but vec2 in the vertex "
                              "shader a.vsh; a uniform declared in both stages must match in type "
                              "and precision, members included (GLSL ES 1.00 §4.5.3, GLSL ES 3.00 "
                              "§4.3.5)"}));

// glslang's preprocessor evaluates an `#if` one call deeper for each parenthesis and unary
// operator: 60,000 of them crashed it on the usual 8 MiB stack ("internal compiler error: glslang
// crashed", no line). Its workers now have the stack for the most the token cap allows, so the
// condition is evaluated and the `#error` under it reported at its line.
TEST(GlslValidatorTest, ADeeplyNestedConditionIsEvaluatedNotCrashed) {
    struct Condition {
        const char* why;
        std::string text;
    };
    const std::vector<Condition> conditions = {
            {"60,000 nested parentheses", Repeated("(", 60000) + "1" + Repeated(")", 60000)},
            {"100,000 unary minuses", Repeated("- ", 100000) + "1"},
    };
    for (const Condition& condition : conditions) {
        TempDir dir;
        const std::string text = "#version 300 es\nprecision mediump float;\nout vec4 c;\n#if " +
                                 condition.text +
                                 "\n#error the condition was evaluated\n#endif\n"
                                 "void main() { c = vec4(1.0); }\n";
        const ValidationReport report =
                ValidateShaderFiles({{dir.Write("a.fsh", text).string(), Stage::kFragment}}, {});
        ASSERT_EQ(report.verdicts.size(), 1U) << condition.why;
        EXPECT_FALSE(report.verdicts[0].valid) << condition.why;
        ASSERT_FALSE(report.verdicts[0].diagnostics.empty()) << condition.why;
        const std::string message = FormatDiagnostic(report.verdicts[0].diagnostics[0]);
        EXPECT_NE(message.find("a.fsh:5"), std::string::npos) << condition.why << ": " << message;
        EXPECT_NE(message.find("the condition was evaluated"), std::string::npos)
                << condition.why << ": " << message;
    }
}

// Every kind of array declaration has the one bound, kMaxArrayElements (65536) elements.
std::string ArrayError(const std::string& place, const std::string& name, long long elements) {
    return place + ": error: '" + name + "' holds " + std::to_string(elements) +
           " array elements, more than the 65536 one declaration may hold; no GPU gives a shader "
           "invocation that much memory";
}
constexpr const char* kFragment300 =
        "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";

INSTANTIATE_TEST_SUITE_P(
        ArrayBounds, GlslValidatorPlainFileTest,
        ::testing::Values(
                PlainFileCase{"global", nullptr,
                              "#version 100\nprecision mediump float;\nfloat big[100000];\n"
                              "void main() { gl_FragColor = vec4(big[0]); }\n",
                              ArrayError("a.fsh:3:7", "big", 100000)},
                PlainFileCase{"local", nullptr,
                              "#version 100\nprecision mediump float;\nvoid main() {\n  float "
                              "big[100000];\n  gl_FragColor = vec4(big[0]);\n}\n",
                              ArrayError("a.fsh:4:9", "big", 100000)},
                PlainFileCase{"varying",
                              "#version 100\nattribute vec4 p;\nvarying float "
                              "big[100000];\nvoid main() { big[0] = 1.0; gl_Position "
                              "= p; }\n",
                              "#version 100\nprecision mediump float;\nvoid main() { "
                              "gl_FragColor = vec4(1.0); }\n",
                              ArrayError("a.vsh:3:15", "big", 100000)},
                PlainFileCase{"vertex output (ES 3.00)",
                              "#version 300 es\nin vec4 p;\nout float big[100000];\nvoid main() "
                              "{ big[0] = 1.0; gl_Position = p; }\n",
                              kFragment300, ArrayError("a.vsh:3:11", "big", 100000)},
                PlainFileCase{"const parameter", nullptr,
                              "#version 100\nprecision mediump float;\nfloat first(const in "
                              "float values[100000]) { return values[0]; }\nvoid main() {\n  "
                              "float v[100000];\n  gl_FragColor = vec4(first(v));\n}\n",
                              ArrayError("a.fsh:3:28", "values", 100000)},
                PlainFileCase{"struct member", nullptr,
                              "#version 100\nprecision mediump float;\nstruct Big { float "
                              "m[100000]; };\nBig b;\nvoid main() { gl_FragColor = "
                              "vec4(b.m[0]); }\n",
                              ArrayError("a.fsh:4:5", "b", 100000)},
                PlainFileCase{"array of structs with arrays", nullptr,
                              "#version 100\nprecision mediump float;\nstruct S { float m[300]; "
                              "};\nS s[300];\nvoid main() { gl_FragColor = vec4(s[0].m[0]); }\n",
                              ArrayError("a.fsh:4:3", "s", 90000)},
                // GLSL ES 3.00 has no arrays of arrays (3.10 added them): glslang refuses them.
                PlainFileCase{"array of arrays (ES 3.00)", nullptr,
                              "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid "
                              "main() {\n  float grid[300][300];\n  c = vec4(grid[0][0]);\n}\n",
                              "a.fsh:5: error: 'arrays of arrays' : not supported for this "
                              "version or the enabled extensions"}));

TEST(GlslValidatorTest, ArrayOfExactlyTheBoundIsAccepted) {
    TempDir dir;
    const std::string path =
            dir.Write("a.fsh",
                      "#version 100\nprecision mediump float;\nvoid main() {\n  float "
                      "ok[65536];\n  gl_FragColor = vec4(ok[0]);\n}\n")
                    .string();
    const ValidationReport report = ValidateShaderFiles({{path, Stage::kFragment}}, {});
    ASSERT_EQ(report.verdicts.size(), 1U);
    EXPECT_TRUE(report.verdicts[0].valid) << FormattedEach(report.verdicts[0].diagnostics)[0];
}

// Where and what, without the variant a diagnostic is tagged with and with files named as in
// `folder`.
std::vector<std::string> Placed(const std::vector<Diagnostic>& diagnostics,
                                const std::filesystem::path& folder) {
    const std::string prefix = folder.string() + "/";
    std::vector<std::string> out;
    for (const Diagnostic& d : diagnostics) {
        std::string message = d.message;
        for (std::size_t at = message.find(prefix); at != std::string::npos;
             at = message.find(prefix)) {
            message.erase(at, prefix.size());
        }
        out.push_back(std::filesystem::path(d.file).filename().string() + ":" +
                      std::to_string(d.line) + ":" + std::to_string(d.column) + " " + message);
    }
    return out;
}

TEST(GlslValidatorTest, LinksThatShareAParseGiveEachVariantTheVerdictOfItsOwnFiles) {
    // A worker parses a stage once for all its links. Variants run in the order of their names,
    // so here a link glslang refuses (A_VEC3: the varying's type differs) comes before a valid
    // link of the same vertex stage (C_FOG), and a valid link before one tidepool refuses with
    // the same fragment stage (B_NO_TINT: `tint` is read, in a function nothing calls, but not
    // written). Each variant's verdict and messages must be those of its two files validated on
    // their own.
    TempDir dir;
    const std::string vertex = dir.Write("k.vsh",
                                         "#version 100\nattribute highp vec4 p;\n"
                                         "varying mediump vec2 uv;\n"
                                         "#ifndef B_NO_TINT\nvarying mediump vec3 tint;\n#endif\n"
                                         "void main() {\n  uv = p.xy;\n"
                                         "#ifndef B_NO_TINT\n  tint = p.xyz;\n#endif\n"
                                         "  gl_Position = p;\n}\n")
                                       .string();
    const std::string fragment =
            dir.Write("k.fsh",
                      "#version 100\nprecision mediump float;\n"
                      "#ifdef A_VEC3\nvarying mediump vec3 uv;\n#else\nvarying mediump vec2 uv;\n"
                      "#endif\nvarying mediump vec3 tint;\n"
                      "vec3 Tinted() { return tint; }\n"
                      "void main() {\n  gl_FragColor = vec4(uv.xy, 0.5, 1.0);\n"
                      "#ifdef C_FOG\n  gl_FragColor *= 0.5;\n#endif\n}\n")
                    .string();
    const ValidationReport report =
            ValidateAll(ConfigIn(dir, "k.vsh", "k.fsh", {"A_VEC3", "B_NO_TINT", "C_FOG"}), 1);
    ASSERT_EQ(report.verdicts.size(), 8U);
    EXPECT_EQ(report.stage_programs.size(), 6U);  // two vertex stages, four fragment stages
    int valid = 0;
    for (const VariantVerdict& verdict : report.verdicts) {
        const ValidationReport own = ValidateShaderFiles(
                {ShaderFile{vertex, Stage::kVertex}, ShaderFile{fragment, Stage::kFragment}},
                verdict.variant.defines);
        ASSERT_EQ(own.verdicts.size(), 1U);
        EXPECT_EQ(verdict.valid, own.verdicts[0].valid) << verdict.variant.Id();
        EXPECT_EQ(Placed(verdict.diagnostics, dir.Path()),
                  Placed(own.verdicts[0].diagnostics, dir.Path()))
                << verdict.variant.Id();
        valid += verdict.valid ? 1 : 0;
    }
    EXPECT_EQ(valid, 2);  // p: and p:C_FOG
}

TEST(GlslValidatorTest, UnusedVaryingTheVertexStageLacksStillLinks) {
    TempDir dir;
    const std::string vertex = dir.Write("a.vsh", kVertex).string();
    const std::string fragment =
            dir.Write("a.fsh",
                      "#version 100\nprecision mediump float;\nvarying mediump vec3 "
                      "unused;\nvoid main() { gl_FragColor = vec4(1.0); }\n")
                    .string();
    const ValidationReport report =
            ValidateShaderFiles({{vertex, Stage::kVertex}, {fragment, Stage::kFragment}}, {});
    ASSERT_EQ(report.verdicts.size(), 1U);
    EXPECT_TRUE(report.verdicts[0].valid);
}

TEST(GlslValidatorTest, EveryDefaultVariantIsValid) {
    const ConfigResult config =
            LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
    ASSERT_TRUE(config.config.has_value());
    const ValidationReport report = ValidateAll(*config.config, 2);
    EXPECT_GT(report.verdicts.size(), 50U);
    for (const VariantVerdict& verdict : report.verdicts) {
        EXPECT_TRUE(verdict.valid)
                << verdict.variant.Id() << ": "
                << (verdict.diagnostics.empty() ? std::string("?")
                                                : FormatDiagnostic(verdict.diagnostics[0]));
    }
    EXPECT_GT(report.SharedStageSlots(), 0);
}

}  // namespace
}  // namespace tidepool
