// Conformance of `tidepool validate` against a dEQP shader-case corpus (the shared GLES2 one by
// default): each case's vertex and fragment files are validated together (both stages parsed, then
// linked), exactly as `tidepool validate VERT FRAG --json` does, and the verdict is compared with
// the case's expectation. glslangValidator is measured in the same run on the same cases with the
// same rules, so the figures side by side are comparable.
//
// Usage: deqp_conformance [--ci] [--target webgl1|webgl2] [--baseline FILE] [--record FILE]
//                         [CORPUS_DIR]
//   CORPUS_DIR defaults to <source root>/../shared/corpus/deqp-gles2; its README.md describes
//   manifest.tsv. A manifest with `target` and `webgl_only` columns (the WebGL suite's, from
//   bench/webgl_glsl_to_corpus.py) has its WebGL-only cases validated with their `target`, as
//   `tidepool validate --target`, and the rest as plain GLSL ES; each group gets its figures.
//   --ci            in-process only (ValidateShaderFiles, the function `tidepool validate` calls)
//                   and no glslangValidator: the quick pass the CI check runs.
//   --target T      every case validated with `--target T` (webgl1 or webgl2), as for a corpus
//                   whose expectations are a WebGL suite's; glslangValidator is then not run,
//                   since it has no WebGL mode.
//   --baseline FILE fail (exit 1) when a strict figure falls below the one recorded in FILE.
//   --record FILE   write this run's strict figures to FILE (the baseline format).
// Without --ci, every case is also run through the tidepool binary (`tidepool validate VERT FRAG
// --json`) and its `valid` is the verdict counted; a case where it differs from the in-process
// verdict is listed. The in-process run tells where a rejection happened (a stage or the link),
// which the strict rule needs and the JSON does not say.
//
// Counting rules (the dEQP shader-case expectations; `build_successful` is `pass`):
//   strict  (dEQP's own): pass → both compile and link; compile_fail → a stage fails to compile;
//           link_fail → both compile, the link fails; compile_or_link_fail → anything rejected.
//   lenient: as strict, but a compile_fail case rejected only at link also counts.
//
// Exit codes: 0 (figures printed; below a baseline only with --baseline), 1 a strict figure below
// the baseline, 2 usage errors (bad arguments, a named corpus folder that does not exist, a
// malformed manifest or baseline), 77 no corpus with --baseline (ctest's "skipped").
#include "tidepool/Diagnostic.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/base/ParallelFor.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "BenchSupport.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using tidepool::bench::HardwareThreads;
using tidepool::bench::NowSeconds;

constexpr int kExitBelowBaseline = 1;
constexpr int kExitUsage = 2;
constexpr int kExitSkipped = 77;  // ctest's SKIP_RETURN_CODE

// A requirement of the manifest's `requires` column and a probe that shows whether tidepool's
// validator provides it: a small GLSL ES 1.00 fragment shader that compiles (or is rejected) only
// when the validator behaves like the context the requirement names. Probing instead of assuming
// keeps the skip list true when GlslangSession's limits change.
struct RequirementProbe {
    const char* name;
    const char* fragment_source;
    bool provided_when_accepted;
    const char* meaning;  // what the requirement asks of the context
};

const std::vector<RequirementProbe>& RequirementProbes() {
    // dEQP's "only_glsl_es_100_support" + "exactly_one_draw_buffer" mean an ES 2.0 context
    // without GL_EXT_draw_buffers, i.e. gl_MaxDrawBuffers == 1 for 1.00 shaders; both are probed
    // by the same gl_FragData[1] write, the only observable difference such a context makes.
    static const std::vector<RequirementProbe> probes = {
            {"full_glsl_es_100_support",
             "precision mediump float;\nuniform int n;\nvoid main() {\n    float x = 0.0;\n"
             "    int i = 0;\n    while (i < n) { x += 1.0; ++i; }\n"
             "    gl_FragColor = vec4(x);\n}\n",
             true, "the whole GLSL ES 1.00 language, beyond the Appendix A minimum (while loops)"},
            {"only_glsl_es_100_support", "void main() {\n    gl_FragData[1] = vec4(1.0);\n}\n",
             false,
             "an ES 2.0-only context: 1.00 shaders see ES 2.0 limits (gl_MaxDrawBuffers = 1)"},
            {"exactly_one_draw_buffer", "void main() {\n    gl_FragData[1] = vec4(1.0);\n}\n",
             false, "gl_MaxDrawBuffers == 1, so gl_FragData[1] must not compile"},
    };
    return probes;
}

