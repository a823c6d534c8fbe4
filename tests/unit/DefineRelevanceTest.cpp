#include "tidepool/TextFile.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "DefineRelevance.h"
#include "GlslangSession.h"
#include "PipelineFixture.h"
#include "StaticCostAnalyzer.h"

namespace tidepool {
namespace {

std::string Repeat(const std::string& text, int times) {
    std::string all;
    for (int i = 0; i < times; ++i) {
        all += text;
    }
    return all;
}

std::optional<std::string> RelevantOf(const std::string& text,
                                      const std::vector<std::string>& defines) {
    return DefineRelevance(text).Relevant(defines);
}

// glslang's preprocessed text of a fragment stage (and whether it preprocessed), the thing two
// define lists with the same answer must agree on.
std::pair<bool, std::string> Preprocessed(const std::string& text,
                                          const std::vector<std::string>& defines) {
    const PreprocessResult result =
            PreprocessStage({"t.fsh", text, Stage::kFragment, GlslTarget::kEs100, defines});
    return {result.ok, result.text};
}

TEST(DefineRelevanceTest, ADefineTestedOnlyInsideAnInactiveBlockIsIrrelevant) {
    const std::string text =
            "#version 100\n#ifdef A\n#ifdef B\nfloat b;\n#endif\n#endif\nvoid main() {}\n";
    EXPECT_EQ(RelevantOf(text, {"B"}), RelevantOf(text, {}));
    EXPECT_NE(RelevantOf(text, {"A", "B"}), RelevantOf(text, {"A"}));
}

TEST(DefineRelevanceTest, AnElifAfterATakenBranchIsNotEvaluated) {
    const std::string text =
            "#version 100\n#if defined(A)\nfloat a;\n#elif defined(B)\nfloat b;\n#else\n"
            "float c;\n#endif\n";
    EXPECT_EQ(RelevantOf(text, {"A", "B"}), RelevantOf(text, {"A"}));
    EXPECT_NE(RelevantOf(text, {"B"}), RelevantOf(text, {}));
}

TEST(DefineRelevanceTest, AnUndefOfANameNoLineExpandsLeavesOnlyItsEffectOnConditions) {
    // The water shaders' normalisation: a define that needs another is undefined without it.
    const std::string text =
            "#version 100\n#if defined(FRESNEL) && !defined(REFRACTION)\n#undef FRESNEL\n#endif\n"
            "#ifdef FRESNEL\nfloat fresnel;\n#endif\n";
    EXPECT_EQ(RelevantOf(text, {"FRESNEL"}), RelevantOf(text, {}));
    EXPECT_EQ(RelevantOf(text, {"REFRACTION"}), RelevantOf(text, {}));
    EXPECT_NE(RelevantOf(text, {"FRESNEL", "REFRACTION"}), RelevantOf(text, {"REFRACTION"}));
}

TEST(DefineRelevanceTest, AValueALineExpandsIsPartOfTheAnswer) {
    const std::string text = "#version 100\nconst float scale = SCALE;\n";
    EXPECT_NE(RelevantOf(text, {"SCALE=2.0"}), RelevantOf(text, {"SCALE=3.0"}));
    EXPECT_EQ(RelevantOf(text, {"SCALE=2.0", "UNUSED"}), RelevantOf(text, {"SCALE=2.0"}));
}

TEST(DefineRelevanceTest, AConditionTheWalkCannotDecideMakesTheWholeConstructRelevant) {
    // glslang defines GL_ES itself, and `A > 1` compares a value: the walk decides neither, so
    // every name in the construct counts, B's in the block as much as A's in the condition.
    const std::string block = "\n#ifdef B\nfloat b;\n#endif\n#endif\n";
    const std::string on_glslang = "#version 100\n#ifdef GL_ES" + block;
    EXPECT_NE(RelevantOf(on_glslang, {"B"}), RelevantOf(on_glslang, {}));
    const std::string on_a_value = "#version 100\n#if A > 1" + block;
    EXPECT_NE(RelevantOf(on_a_value, {"B", "A=0"}), RelevantOf(on_a_value, {"A=0"}));
    EXPECT_NE(RelevantOf(on_a_value, {"A=2"}), RelevantOf(on_a_value, {"A=0"}));
    // Nesting deeper than the walk follows is undecided too, not a deep recursion.
    const std::string deep = "#version 100\n#if " + std::string(100000, '(') + "defined(A)" +
                             std::string(100000, ')') + "\n#ifdef B\nfloat b;\n#endif\n#endif\n";
    EXPECT_NE(RelevantOf(deep, {"B"}), RelevantOf(deep, {}));
    const std::string shallow = "#version 100\n#if ((defined(A)))" + block;
    EXPECT_EQ(RelevantOf(shallow, {"B"}), RelevantOf(shallow, {}));
}

TEST(DefineRelevanceTest, TextsAndDefinesBeyondTheWalkGetNoAnswer) {
    const std::string plain = "#version 100\n#ifdef A\nfloat a;\n#endif\n";
    const struct {
        std::string text;
        std::vector<std::string> defines;
        const char* why;
    } cases[] = {
            {"#version 300 es\n#ifdef A\\\nB\nfloat a;\n#endif\n", {}, "a line continuation"},
            {"#version 100\n#ifdef A\nfloat a;\n", {}, "an #if without #endif"},
            {"#version 100\n#endif\n", {}, "an #endif without #if"},
            {"#version 100\n#ifdef A\n#else\n#else\n#endif\n", {}, "a second #else"},
            {"#version 100\n/* a\n */ #ifdef A\nfloat a;\n#endif\n",
             {},
             "a directive after a comment that spans lines"},
            {plain, {"GL_A"}, "a name glslang reserves"},
            {plain, {"A__B"}, "a name with a double underscore"},
            {plain, {"defined"}, "the word defined"},
            {plain, {"A", "A=2"}, "a name given twice"},
            {plain, {"A=B"}, "a value holding a name"},
            {plain, {"filter"}, "a word the ES 1.00 renaming renames"},
            {"#version 100\n#ifdef A\rfloat a;\n#endif\n", {}, "a lone carriage return"},
            {"#version 100\n#define X 1\f\n", {}, "a form feed"},
            {"#version 100\n#undef X\v\n", {}, "a vertical tab"},
            {"#version 100\n#if 0 /*\n*/ || defined(A)\nfloat a;\n#endif\n",
             {},
             "a directive that a comment carries on to the next line"},
            {"#version 100\n#/*\n*/define X 1\n", {}, "a directive after a comment's line break"},
            {"#version 100\n#ifdef NEVER\n##endif\n#endif\n",
             {},
             "a second `#`, which glslang reads as the directive's own in skipped text"},
            {"#version 100\n#define CAT(a, b) a##b\nfloat x = CAT(ENABLE_, FOG);\n",
             {},
             "token pasting, which makes a name the text never spells"},
            {"#version 100\nfloat x = CAT(ENABLE_, FOG);\n#define CAT(a, b) a ## b\n",
             {},
             "token pasting after the use, spaced"},
            {plain, {std::string(1025, 'A')}, "a name longer than glslang's tokens"},
            {plain, {"A=/*"}, "a value glslang's preamble refuses"},
            {std::string("#version 100\n#ifdef A\n#endif\n\0\n#ifdef B\n", 32), {}, "a NUL"},
            {"#version 100\n" + Repeat("#ifdef A\n", 51) + Repeat("#endif\n", 51),
             {},
             "#if nested deeper than the walk follows"},
    };
    for (const auto& c : cases) {
        EXPECT_EQ(RelevantOf(c.text, c.defines), std::nullopt) << c.why;
    }
    EXPECT_NE(RelevantOf(plain, {"A=0.5"}), std::nullopt);  // a number is no name
}

TEST(DefineRelevanceTest, APlainDefineIsANameGlslangTakesWithAtMostANumber) {
    for (const std::string define :
         {"ENABLE_FOG", "A=1", "A=0", "SCALE=0.5", "A=10.25", "TP_NO_EYE_FLOOR"}) {
        EXPECT_TRUE(IsPlainDefine(define)) << define;
    }
    for (const std::string define :
         {"GL_X", "A__B", "defined", "1A", "A=B", "A=", "A=-1", "A=\"s\"", "A=/*", "A B", "A=08",
          "A=4294967296", "A=1.", "A=.5", "A=1.2.3"}) {
        EXPECT_FALSE(IsPlainDefine(define)) << define;
    }
    EXPECT_TRUE(IsPlainDefine(std::string(1024, 'A')));
    EXPECT_FALSE(IsPlainDefine(std::string(1025, 'A')));
}

TEST(DefineRelevanceTest, ATextThatPastesTokensMentionsEveryDefine) {
    EXPECT_EQ(MentionedIdentifiers("#define CAT(a, b) a##b\nfloat x = CAT(VAL, UE);\n"),
              (std::set<std::string>{"##", "CAT", "UE", "VAL", "a", "b", "define", "float", "x"}));
    EXPECT_EQ(MentionedIdentifiers("// a##b\nfloat x;\n").count(kPastesTokens), 0U);
}

TEST(DefineRelevanceTest, EachTextWhereADefineChangesGlslangsOutputGetsTwoAnswers) {
    // Found by review: each text's output from glslang's preprocessor (or its verdict) differs
    // with and without A, through a path an earlier walk did not count.
    const struct {
        std::string text;
        const char* why;
    } cases[] = {
            {"#ifdef A\n#define X 1\n#else\n#define X 0\n#endif\n#if X\nfloat a;\n#endif\n",
             "a value of the file's own that an undecided #if reads"},
            {"#ifdef A\n#define X 1\n#endif\n#if defined(GL_ES)\n#ifdef X\nfloat a;\n#endif\n"
             "#endif\n",
             "a definition of the file's that an undecided block reads"},
            {"#define X 1\n#ifdef A\n#undef X\n#endif\n#if defined(GL_ES)\n#ifdef X\nfloat a;\n"
             "#endif\n#endif\n",
             "an #undef that an undecided block reads"},
            {"#ifdef A\n#define 1\n#endif\n", "a #define glslang refuses"},
            {"#ifdef A\n#define X 1\n#endif\n#define X 2\n", "a redefinition"},
            {"#ifdef A\n#undef GL_ES\n#endif\n", "an #undef of glslang's own macro"},
            {"#ifdef A\n#undef X Y\n#endif\n", "an #undef with more than a name"},
            {"#line 10A\n", "a name right after a number"},
            {"#ifdef NEVER\n#error \"/*\"\n#endif\n#ifdef A\n#error boom\n#endif\n#ifdef NEVER\n"
             "#error \"*/\"\n#endif\n",
             "comment marks inside strings"},
            {"#define X-1\n#ifndef X\n#ifdef A\nfloat a;\n#endif\n#endif\n",
             "a #define with no space after its name, which defines nothing"},
            {"#ifdef A\n#define defined 1\n#endif\n", "a #define of `defined`"},
            {"#ifdef A\n#undef defined\n#endif\n", "an #undef of `defined`"},
            {"#define X \"a b\"\n#ifdef A\n#define X \"a  b\"\n#endif\n",
             "a redefinition whose strings differ in spaces"},
            {"#ifdef A\n#define X\n#endif\n#define X(x) x\n",
             "a function-like #define after a quiet one"},
            {"#define Y 1\n#ifndef A\n#undef Y\n#endif\n#define Y \"s\"\n",
             "a #define glslang may refuse after a quiet #undef"},
    };
    for (const auto& c : cases) {
        const std::string text = "#version 100\nprecision mediump float;\n" + c.text;
        ASSERT_NE(Preprocessed(text, {"A"}), Preprocessed(text, {})) << c.why;
        EXPECT_NE(RelevantOf(text, {"A"}), RelevantOf(text, {})) << c.why;
    }
}

// A random shader text of nested conditionals on A to E (E only the file defines), with
// definitions, undefinitions and lines that expand the names, some conditions the walk cannot
// decide, and some the preprocessor refuses.
class RandomShader {
public:
    explicit RandomShader(unsigned seed) : random_(seed) {}

