// Conformance of `tidepool validate` against the dEQP GLES2 shader corpus: each case's vertex and
// fragment files are validated together (both stages parsed, then linked), exactly as
// `tidepool validate a.vert b.frag` does, and the verdict is compared with the case's expectation.
//
// Usage: deqp_conformance [CORPUS_DIR]
//   CORPUS_DIR defaults to <source root>/../shared/corpus/deqp-gles2; its README.md describes
//   manifest.tsv. Without an argument and without the folder, the benchmark says so and exits 0.
//
// A benchmark reports; it never fails a build: exit 0 whatever the agreement, 2 on usage errors
// (too many arguments, a named corpus folder that does not exist, a malformed manifest).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#include "BenchSupport.h"
#include "tidepool/Diagnostic.h"
#include "tidepool/GlslValidator.h"

namespace {

namespace fs = std::filesystem;
using tidepool::bench::HardwareThreads;
using tidepool::bench::NowSeconds;

constexpr int kExitUsage = 2;
// How many ids each disagreement group lists: enough to see the pattern, short enough to read.
constexpr std::size_t kIdsPerGroup = 15;
// glslangValidator's agreement on dEQP GLES2+GLES3, as the corpus README states it (not measured
// here, and over a larger corpus than this one).
constexpr double kReferenceAgreementPercent = 99.4;

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
            {"only_glsl_es_100_support",
             "void main() {\n    gl_FragData[1] = vec4(1.0);\n}\n", false,
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
    std::string expect;      // pass, compile_fail or link_fail
    std::string test_stage;  // vertex, fragment or program
    std::string vertex_file;
    std::string fragment_file;
    std::vector<std::string> requires_list;
    bool in_mustpass = false;
    std::string issue_list;  // the must-pass exclusion list naming the case, if any
    std::string origin;      // test_file:line in the original .test file
};

// What tidepool said about one case.
struct Outcome {
    bool ran = false;  // false for skipped cases
    bool vertex_ok = false;
    bool fragment_ok = false;
    bool linked = false;  // meaningful only when both stages compiled
    std::string first_error;
    double seconds = 0.0;
};

std::vector<std::string> SplitTabs(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t begin = 0;
    for (;;) {
        const std::size_t tab = line.find('\t', begin);
        fields.push_back(line.substr(begin, tab == std::string::npos ? std::string::npos
                                                                     : tab - begin));
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
bool LoadManifest(const fs::path& path, std::vector<Case>* cases, std::string* error) {
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
    for (const char* needed : {"id", "expect", "test_stage", "vertex_file", "fragment_file",
                               "requires", "in_mustpass", "mustpass_issue_list", "test_file",
                               "line"}) {
        if (column.count(needed) == 0) {
            *error = fmt::format("{}:1: the header has no '{}' column", path.string(), needed);
            return false;
        }
    }
    int line_number = 1;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty()) {
            continue;
        }
        const std::vector<std::string> fields = SplitTabs(line);
        if (fields.size() != header.size()) {
            *error = fmt::format("{}:{}: {} fields, the header has {}", path.string(),
                                 line_number, fields.size(), header.size());
            return false;
        }
        auto field = [&](const char* name) { return fields[column[name]]; };
        Case c;
        c.id = field("id");
        c.expect = field("expect");
        if (c.expect != "pass" && c.expect != "compile_fail" && c.expect != "link_fail") {
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
        cases->push_back(std::move(c));
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
    const tidepool::ValidationReport report = tidepool::ValidateShaderFiles(files, {});
    outcome.seconds = NowSeconds() - start;
    outcome.vertex_ok = report.stage_programs.size() == 2 && report.stage_programs[0].valid;
    outcome.fragment_ok = report.stage_programs.size() == 2 && report.stage_programs[1].valid;
    outcome.linked = !report.verdicts.empty() && report.verdicts[0].valid;
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

// Where tidepool rejected a case, in words: "vertex compile", "fragment compile", "both
// compiles", "link", or "" when it accepted.
std::string RejectionPlace(const Outcome& o) {
    if (!o.vertex_ok && !o.fragment_ok) {
        return "both compiles";
    }
    if (!o.vertex_ok) {
        return "vertex compile";
    }
    if (!o.fragment_ok) {
        return "fragment compile";
    }
    return o.linked ? "" : "link";
}

// The rule that decides agreement:
//   pass         → both stages compile and the program links;
//   compile_fail → anything rejected (a check glslang runs at link time still rejects the
//                  shader, which is what the conformance test observes);
//   link_fail    → both stages compile and the link fails.
bool Matches(const Case& c, const Outcome& o) {
    const bool accepted = o.vertex_ok && o.fragment_ok && o.linked;
    if (c.expect == "pass") {
        return accepted;
    }
    if (c.expect == "compile_fail") {
        return !accepted;
    }
    return o.vertex_ok && o.fragment_ok && !o.linked;
}

// For a matched compile_fail: did the stage under test fail to compile (for "program" cases,
// either stage)?
bool FailedAtTestStage(const Case& c, const Outcome& o) {
    if (c.test_stage == "vertex") {
        return !o.vertex_ok;
    }
    if (c.test_stage == "fragment") {
        return !o.fragment_ok;
    }
    return !o.vertex_ok || !o.fragment_ok;
}

std::string DisagreementKind(const Case& c, const Outcome& o) {
    const std::string place = RejectionPlace(o);
    if (place.empty()) {
        return fmt::format("expected {}, we accepted", c.expect);
    }
    return fmt::format("expected {}, we rejected at {}", c.expect, place);
}

std::string Percent(std::size_t part, std::size_t whole) {
    return whole == 0 ? "n/a" : fmt::format("{:.2f}%", 100.0 * static_cast<double>(part) /
                                                               static_cast<double>(whole));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 2) {
        std::fprintf(stderr, "usage: %s [CORPUS_DIR]\n", argv[0]);
        return kExitUsage;
    }
    const bool named = argc == 2;
    const fs::path corpus = named ? fs::path(argv[1])
                                  : fs::path(TIDEPOOL_SOURCE_ROOT) / ".." / "shared" / "corpus" /
                                            "deqp-gles2";
    fmt::print("deqp_conformance: tidepool validate over the dEQP GLES2 shader corpus\n");
    fmt::print("environment: {}\n", tidepool::bench::DescribeEnvironment());
    if (!fs::is_directory(corpus)) {
        if (named) {
            fmt::print(stderr, "error: {}: no such folder\n", corpus.string());
            return kExitUsage;
        }
        fmt::print("skipped: the corpus folder {} is absent\n", corpus.lexically_normal().string());
        return 0;
    }
    std::vector<Case> cases;
    std::string error;
    if (!LoadManifest(corpus / "manifest.tsv", &cases, &error)) {
        fmt::print(stderr, "error: {}\n", error);
        return kExitUsage;
    }
    fmt::print("corpus: {} ({} cases)\n", fs::weakly_canonical(corpus).string(), cases.size());

    // Each case is independent and glslang is thread-safe once initialised, so the cases are
    // spread over every hardware thread.
    const std::map<std::string, bool> provided = ProbeRequirements();
    const int jobs = HardwareThreads();
    std::vector<Outcome> outcomes(cases.size());
    const double start = NowSeconds();
    tidepool::bench::ParallelFor(cases.size(), jobs, [&](std::size_t i) {
        if (MissingRequirements(cases[i], provided).empty()) {
            outcomes[i] = Validate(corpus, cases[i]);
        }
    });
    const double wall = NowSeconds() - start;

    std::size_t ran = 0;
    std::size_t matched = 0;
    std::size_t mustpass_ran = 0;
    std::size_t mustpass_matched = 0;
    std::map<std::string, std::size_t> ran_by_expect;
    std::map<std::string, std::size_t> matched_by_expect;
    std::size_t compile_fail_matched = 0;
    std::size_t compile_fail_at_stage = 0;
    std::vector<std::string> compile_fail_elsewhere;  // matched, but not at the stage under test
    std::map<std::string, std::vector<std::size_t>> disagreements;
    std::map<std::string, std::vector<std::size_t>> skipped;  // by missing requirement
    double case_seconds = 0.0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const Outcome& o = outcomes[i];
        if (!o.ran) {
            skipped[fmt::format("{}", fmt::join(MissingRequirements(c, provided), ", "))]
                    .push_back(i);
            continue;
        }
        case_seconds += o.seconds;
        ++ran;
        ++ran_by_expect[c.expect];
        if (c.in_mustpass) {
            ++mustpass_ran;
        }
        if (!Matches(c, o)) {
            disagreements[DisagreementKind(c, o)].push_back(i);
            continue;
        }
        ++matched;
        ++matched_by_expect[c.expect];
        if (c.in_mustpass) {
            ++mustpass_matched;
        }
        if (c.expect == "compile_fail") {
            ++compile_fail_matched;
            if (FailedAtTestStage(c, o)) {
                ++compile_fail_at_stage;
            } else {
                compile_fail_elsewhere.push_back(fmt::format(
                        "{} (test stage {}, we rejected at {})", c.id, c.test_stage,
                        RejectionPlace(o)));
            }
        }
    }

    fmt::print("\nmethod: each case's vertex_file and fragment_file go to ValidateShaderFiles "
               "together (both parsed, then linked); cases spread over {} threads.\n"
               "  pass = both compile and link; compile_fail = any rejection (compile or link); "
               "link_fail = both compile, link fails.\n",
               jobs);
    fmt::print("time: {:.2f} s wall for {} cases ({:.2f} ms per case, mean of per-case wall "
               "times measured inside the worker threads)\n",
               wall, ran, ran == 0 ? 0.0 : 1000.0 * case_seconds / static_cast<double>(ran));

    fmt::print("\nrequirements (probed: a small 1.00 fragment shader that compiles, or is rejected, "
               "only when the validator provides it):\n");
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
    fmt::print("skipped: {} case(s) need something tidepool does not provide\n",
               cases.size() - ran);
    for (const auto& [requirement, indices] : skipped) {
        fmt::print("  requires {} ({} case(s)):\n", requirement, indices.size());
        for (std::size_t i : indices) {
            fmt::print("    {} (expect {})\n", cases[i].id, cases[i].expect);
        }
    }

    fmt::print("\nagreement (matched / cases run):\n");
    fmt::print("  all cases:        {:>4} / {:>4} = {}\n", matched, ran, Percent(matched, ran));
    fmt::print("  in_mustpass:      {:>4} / {:>4} = {}\n", mustpass_matched, mustpass_ran,
               Percent(mustpass_matched, mustpass_ran));
    for (const auto& [expect, count] : ran_by_expect) {
        fmt::print("  expect {:<12} {:>4} / {:>4} = {}\n", expect + ":", matched_by_expect[expect],
                   count, Percent(matched_by_expect[expect], count));
    }
    fmt::print("  compile_fail matched at the stage under test: {} of {} (the rest were rejected "
               "by the other stage or at link)\n",
               compile_fail_at_stage, compile_fail_matched);
    for (const std::string& line : compile_fail_elsewhere) {
        fmt::print("    {}\n", line);
    }
    fmt::print("  reference: glslangValidator 12.0.0 with both stages and -l agrees on {}% of "
               "dEQP GLES2+GLES3 (corpus README; not measured here)\n",
               kReferenceAgreementPercent);
    const bool met = ran > 0 && 100.0 * static_cast<double>(matched) / static_cast<double>(ran) >=
                                        kReferenceAgreementPercent;
    fmt::print("  target: >= {}% of all cases: {}; 100% of in_mustpass: {}\n",
               kReferenceAgreementPercent, met ? "met" : "NOT met",
               mustpass_matched == mustpass_ran ? "met" : "NOT met");

    fmt::print("\ndisagreements: {}\n", ran - matched);
    for (const auto& [kind, indices] : disagreements) {
        std::size_t mustpass = 0;
        for (std::size_t i : indices) {
            if (cases[i].in_mustpass) {
                ++mustpass;
            }
        }
        fmt::print("  {}: {} case(s), {} in_mustpass\n", kind, indices.size(), mustpass);
        for (std::size_t k = 0; k < indices.size() && k < kIdsPerGroup; ++k) {
            const Case& c = cases[indices[k]];
            const Outcome& o = outcomes[indices[k]];
            const std::string flag =
                    c.in_mustpass ? "" : fmt::format(" [not mustpass: {} issue]", c.issue_list);
            fmt::print("    {}{}\n      {}\n", c.id, flag,
                       o.first_error.empty() ? fmt::format("(no error; case at {})", c.origin)
                                             : o.first_error);
        }
        if (indices.size() > kIdsPerGroup) {
            fmt::print("    ... and {} more\n", indices.size() - kIdsPerGroup);
        }
    }
    return 0;
}