// Runs every probe in a temporary folder; maps requirement → provided. A probe that cannot be
// written counts as not provided, so its cases are skipped rather than misjudged.
std::map<std::string, bool> ProbeRequirements() {
    std::map<std::string, bool> provided;
    std::error_code error;
    const fs::path folder = fs::temp_directory_path(error) /
                            fmt::format("tidepool-deqp-probe-{}", static_cast<long>(getpid()));
    fs::create_directories(folder, error);
    for (const RequirementProbe& probe : RequirementProbes()) {
        const fs::path file = folder / (std::string(probe.name) + ".frag");
        std::ofstream(file) << probe.fragment_source;
        const tidepool::ValidationReport report =
                tidepool::ValidateShaderFiles({{file.string(), tidepool::Stage::kFragment}}, {});
        const bool accepted = !report.verdicts.empty() && report.verdicts[0].valid;
        provided[probe.name] = fs::exists(file) && accepted == probe.provided_when_accepted;
    }
    fs::remove_all(folder, error);
    return provided;
}

struct Case {
    std::string id;
    std::string expect;      // pass, compile_fail, link_fail or compile_or_link_fail
    std::string test_stage;  // vertex, fragment or program
    std::string vertex_file;
    std::string fragment_file;
    std::vector<std::string> requires_list;
    bool in_mustpass = false;
    std::string issue_list;  // the must-pass exclusion list naming the case, if any
    std::string origin;      // test_file:line in the original .test file
    // Validated with this WebGL target (`--target`, or a WebGL-only case of a WebGL corpus);
    // none: plain GLSL ES.
    std::optional<tidepool::GlslTarget> target;
};

// What one validator said about one case.
struct Outcome {
    bool ran = false;  // false for skipped cases
    bool vertex_ok = false;
    bool fragment_ok = false;
    bool accepted = false;  // both stages compiled and the program linked
    std::string first_error;
    double seconds = 0.0;
};

std::vector<std::string> SplitTabs(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t begin = 0;
    for (;;) {
        const std::size_t tab = line.find('\t', begin);
        fields.push_back(
                line.substr(begin, tab == std::string::npos ? std::string::npos : tab - begin));
        if (tab == std::string::npos) {
            return fields;
        }
        begin = tab + 1;
    }
}

std::vector<std::string> SplitList(const std::string& text, char separator) {
    std::vector<std::string> items;
    std::istringstream in(text);
    for (std::string item; std::getline(in, item, separator);) {
        if (!item.empty()) {
            items.push_back(item);
        }
    }
    return items;
}