    std::string Text() {
        text_ = "#version 100\nprecision mediump float;\n";
        lines_ = 0;
        Block(0);
        return text_;
    }

private:
    std::string Name() { return std::string(1, static_cast<char>('A' + Pick(5))); }
    std::size_t Pick(std::size_t n) {
        return std::uniform_int_distribution<std::size_t>(0, n - 1)(random_);
    }

    void Block(int depth) {
        for (std::size_t n = 1 + Pick(4); n > 0; --n) {
            switch (Pick(depth < 3 ? 4 : 2)) {
                case 0: {
                    static const char* const kValues[] = {"1.0", "", "10", "#error ", "#line 10"};
                    const std::string value = kValues[Pick(std::size(kValues))];
                    text_ += value[0] == '#' ? value + Name() + "\n"
                                             : "float v" + std::to_string(lines_++) + " = " +
                                                       value + Name() + ";\n";
                    break;
                }
                case 1: {
                    const std::string name = Name();
                    static const char* const kLines[] = {"#define {}\n",     "#define {} 2.0\n",
                                                         "#define {} 0\n",   "#define {} 1\n",
                                                         "#undef {}\n",      "#undef {} E\n",
                                                         "#define {}(x) x\n"};
                    std::string line = kLines[Pick(std::size(kLines))];
                    line.replace(line.find("{}"), 2, name);
                    text_ += line;
                    break;
                }
                default:
                    Conditional(depth);
                    break;
            }
        }
    }