// Reads manifest.tsv by column name (not position), so added columns do not break it; returns an
// error message instead of cases when a needed column or a field is missing.
// `corpus_name` is "dEQP <suite>, GLSL ES <version>" from the manifest's own columns; a corpus
// whose cases have more than one version lists each with its case count, the commonest first.
bool LoadManifest(const fs::path& path, std::vector<Case>* cases, std::string* corpus_name,
                  std::string* error) {
    using tidepool::GlslTarget;
    std::ifstream in(path);
    if (!in) {
        *error = fmt::format("{}: cannot open the manifest", path.string());
        return false;
    }
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = SplitTabs(line);
    std::map<std::string, std::size_t> column;
    for (std::size_t i = 0; i < header.size(); ++i) {
        column[header[i]] = i;
    }
    for (const char* needed :
         {"id", "expect", "test_stage", "vertex_file", "fragment_file", "requires", "in_mustpass",
          "mustpass_issue_list", "test_file", "line"}) {
        if (column.count(needed) == 0) {
            *error = fmt::format("{}:1: the header has no '{}' column", path.string(), needed);
            return false;
        }
    }
    std::string suite;
    std::vector<std::pair<std::string, int>> versions;  // in order of first appearance
    int line_number = 1;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty()) {
            continue;
        }
        const std::vector<std::string> fields = SplitTabs(line);
        if (fields.size() != header.size()) {
            *error = fmt::format("{}:{}: {} fields, the header has {}", path.string(), line_number,
                                 fields.size(), header.size());
            return false;
        }
        auto field = [&](const char* name) { return fields[column[name]]; };
        Case c;
        c.id = field("id");
        // Every expectation of dEQP's shader-case format; build_successful means pass.
        c.expect = field("expect") == "build_successful" ? "pass" : field("expect");
        if (c.expect != "pass" && c.expect != "compile_fail" && c.expect != "link_fail" &&
            c.expect != "compile_or_link_fail") {
            *error = fmt::format("{}:{}: unknown expectation '{}'", path.string(), line_number,
                                 c.expect);
            return false;
        }
        c.test_stage = field("test_stage");
        c.vertex_file = field("vertex_file");
        c.fragment_file = field("fragment_file");
        c.requires_list = SplitList(field("requires"), ';');
        c.in_mustpass = field("in_mustpass") == "True";
        c.issue_list = field("mustpass_issue_list");
        c.origin = fmt::format("{}:{}", field("test_file"), field("line"));
        if (column.count("webgl_only") != 0 && field("webgl_only") == "True") {
            GlslTarget target = GlslTarget::kEs100;
            const std::string name = column.count("target") != 0 ? field("target") : "";
            if (!tidepool::TargetFromName(name, &target) || !tidepool::IsWebGlTarget(target)) {
                *error = fmt::format(
                        "{}:{}: a WebGL-only case needs a target of webgl1 or "
                        "webgl2, got '{}'",
                        path.string(), line_number, name);
                return false;
            }
            c.target = target;
        }
        if (column.count("suite") != 0 && column.count("glsl_version") != 0) {
            if (suite.empty()) {
                suite = field("suite");
            }
            const std::string version = field("glsl_version");
            auto it = std::find_if(versions.begin(), versions.end(),
                                   [&](const auto& v) { return v.first == version; });
            if (it == versions.end()) {
                versions.emplace_back(version, 1);
            } else {
                ++it->second;
            }
        }
        cases->push_back(std::move(c));
    }
    // The WebGL suite's corpus names its suite "webgl"; dEQP's name theirs "gles2", "gles3".
    const std::string source =
            suite == "webgl" ? "WebGL conformance suite" : fmt::format("dEQP {}", suite);
    if (versions.size() == 1) {
        *corpus_name = fmt::format("{}, GLSL ES {}", source, versions[0].first);
    } else if (!versions.empty()) {
        std::stable_sort(versions.begin(), versions.end(),
                         [](const auto& a, const auto& b) { return a.second > b.second; });
        std::vector<std::string> parts;
        for (const auto& [version, count] : versions) {
            parts.push_back(fmt::format("{} ({} cases)", version, count));
        }
        *corpus_name = fmt::format("{}, GLSL ES {}", source, fmt::join(parts, ", "));
    }
    return true;
}

// The requirements of a case tidepool does not provide (empty: the case runs); a requirement no
// probe knows is never provided.
std::vector<std::string> MissingRequirements(const Case& c,
                                             const std::map<std::string, bool>& provided) {
    std::vector<std::string> missing;
    for (const std::string& requirement : c.requires_list) {
        const auto it = provided.find(requirement);
        if (it == provided.end() || !it->second) {
            missing.push_back(requirement);
        }
    }
    return missing;
}

Outcome Validate(const fs::path& corpus, const Case& c) {
    Outcome outcome;
    outcome.ran = true;
    const double start = NowSeconds();
    const std::vector<tidepool::ShaderFile> files = {
            {(corpus / c.vertex_file).string(), tidepool::Stage::kVertex},
            {(corpus / c.fragment_file).string(), tidepool::Stage::kFragment},
    };
    tidepool::ShaderFileOptions options;
    options.target = c.target;
    const tidepool::ValidationReport report = tidepool::ValidateShaderFiles(files, {}, options);
    outcome.seconds = NowSeconds() - start;
    outcome.vertex_ok = report.stage_programs.size() == 2 && report.stage_programs[0].valid;
    outcome.fragment_ok = report.stage_programs.size() == 2 && report.stage_programs[1].valid;
    outcome.accepted = !report.verdicts.empty() && report.verdicts[0].valid;
    for (const tidepool::VariantVerdict& verdict : report.verdicts) {
        for (const tidepool::Diagnostic& d : verdict.diagnostics) {
            if (d.severity == tidepool::Severity::kError && outcome.first_error.empty()) {
                tidepool::Diagnostic shown = d;
                // Paths relative to the corpus are shorter and still unique.
                shown.file = fs::path(d.file).lexically_relative(corpus).string();
                outcome.first_error = tidepool::FormatDiagnostic(shown);
            }
        }
    }
    return outcome;
}

std::string Quoted(const std::string& word) {
    std::string quoted = "'";
    for (char ch : word) {
        quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    }
    return quoted + "'";
}

// Runs a shell command line; returns its exit status (-1 when it did not exit normally) and
// what it printed (the command line chooses where stderr goes).
int RunCommand(const std::string& command, std::string* output) {
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return -1;
    }
    std::array<char, 4096> buffer{};
    for (std::size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) {
        output->append(buffer.data(), n);
    }
    const int status = pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// glslangValidator with both stages and -l, one process per case as a shell user runs it: exit 0
// means all compiled and linked, 2 a compile failure (glslang's EFailCompile), 3 a link failure.
Outcome ValidateWithGlslang(const fs::path& corpus, const Case& c) {
    Outcome outcome;
    outcome.ran = true;
    const double start = NowSeconds();
    std::string output;
    const int status = RunCommand(
            fmt::format("glslangValidator -l {} {} 2>&1", Quoted((corpus / c.vertex_file).string()),
                        Quoted((corpus / c.fragment_file).string())),
            &output);
    outcome.seconds = NowSeconds() - start;
    outcome.vertex_ok = outcome.fragment_ok = status == 0 || status == 3;
    outcome.accepted = status == 0;
    if (status != 0) {
        std::istringstream lines(output);
        for (std::string line; std::getline(lines, line);) {
            if (line.rfind("ERROR: ", 0) == 0) {
                outcome.first_error = line;
                break;
            }
        }
        if (status != 2 && status != 3) {
            outcome.first_error =
                    fmt::format("glslangValidator exited with {}: {}", status, outcome.first_error);
        }
    }
    return outcome;
}

// `tidepool validate VERT FRAG --json` as a user runs it: true when every verdict is valid;
// `error` is set when the output is not the JSON the command prints.
bool ValidateWithCli(const std::string& binary, const fs::path& corpus, const Case& c,
                     std::string* error) {
    std::string output;
    const std::string target =
            c.target ? fmt::format(" --target {}", tidepool::TargetName(*c.target)) : "";
    const int status =
            RunCommand(fmt::format("{} validate{} {} {} --json 2>/dev/null", Quoted(binary), target,
                                   Quoted((corpus / c.vertex_file).string()),
                                   Quoted((corpus / c.fragment_file).string())),
                       &output);
    const nlohmann::json json = nlohmann::json::parse(output, nullptr, false);
    if (!json.is_array() || json.empty()) {
        *error = fmt::format("exit {}, output not JSON: {}", status, output.substr(0, 200));
        return false;
    }
    return std::all_of(json.begin(), json.end(),
                       [](const nlohmann::json& verdict) { return verdict.value("valid", false); });
}

// Where a validator rejected a case, in words: "vertex compile", "fragment compile", "both
// compiles", "a compile" (glslangValidator does not say which), "link", or "" when it accepted.
std::string RejectionPlace(const Outcome& o, bool stages_known) {
    if (!o.vertex_ok && !o.fragment_ok) {
        return stages_known ? "both compiles" : "a compile";
    }
    if (!o.vertex_ok) {
        return "vertex compile";
    }
    if (!o.fragment_ok) {
        return "fragment compile";
    }
    return o.accepted ? "" : "link";
}

enum class Rule { kStrict, kLenient };

bool Matches(const Case& c, const Outcome& o, Rule rule) {
    const bool compiled = o.vertex_ok && o.fragment_ok;
    if (c.expect == "pass") {
        return o.accepted;
    }
    if (c.expect == "compile_fail") {
        return rule == Rule::kStrict ? !compiled : !o.accepted;
    }
    if (c.expect == "link_fail") {
        return compiled && !o.accepted;
    }
    return !o.accepted;  // compile_or_link_fail
}