    void Conditional(int depth) {
        const std::string x = Name();
        const std::string y = Name();
        const std::string conditions[] = {
                "#ifdef " + x,
                "#ifndef " + x,
                "#if defined(" + x + ") && !defined(" + y + ")",
                "#if defined " + x + " || (defined(" + y + ") && 1)",
                "#if 0",
                "#ifdef GL_ES",
                "#if " + x + " > 1",
                "#if " + x,
        };
        text_ += conditions[Pick(std::size(conditions))] + "\n";
        Block(depth + 1);
        if (Pick(3) == 0) {
            text_ += "#elif defined(" + Name() + ")\n";
            Block(depth + 1);
        }
        if (Pick(2) == 0) {
            text_ += "#else\n";
            Block(depth + 1);
        }
        text_ += "#endif\n";
    }

    std::mt19937 random_;
    std::string text_;
    int lines_ = 0;
};

TEST(DefineRelevanceTest, DefineListsWithOneAnswerGetOnePreprocessedTextFromGlslang) {
    // Every subset of four user defines, on random texts: wherever two lists get the same
    // answer, glslang's preprocessor must agree on them too, errors included.
    const std::vector<std::string> pool = {"A", "B", "C=2.0", "D"};
    int shared = 0;
    for (unsigned seed = 1; seed <= 150; ++seed) {
        const std::string text = RandomShader(seed).Text();
        const DefineRelevance relevance(text);
        std::map<std::string, std::pair<std::vector<std::string>, std::pair<bool, std::string>>>
                first_by_answer;
        for (unsigned mask = 0; mask < 16; ++mask) {
            std::vector<std::string> defines;
            for (std::size_t k = 0; k < pool.size(); ++k) {
                if ((mask & (1U << k)) != 0) {
                    defines.push_back(pool[k]);
                }
            }
            const std::optional<std::string> answer = relevance.Relevant(defines);
            ASSERT_TRUE(answer.has_value()) << text;
            const auto preprocessed = Preprocessed(text, defines);
            const auto [it, inserted] =
                    first_by_answer.emplace(*answer, std::make_pair(defines, preprocessed));
            if (!inserted) {
                ++shared;
                EXPECT_EQ(it->second.second, preprocessed)
                        << "seed " << seed << ", defines " << ::testing::PrintToString(defines)
                        << " and " << ::testing::PrintToString(it->second.first) << ":\n"
                        << text;
            }
        }
    }
    EXPECT_GT(shared, 500);  // the walk does find duplicates, or the check above checks little
}

// The default matrix's stage slots (each variant's vertex and fragment file), with each file's
// text and walk: what the tests below hold the walk to on the shaders tidepool ships.
class DefaultMatrixSlots {
public:
    struct Slot {
        const std::string& path;
        const std::string& text;
        Stage stage;
        const Variant& variant;
        const DefineRelevance& relevance;
    };