std::string DisagreementKind(const Case& c, const Outcome& o, bool stages_known) {
    const std::string place = RejectionPlace(o, stages_known);
    if (place.empty()) {
        return fmt::format("expected {}, accepted", c.expect);
    }
    return fmt::format("expected {}, rejected at {}", c.expect, place);
}

std::string Percent(std::size_t part, std::size_t whole) {
    return whole == 0 ? "n/a"
                      : fmt::format("{:.2f}%",
                                    100.0 * static_cast<double>(part) / static_cast<double>(whole));
}

// Matched / run over a set of cases, for one validator and one rule.
struct Figure {
    std::size_t matched = 0;
    std::size_t ran = 0;
    std::string Text() const {
        return fmt::format("{} / {} = {}", matched, ran, Percent(matched, ran));
    }
};

Figure Count(const std::vector<Case>& cases, const std::vector<Outcome>& outcomes, Rule rule,
             bool (*selected)(const Case&)) {
    Figure figure;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        if (outcomes[i].ran && selected(cases[i])) {
            ++figure.ran;
            figure.matched += Matches(cases[i], outcomes[i], rule) ? 1U : 0U;
        }
    }
    return figure;
}

bool AllCases(const Case&) {
    return true;
}
bool MustPass(const Case& c) {
    return c.in_mustpass;
}
bool PlainCase(const Case& c) {
    return !c.target;
}
bool TargetCase(const Case& c) {
    return c.target.has_value();
}

// The recorded figures a run must not fall below: "key matched/ran" lines, '#' comments.
struct Baseline {
    std::map<std::string, Figure> figures;
};

bool LoadBaseline(const fs::path& path, Baseline* baseline, std::string* error) {
    std::ifstream in(path);
    if (!in) {
        *error = fmt::format("{}: cannot open the baseline", path.string());
        return false;
    }
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        if (line.empty() || line[0] == '#') {
            continue;
        }
        std::istringstream words(line);
        std::string key;
        std::string value;
        char slash = 0;
        Figure figure;
        words >> key >> value;
        std::istringstream numbers(value);
        if (key == "corpus") {
            continue;
        }
        if (!(numbers >> figure.matched >> slash >> figure.ran) || slash != '/') {
            *error = fmt::format("{}:{}: expected 'KEY MATCHED/RAN', got '{}'", path.string(),
                                 number, line);
            return false;
        }
        baseline->figures[key] = figure;
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    bool ci = false;
    std::string baseline_path;
    std::string record_path;
    std::string corpus_arg;
    std::optional<tidepool::GlslTarget> target;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        tidepool::GlslTarget named_target = tidepool::GlslTarget::kEs100;
        if (arg == "--ci") {
            ci = true;
        } else if ((arg == "--baseline" || arg == "--record") && i + 1 < argc) {
            (arg == "--baseline" ? baseline_path : record_path) = argv[++i];
        } else if (arg == "--target" && i + 1 < argc &&
                   tidepool::TargetFromName(argv[i + 1], &named_target) &&
                   tidepool::IsWebGlTarget(named_target)) {
            target = named_target;
            ++i;
        } else if (!arg.empty() && arg[0] != '-' && corpus_arg.empty()) {
            corpus_arg = arg;
        } else {
            std::fprintf(stderr,
                         "usage: %s [--ci] [--target webgl1|webgl2] [--baseline FILE] "
                         "[--record FILE] [CORPUS_DIR]\n",
                         argv[0]);
            return kExitUsage;
        }
    }
    const bool named = !corpus_arg.empty();
    const fs::path corpus =
            named ? fs::path(corpus_arg)
                  : fs::path(TIDEPOOL_SOURCE_ROOT) / ".." / "shared" / "corpus" / "deqp-gles2";
    fmt::print("deqp_conformance: tidepool validate over a dEQP shader-case corpus\n");
    fmt::print("environment: {}\n", tidepool::bench::DescribeEnvironment());
    if (!fs::is_directory(corpus)) {
        if (named) {
            fmt::print(stderr, "error: {}: no such folder\n", corpus.string());
            return kExitUsage;
        }
        fmt::print("skipped: the corpus folder {} is absent\n", corpus.lexically_normal().string());
        return baseline_path.empty() ? 0 : kExitSkipped;
    }
    std::vector<Case> cases;
    std::string corpus_name;
    std::string error;
    if (!LoadManifest(corpus / "manifest.tsv", &cases, &corpus_name, &error)) {
        fmt::print(stderr, "error: {}\n", error);
        return kExitUsage;
    }
    if (target) {
        for (Case& c : cases) {
            c.target = target;
        }
    }
    const auto targeted =
            static_cast<std::size_t>(std::count_if(cases.begin(), cases.end(), TargetCase));
    Baseline baseline;
    if (!baseline_path.empty() && !LoadBaseline(baseline_path, &baseline, &error)) {
        fmt::print(stderr, "error: {}\n", error);
        return kExitUsage;
    }
    const std::string folder_name = fs::weakly_canonical(corpus).filename().string();
    fmt::print("corpus: {} ({}; {} cases) at {}\n", folder_name,
               corpus_name.empty() ? "suite not named in the manifest" : corpus_name, cases.size(),
               fs::weakly_canonical(corpus).string());

    // In process, one case after another: ValidateShaderFiles forks its glslang workers, and two
    // threads forking at once let each pool's worker inherit the other pool's socket, so neither
    // worker ever sees its end of input (a hang seen on the loaded CI machine). The commands run
    // below (the binary, glslangValidator) exec at once and are spread over every thread.
    const std::map<std::string, bool> provided = ProbeRequirements();
    const int jobs = HardwareThreads();
    std::vector<Outcome> outcomes(cases.size());
    const double start = NowSeconds();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        if (MissingRequirements(cases[i], provided).empty()) {
            outcomes[i] = Validate(corpus, cases[i]);
        }
    }
    const double wall = NowSeconds() - start;

    // The same verdicts as a user gets them from the binary; the binary's word is the one counted.
    std::vector<std::string> cli_differences;
    double cli_wall = 0.0;
    if (!ci) {
        std::vector<std::string> notes(cases.size());
        const double cli_start = NowSeconds();
        tidepool::base::ParallelFor(cases.size(), jobs, [&](std::size_t i) {
            if (!outcomes[i].ran) {
                return;
            }
            std::string cli_error;
            const bool valid = ValidateWithCli(TIDEPOOL_BINARY, corpus, cases[i], &cli_error);
            if (!cli_error.empty() || valid != outcomes[i].accepted) {
                notes[i] = fmt::format("{}: binary says {}, in-process says {}{}", cases[i].id,
                                       valid ? "valid" : "invalid",
                                       outcomes[i].accepted ? "valid" : "invalid",
                                       cli_error.empty() ? "" : " (" + cli_error + ")");
                outcomes[i].accepted = valid;
                if (!valid && outcomes[i].vertex_ok && outcomes[i].fragment_ok) {
                    outcomes[i].first_error = "rejected by the binary only";
                }
            }
        });
        cli_wall = NowSeconds() - cli_start;
        for (std::string& note : notes) {
            if (!note.empty()) {
                cli_differences.push_back(std::move(note));
            }
        }
    }

    // glslangValidator on exactly the cases tidepool ran.
    std::vector<Outcome> reference(cases.size());
    double reference_wall = 0.0;
    std::string output;
    // glslangValidator has no WebGL mode: it runs only where some case is plain GLSL ES.
    const bool have_glslang = !ci && targeted != cases.size() &&
                              RunCommand("glslangValidator --version 2>&1", &output) == 0;
    if (have_glslang) {
        const double reference_start = NowSeconds();
        tidepool::base::ParallelFor(cases.size(), jobs, [&](std::size_t i) {
            if (outcomes[i].ran && !cases[i].target) {
                reference[i] = ValidateWithGlslang(corpus, cases[i]);
            }
        });
        reference_wall = NowSeconds() - reference_start;
    }

    std::size_t ran = 0;
    double case_seconds = 0.0;
    std::map<std::string, std::vector<std::size_t>> skipped;  // by missing requirement
    for (std::size_t i = 0; i < cases.size(); ++i) {
        if (!outcomes[i].ran) {
            skipped[fmt::format("{}", fmt::join(MissingRequirements(cases[i], provided), ", "))]
                    .push_back(i);
            continue;
        }
        ++ran;
        case_seconds += outcomes[i].seconds;
    }

    fmt::print(
            "\nmethod: each case's vertex_file and fragment_file validated together (both "
            "parsed, then linked); in process one case at a time, commands over {} threads;\n"
            "  tidepool: {};\n"
            "  glslangValidator: {}.\n",
            jobs,
            ci ? "in process (ValidateShaderFiles, what `tidepool validate VERT FRAG` calls); "
                 "--ci, so the binary was not run"
               : "`tidepool validate VERT FRAG --json` per case (its `valid` is counted), "
                 "and in process to tell a stage's rejection from the link's",
            have_glslang ? "`glslangValidator -l VERT FRAG` per case on the same cases, those "
                           "validated without a WebGL target (exit 2 = a compile failed, 3 = "
                           "the link failed)"
                         : (ci ? "not run (--ci)"
                            : targeted == cases.size()
                                    ? "not run (it has no WebGL mode, and every case has a "
                                      "WebGL target)"
                                    : "not installed, not run"));
    if (targeted != 0) {
        fmt::print(
                "  {} case(s) validated with a WebGL target ({}); the other {} as plain GLSL "
                "ES.\n",
                targeted,
                target ? fmt::format("--target {} for every case", tidepool::TargetName(*target))
                       : std::string("the WebGL-only cases, each with its manifest's target"),
                cases.size() - targeted);
    }
    fmt::print("time: {:.2f} s wall in process for {} cases ({:.2f} ms per case)", wall, ran,
               ran == 0 ? 0.0 : 1000.0 * case_seconds / static_cast<double>(ran));
    if (!ci) {
        fmt::print("; {:.2f} s for the binary", cli_wall);
    }
    if (have_glslang) {
        fmt::print("; {:.2f} s for glslangValidator", reference_wall);
    }
    fmt::print("\n");

    fmt::print(
            "\nrequirements (probed: a small 1.00 fragment shader that compiles, or is "
            "rejected, only when the validator provides it):\n");
    for (const RequirementProbe& probe : RequirementProbes()) {
        std::size_t count = 0;
        for (const Case& c : cases) {
            if (std::find(c.requires_list.begin(), c.requires_list.end(), probe.name) !=
                c.requires_list.end()) {
                ++count;
            }
        }
        fmt::print("  {}: {}; it means {}; {} case(s) require it\n", probe.name,
                   provided.at(probe.name) ? "provided" : "NOT provided", probe.meaning, count);
    }
    fmt::print("skipped (both validators): {} case(s) need something tidepool does not provide\n",
               cases.size() - ran);
    for (const auto& [requirement, indices] : skipped) {
        fmt::print("  requires {} ({} case(s)):\n", requirement, indices.size());
        for (std::size_t i : indices) {
            fmt::print("    {} (expect {})\n", cases[i].id, cases[i].expect);
        }
    }

    const Figure strict_all = Count(cases, outcomes, Rule::kStrict, AllCases);
    const Figure strict_mustpass = Count(cases, outcomes, Rule::kStrict, MustPass);
    fmt::print(
            "\nagreement, matched / cases run (strict = dEQP's own rule; lenient = a "
            "compile_fail case may be rejected at link):\n");
    fmt::print("  {:<13} {:<24} {:<24} {:<24} {:<24}\n", "", "tidepool strict", "tidepool lenient",
               "glslangValidator strict", "glslangValidator lenient");
    std::vector<std::pair<const char*, bool (*)(const Case&)>> rows = {{"all cases", AllCases},
                                                                       {"in_mustpass", MustPass}};
    if (targeted != 0 && targeted != cases.size()) {
        rows.emplace_back("plain GLSL ES", PlainCase);
        rows.emplace_back("--target", TargetCase);
    }
    for (const auto& [label, selected] : rows) {
        auto reference_text = [&](Rule rule) {
            const Figure figure = Count(cases, reference, rule, selected);
            return have_glslang && figure.ran != 0 ? figure.Text() : std::string("not run");
        };
        fmt::print("  {:<13} {:<24} {:<24} {:<24} {:<24}\n", label,
                   Count(cases, outcomes, Rule::kStrict, selected).Text(),
                   Count(cases, outcomes, Rule::kLenient, selected).Text(),
                   reference_text(Rule::kStrict), reference_text(Rule::kLenient));
    }
    std::map<std::string, Figure> by_expect;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        if (outcomes[i].ran) {
            Figure& figure = by_expect[cases[i].expect];
            ++figure.ran;
            figure.matched += Matches(cases[i], outcomes[i], Rule::kStrict) ? 1U : 0U;
        }
    }
    for (const auto& [expect, figure] : by_expect) {
        fmt::print("  tidepool strict, expect {:<22} {}\n", expect + ":", figure.Text());
    }
    if (!ci) {
        fmt::print("  the binary and the in-process call disagreed on {} case(s)\n",
                   cli_differences.size());
        for (const std::string& line : cli_differences) {
            fmt::print("    {}\n", line);
        }
    }

    auto print_misses = [&](const char* who, const std::vector<Outcome>& results,
                            bool stages_known) {
        std::map<std::string, std::vector<std::size_t>> misses;
        std::size_t count = 0;
        for (std::size_t i = 0; i < cases.size(); ++i) {
            if (results[i].ran && !Matches(cases[i], results[i], Rule::kStrict)) {
                misses[DisagreementKind(cases[i], results[i], stages_known)].push_back(i);
                ++count;
            }
        }
        fmt::print(
                "\n{} misses under the strict rule: {} (each with its cause: the first error, "
                "or where the case stands)\n",
                who, count);
        for (const auto& [kind, indices] : misses) {
            const auto mustpass = std::count_if(indices.begin(), indices.end(), [&](std::size_t i) {
                return cases[i].in_mustpass;
            });
            fmt::print("  {}: {} case(s), {} in_mustpass\n", kind, indices.size(), mustpass);
            for (std::size_t i : indices) {
                const Case& c = cases[i];
                std::string flag =
                        c.in_mustpass ? "" : fmt::format(" [not mustpass: {} issue]", c.issue_list);
                if (c.target) {
                    flag += fmt::format(" [--target {}]", tidepool::TargetName(*c.target));
                }
                fmt::print("    {}{}\n      {}\n", c.id, flag,
                           results[i].first_error.empty()
                                   ? fmt::format("(no error; case at {})", c.origin)
                                   : results[i].first_error);
            }
        }
    };
    print_misses("tidepool", outcomes, true);
    if (have_glslang) {
        print_misses("glslangValidator", reference, false);
        // The issue's rule: no case glslangValidator gets right may be lost.
        std::vector<std::size_t> lost;
        for (std::size_t i = 0; i < cases.size(); ++i) {
            if (reference[i].ran && Matches(cases[i], reference[i], Rule::kStrict) &&
                !Matches(cases[i], outcomes[i], Rule::kStrict)) {
                lost.push_back(i);
            }
        }
        fmt::print("\ncases glslangValidator gets right and tidepool misses (strict): {}\n",
                   lost.size());
        for (std::size_t i : lost) {
            fmt::print("  {}\n", cases[i].id);
        }
    }

    if (!record_path.empty()) {
        std::ofstream out(record_path);
        out << "# Strict figures of bench/deqp_conformance (matched/run), recorded with --record.\n"
               "# The CI check (ctest DeqpConformanceStrict) fails when a run falls below them.\n"
            << fmt::format("corpus {}\nstrict_all {}/{}\nstrict_mustpass {}/{}\n", folder_name,
                           strict_all.matched, strict_all.ran, strict_mustpass.matched,
                           strict_mustpass.ran);
        fmt::print("\nrecorded the strict figures in {}\n", record_path);
    }
    if (!baseline_path.empty()) {
        bool below = false;
        fmt::print("\nbaseline {}:\n", baseline_path);
        for (const auto& [key, figure] : {std::pair<std::string, Figure>{"strict_all", strict_all},
                                          {"strict_mustpass", strict_mustpass}}) {
            const auto recorded = baseline.figures.find(key);
            if (recorded == baseline.figures.end()) {
                continue;
            }
            // Compared as counts over the same number of cases: a changed corpus is a new
            // baseline, not a pass or a failure.
            const bool same_cases = recorded->second.ran == figure.ran;
            const bool ok = same_cases && figure.matched >= recorded->second.matched;
            below = below || !ok;
            fmt::print("  {}: {} now, {} recorded: {}\n", key, figure.Text(),
                       recorded->second.Text(),
                       ok ? "ok"
                          : (same_cases ? "BELOW the recorded figure"
                                        : "a different number of cases; record again"));
        }
        return below ? kExitBelowBaseline : 0;
    }
    return 0;
}