    DefaultMatrixSlots() {
        const ConfigResult loaded =
                LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
        if (!loaded.config) {
            ADD_FAILURE() << "the default variants.yaml does not load";
            return;
        }
        config_ = *loaded.config;
        expansion_ = ExpandVariants(*config_, ExpansionOptions{config_->max_variants});
        for (const Variant& variant : expansion_.variants) {
            const ProgramConfig* program = config_->FindProgram(variant.program);
            if (program == nullptr) {
                ADD_FAILURE() << variant.Id() << ": no program";
                continue;
            }
            for (const std::string& path : {program->vertex_path, program->fragment_path}) {
                if (texts_.count(path) == 0) {
                    const TextFileRead read = ReadShaderFile(config_->Resolve(path));
                    EXPECT_TRUE(read.ok) << path;
                    texts_[path] = read.text;
                    relevance_.emplace(path, DefineRelevance(read.text));
                }
            }
        }
    }

    // Calls visit(Slot) for every slot, variant by variant.
    template <typename Visit>
    void ForEach(Visit visit) const {
        for (const Variant& variant : expansion_.variants) {
            const ProgramConfig* program = config_->FindProgram(variant.program);
            if (program == nullptr) {
                continue;
            }
            for (const auto& [path, stage] :
                 {std::make_pair(program->vertex_path, Stage::kVertex),
                  std::make_pair(program->fragment_path, Stage::kFragment)}) {
                visit(Slot{path, texts_.at(path), stage, variant, relevance_.at(path)});
            }
        }
    }

private:
    std::optional<VariantConfig> config_;
    ExpansionResult expansion_;
    std::map<std::string, std::string> texts_;
    std::map<std::string, DefineRelevance> relevance_;
};

TEST(DefineRelevanceTest, TheDefaultMatrixGroupsExactlyAsGlslangsPreprocessedTexts) {
    // On the shaders tidepool ships, the walk finds every duplicate glslang's preprocessor would
    // and no other: one answer per distinct preprocessed text.
    std::map<std::pair<std::string, std::string>, std::set<std::string>> texts_by_answer;
    std::map<std::pair<std::string, std::string>, std::set<std::string>> answers_by_text;
    DefaultMatrixSlots().ForEach([&](const DefaultMatrixSlots::Slot& slot) {
        const std::optional<std::string> answer = slot.relevance.Relevant(slot.variant.defines);
        ASSERT_TRUE(answer.has_value()) << slot.path;
        const PreprocessResult preprocessed = PreprocessStage(
                {slot.path, slot.text, slot.stage, GlslTarget::kEs100, slot.variant.defines});
        ASSERT_TRUE(preprocessed.ok) << slot.path << " " << slot.variant.Id();
        texts_by_answer[{slot.path, *answer}].insert(preprocessed.text);
        answers_by_text[{slot.path, preprocessed.text}].insert(*answer);
    });
    EXPECT_FALSE(texts_by_answer.empty());
    for (const auto& [answer, distinct] : texts_by_answer) {
        EXPECT_EQ(distinct.size(), 1U) << answer.first;
    }
    for (const auto& [text, distinct] : answers_by_text) {
        EXPECT_EQ(distinct.size(), 1U) << text.first;
    }
    EXPECT_EQ(texts_by_answer.size(), answers_by_text.size());
}

TEST(DefineRelevanceTest, SkippedLinesAreTheCodeOfBranchesGlslangDoesNotRead) {
    const std::string text =
            "#version 100\n"                       // 1
            "float a;\n"                           // 2
            "#ifdef A\n"                           // 3
            "float b;\n"                           // 4
            "\n"                                   // 5
            "float c;\n"                           // 6
            "#else\n"                              // 7
            "float d;\n"                           // 8
            "#ifdef B\n"                           // 9
            "float e;\n"                           // 10
            "#endif\n"                             // 11
            "#endif\n"                             // 12
            "#ifdef GL_FRAGMENT_PRECISION_HIGH\n"  // 13: the walk does not decide it
            "float f;\n"                           // 14
            "#else\n"                              // 15
            "float g;\n"                           // 16
            "#endif\n";                            // 17
    const DefineRelevance relevance(text);
    std::vector<LineSpan> skipped;
    ASSERT_TRUE(relevance.Relevant({"A"}, &skipped).has_value());
    EXPECT_EQ(skipped, (std::vector<LineSpan>{{8, 8}, {10, 10}}));
    ASSERT_TRUE(relevance.Relevant({}, &skipped).has_value());
    EXPECT_EQ(skipped, (std::vector<LineSpan>{{4, 6}, {10, 10}}));
    ASSERT_TRUE(relevance.Relevant({"B"}, &skipped).has_value());
    EXPECT_EQ(skipped, (std::vector<LineSpan>{{4, 6}}));
    // A text the walk does not follow has no skipped lines it knows of.
    EXPECT_FALSE(DefineRelevance("#ifdef A\nfloat x;\n").Relevant({}, &skipped).has_value());
    EXPECT_TRUE(skipped.empty());
}

// What a parse decides: its verdict, its messages and, for a valid stage, its cost.
std::string OutcomeOf(const StageParse& parse) {
    std::string outcome =
            std::string(parse.ok ? "valid\n" : "invalid\n") + testing::Formatted(parse.diagnostics);
    if (parse.ok && parse.intermediate != nullptr) {
        outcome += ToJson(AnalyzeStageCost(*parse.intermediate)).dump();
    }
    return outcome;
}

TEST(DefineRelevanceTest, BlankingTheLinesTheWalkSkipsChangesNoParse) {
    // Random texts whose code lines hold, among quiet ones, tokens glslang's scanner refuses
    // even in skipped text (or that are too near such tokens to be left out); every subset of
    // three defines. Given the skipped lines, ParseStage must decide and say exactly what it
    // does without them.
    static const char* const kValues[] = {"1.0",        "0x",   "09",    "1e",   "4294967296",
                                          "1.0f",       "2.5A", "\"s\"", "$",    "b.c * 2.0",
                                          "0.5e+3 + d", "(e)",  "1u",    "0x1F", "'q'"};
    const std::regex code_line("^float v([0-9]+) = [^\n]*;$");
    const std::vector<std::string> pool = {"A", "B", "C"};
    int blanked = 0;
    int kept_in_skipped = 0;
    int differ_when_all_blanked = 0;
    for (unsigned seed = 1; seed <= 60; ++seed) {
        std::string text;
        {
            std::istringstream lines(RandomShader(seed).Text());
            std::size_t k = seed;
            for (std::string line; std::getline(lines, line);) {
                std::smatch match;
                if (std::regex_match(line, match, code_line)) {
                    line = "float v" + match[1].str() + " = " + kValues[k++ % std::size(kValues)] +
                           ";";
                }
                text += line + "\n";
            }
        }
        const DefineRelevance relevance(text);
        const std::vector<bool> quiet = QuietWhenSkippedLines(text);
        for (unsigned mask = 0; mask < 8; ++mask) {
            std::vector<std::string> defines;
            for (std::size_t d = 0; d < pool.size(); ++d) {
                if ((mask & (1U << d)) != 0) {
                    defines.push_back(pool[d]);
                }
            }
            std::vector<LineSpan> skipped;
            ASSERT_TRUE(relevance.Relevant(defines, &skipped).has_value()) << text;
            GlslangStageInput input{"t.fsh", text, Stage::kFragment, GlslTarget::kEs100, defines};
            const std::string as_written = OutcomeOf(ParseStage(input));
            input.skipped_lines = &skipped;
            EXPECT_EQ(OutcomeOf(ParseStage(input)), as_written)
                    << "seed " << seed << ", defines " << ::testing::PrintToString(defines) << ":\n"
                    << text;
            if (WithSkippedLinesBlanked(text, skipped, quiet) != text) {
                ++blanked;
            }
            for (const LineSpan& span : skipped) {
                for (int line = span.first; line <= span.last; ++line) {
                    kept_in_skipped += quiet[static_cast<std::size_t>(line - 1)] ? 0 : 1;
                }
            }
            // Blanking every skipped line, quiet or not, does change what glslang says: the
            // comparison above can see a difference, and IsQuietWhenSkipped is needed.
            const std::string all_blanked =
                    WithSkippedLinesBlanked(text, skipped, std::vector<bool>(quiet.size(), true));
            const GlslangStageInput blind{"t.fsh", all_blanked, Stage::kFragment,
                                          GlslTarget::kEs100, defines};
            differ_when_all_blanked += OutcomeOf(ParseStage(blind)) != as_written ? 1 : 0;
        }
    }
    EXPECT_GT(blanked, 100);
    EXPECT_GT(kept_in_skipped, 100);
    EXPECT_GT(differ_when_all_blanked, 10);
}

TEST(DefineRelevanceTest, BlankingTheSkippedLinesOfTheDefaultMatrixChangesNoParse) {
    std::set<std::pair<std::string, std::string>> parsed;  // (file, answer)
    int blanked = 0;
    DefaultMatrixSlots().ForEach([&](const DefaultMatrixSlots::Slot& slot) {
        std::vector<LineSpan> skipped;
        const std::optional<std::string> answer =
                slot.relevance.Relevant(slot.variant.defines, &skipped);
        ASSERT_TRUE(answer.has_value()) << slot.path;
        if (!parsed.emplace(slot.path, *answer).second) {
            return;
        }
        GlslangStageInput input{slot.path, slot.text, slot.stage, GlslTarget::kEs100,
                                slot.variant.defines};
        const std::string as_written = OutcomeOf(ParseStage(input));
        input.skipped_lines = &skipped;
        EXPECT_EQ(OutcomeOf(ParseStage(input)), as_written)
                << slot.path << " " << slot.variant.Id();
        blanked += skipped.empty() ? 0 : 1;
    });
    EXPECT_GT(blanked, 100);  // most water.fsh programs skip lines
}

}  // namespace
}  // namespace tidepool
