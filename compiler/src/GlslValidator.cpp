// glslang is wrapped here: it is initialised once per process, its text info log is turned into
// Diagnostics at the user's own lines (defines travel through TShader::setPreamble, so the user's
// file is string 0 and keeps its numbering), and nothing of it leaks through the public header.
#include "tidepool/GlslValidator.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <set>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "GlslangSession.h"
#include "StaticCostAnalyzer.h"

namespace tidepool {

int ValidationReport::InvalidCount() const {
    return static_cast<int>(std::count_if(verdicts.begin(), verdicts.end(),
                                          [](const VariantVerdict& v) { return !v.valid; }));
}

bool StageFromExtension(const std::string& path, Stage* stage) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".vert" || ext == ".vsh" || ext == ".vs") {
        *stage = Stage::kVertex;
        return true;
    }
    if (ext == ".frag" || ext == ".fsh" || ext == ".fs") {
        *stage = Stage::kFragment;
        return true;
    }
    return false;
}

namespace {

// Runs fn(i) for i in [0, count) on up to `jobs` threads; each index runs exactly once.
template <typename Fn>
void ParallelFor(std::size_t count, int jobs, Fn fn) {
    const std::size_t workers =
            std::min<std::size_t>(count, static_cast<std::size_t>(std::max(jobs, 1)));
    if (workers <= 1) {
        for (std::size_t i = 0; i < count; ++i) {
            fn(i);
        }
        return;
    }
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> threads;
    threads.reserve(workers);
    for (std::size_t w = 0; w < workers; ++w) {
        threads.emplace_back([&] {
            for (std::size_t i = next++; i < count; i = next++) {
                fn(i);
            }
        });
    }
    for (std::thread& t : threads) {
        t.join();
    }
}

std::string Fnv1a64Hex(std::string_view text) {
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    for (char c : text) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 0x100000001b3ULL;
    }
    return fmt::format("{:016x}", hash);
}

struct FileText {
    bool ok = false;
    std::string text;
};

FileText ReadFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        return {};
    }
    std::ostringstream out;
    out << in.rdbuf();
    return {true, out.str()};
}

// One (file, stage, target, defines) to compile; the unit of preprocessing and hashing.
struct StageJob {
    std::string file;
    const FileText* source = nullptr;
    Stage stage = Stage::kVertex;
    GlslTarget target = GlslTarget::kEs100;
    std::vector<std::string> defines;
    std::string variant_id;
    std::string key;   // dedupe key: file + stage + target + content hash
    std::string hash;  // content hash of the preprocessed text
};

void HashStage(StageJob& job) {
    const GlslangStageInput input{job.file, job.source->text, job.stage, job.target, job.defines};
    const PreprocessResult pre = PreprocessStage(input);
    // A stage that does not even preprocess gets a hash of its raw input, so it stays distinct
    // per define set and the parse reports the error at its line.
    const std::string material =
            pre.ok ? pre.text : job.source->text + "\n//" + DefinePreamble(job.defines);
    job.hash = Fnv1a64Hex(fmt::format("{}|{}|{}", StageName(job.stage), TargetName(job.target),
                                      material));
    job.key = job.file + "|" + job.hash;
}

// Every identifier-like token of a file (comments included: over-counting only costs a
// preprocessor run). GLSL ES has no token pasting (glslang rejects `##` for ES), so a define can
// only change the preprocessed text if its name is spelled out somewhere in the file.
std::set<std::string> MentionedIdentifiers(const std::string& text) {
    std::set<std::string> names;
    std::size_t i = 0;
    while (i < text.size()) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (std::isalpha(c) != 0 || c == '_') {
            const std::size_t start = i;
            while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) != 0 ||
                                       text[i] == '_')) {
                ++i;
            }
            names.insert(text.substr(start, i - start));
        } else {
            ++i;
        }
    }
    return names;
}

// The part of a slot's identity that can change glslang's preprocessed output.
std::string PreprocessGroupKey(const StageJob& job, const std::set<std::string>& mentioned) {
    std::string key = fmt::format("{}|{}|{}|", job.file, StageName(job.stage),
                                  TargetName(job.target));
    for (const std::string& define : job.defines) {
        if (mentioned.count(define) != 0) {
            key += define + ",";
        }
    }
    return key;
}

std::vector<Diagnostic> Tagged(std::vector<Diagnostic> diagnostics, const std::string& id) {
    for (Diagnostic& d : diagnostics) {
        d.variant = id;
    }
    return diagnostics;
}

}  // namespace

ValidationReport ValidateVariants(const VariantConfig& config, const std::vector<Variant>& variants,
                                  const ValidationOptions& options) {
    ValidationReport report;

    // Read every shader file once.
    std::map<std::string, FileText> files;
    for (const ProgramConfig& program : config.programs) {
        for (const std::string& path : {program.vertex_path, program.fragment_path}) {
            if (files.count(path) == 0) {
                files[path] = ReadFile(config.Resolve(path));
                if (!files[path].ok) {
                    report.diagnostics.push_back(MakeError(
                            path, 0, 0, "cannot read shader file; check the path in " +
                                                config.path));
                }
            }
        }
    }

    // 1. Preprocess and hash every stage slot.
    std::vector<StageJob> jobs;
    for (GlslTarget target : options.targets) {
        for (const Variant& variant : variants) {
            const ProgramConfig* program = config.FindProgram(variant.program);
            if (program == nullptr) {
                continue;  // a variant of another configuration: nothing to compile it from
            }
            for (Stage stage : {Stage::kVertex, Stage::kFragment}) {
                StageJob job;
                job.file = stage == Stage::kVertex ? program->vertex_path : program->fragment_path;
                job.source = &files[job.file];
                job.stage = stage;
                job.target = target;
                job.defines = variant.defines;
                job.variant_id = variant.Id();
                jobs.push_back(std::move(job));
            }
        }
    }
    report.stage_slots = static_cast<int>(jobs.size());
    // Slots whose defines differ only in names the file never mentions preprocess to the same
    // text, so glslang's preprocessor (which costs nearly a parse) runs once per group.
    std::map<std::string, std::set<std::string>> mentioned;
    for (const auto& [path, text] : files) {
        mentioned[path] = MentionedIdentifiers(text.text);
    }
    std::map<std::string, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        groups[PreprocessGroupKey(jobs[i], mentioned[jobs[i].file])].push_back(i);
    }
    std::vector<const std::vector<std::size_t>*> group_list;
    for (const auto& [key, members] : groups) {
        group_list.push_back(&members);
    }
    ParallelFor(group_list.size(), options.jobs, [&](std::size_t g) {
        const std::vector<std::size_t>& members = *group_list[g];
        StageJob& first = jobs[members.front()];
        if (first.source->ok) {
            HashStage(first);
        } else {
            first.key = first.file + "|unreadable";
        }
        for (std::size_t i : members) {
            jobs[i].hash = first.hash;
            jobs[i].key = first.key;
        }
    });

    // 2. Parse each distinct stage program once.
    std::map<std::string, std::size_t> program_index;
    std::vector<const StageJob*> representative;
    for (const StageJob& job : jobs) {
        auto [it, inserted] = program_index.emplace(job.key, report.stage_programs.size());
        if (inserted) {
            StageProgram program;
            program.stage = job.stage;
            program.target = job.target;
            program.file = job.file;
            program.hash = job.hash;
            program.defines = job.defines;
            report.stage_programs.push_back(std::move(program));
            representative.push_back(&job);
        }
        report.stage_programs[it->second].variants.push_back(job.variant_id);
    }
    // Each parsed stage is kept for the first link that needs it; later links sharing that stage
    // parse it again, because a glslang tree is finalised by the one program that links it.
    std::vector<StageParse> parsed(report.stage_programs.size());
    std::vector<std::atomic<bool>> claimed(report.stage_programs.size());
    ParallelFor(report.stage_programs.size(), options.jobs, [&](std::size_t i) {
        StageProgram& program = report.stage_programs[i];
        const StageJob& job = *representative[i];
        if (!job.source->ok) {
            program.diagnostics.push_back(MakeError(job.file, 0, 0, "cannot read shader file"));
            return;
        }
        const GlslangStageInput input{job.file, job.source->text, job.stage, job.target,
                                      job.defines};
        StageParse parse = ParseStage(input);
        program.valid = parse.ok;
        program.diagnostics = std::move(parse.diagnostics);
        if (parse.ok && parse.intermediate != nullptr) {
            program.cost = AnalyzeStageCost(*parse.intermediate);
            parsed[i] = std::move(parse);
        }
    });

    // 3. Link each distinct (vertex, fragment) pair whose stages both parsed.
    struct LinkJob {
        std::size_t vertex = 0;
        std::size_t fragment = 0;
        bool linked = false;
        std::vector<Diagnostic> diagnostics;
    };
    std::vector<LinkJob> links;
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> link_index;
    std::vector<std::size_t> verdict_link(jobs.size() / 2);
    for (std::size_t v = 0; v < jobs.size() / 2; ++v) {
        const std::size_t vs = program_index[jobs[2 * v].key];
        const std::size_t fs = program_index[jobs[2 * v + 1].key];
        auto [it, inserted] = link_index.emplace(std::make_pair(vs, fs), links.size());
        if (inserted) {
            links.push_back(LinkJob{vs, fs, false, {}});
        }
        verdict_link[v] = it->second;
    }
    ParallelFor(links.size(), options.jobs, [&](std::size_t i) {
        LinkJob& link = links[i];
        const StageProgram& vs = report.stage_programs[link.vertex];
        const StageProgram& fs = report.stage_programs[link.fragment];
        if (!vs.valid || !fs.valid) {
            return;  // the stage errors already explain the verdict
        }
        const StageJob& vjob = *representative[link.vertex];
        const StageJob& fjob = *representative[link.fragment];
        auto take = [&](std::size_t index) {
            return claimed[index].exchange(true) ? StageParse{} : std::move(parsed[index]);
        };
        const LinkResult result = LinkStages(
                {vjob.file, vjob.source->text, Stage::kVertex, vjob.target, vjob.defines},
                {fjob.file, fjob.source->text, Stage::kFragment, fjob.target, fjob.defines},
                take(link.vertex), take(link.fragment));
        link.linked = result.ok;
        link.diagnostics = result.diagnostics;
    });
    report.links = static_cast<int>(links.size());

    // 4. One verdict per variant and target.
    for (std::size_t v = 0; v < jobs.size() / 2; ++v) {
        const StageJob& vjob = jobs[2 * v];
        const StageJob& fjob = jobs[2 * v + 1];
        const StageProgram& vs = report.stage_programs[program_index[vjob.key]];
        const StageProgram& fs = report.stage_programs[program_index[fjob.key]];
        const LinkJob& link = links[verdict_link[v]];
        VariantVerdict verdict;
        const Variant* variant = nullptr;
        for (const Variant& candidate : variants) {
            if (candidate.Id() == vjob.variant_id) {
                variant = &candidate;
                break;
            }
        }
        verdict.variant = variant != nullptr ? *variant : Variant{};
        verdict.target = vjob.target;
        verdict.vertex_hash = vs.hash;
        verdict.fragment_hash = fs.hash;
        verdict.valid = vs.valid && fs.valid && link.linked;
        for (const auto* diagnostics : {&vs.diagnostics, &fs.diagnostics, &link.diagnostics}) {
            for (Diagnostic d : Tagged(*diagnostics, vjob.variant_id)) {
                verdict.diagnostics.push_back(std::move(d));
            }
        }
        report.verdicts.push_back(std::move(verdict));
    }
    return report;
}

ValidationReport ValidateShaderFiles(const std::vector<ShaderFile>& files,
                                     const std::vector<std::string>& defines) {
    ValidationReport report;
    std::vector<FileText> texts(files.size());
    std::vector<StageParse> parses(files.size());
    for (std::size_t i = 0; i < files.size(); ++i) {
        texts[i] = ReadFile(files[i].path);
        StageProgram program;
        program.stage = files[i].stage;
        program.file = files[i].path;
        program.defines = defines;
        program.variants.push_back(files[i].path);
        if (!texts[i].ok) {
            program.diagnostics.push_back(
                    MakeError(files[i].path, 0, 0, "cannot read shader file; check the path"));
        } else {
            const GlslangStageInput input{files[i].path, texts[i].text, files[i].stage,
                                          std::nullopt, defines};
            parses[i] = ParseStage(input);
            program.valid = parses[i].ok;
            program.diagnostics = parses[i].diagnostics;
            program.hash = Fnv1a64Hex(texts[i].text);
            if (parses[i].ok && parses[i].intermediate != nullptr) {
                program.cost = AnalyzeStageCost(*parses[i].intermediate);
            }
        }
        report.stage_programs.push_back(std::move(program));
    }
    report.stage_slots = static_cast<int>(files.size());

    // Link each vertex file with each fragment file given (usually one of each); a lone stage is
    // linked alone, since some errors (recursion, missing main) appear only at link time.
    std::vector<std::size_t> vertex;
    std::vector<std::size_t> fragment;
    for (std::size_t i = 0; i < files.size(); ++i) {
        (files[i].stage == Stage::kVertex ? vertex : fragment).push_back(i);
    }
    auto link_group = [&](const std::vector<std::size_t>& members) {
        VariantVerdict verdict;
        std::vector<std::string> names;
        bool stages_ok = true;
        std::vector<GlslangStageInput> inputs;
        for (std::size_t i : members) {
            names.push_back(files[i].path);
            const StageProgram& program = report.stage_programs[i];
            stages_ok = stages_ok && program.valid;
            verdict.diagnostics.insert(verdict.diagnostics.end(), program.diagnostics.begin(),
                                       program.diagnostics.end());
            (files[i].stage == Stage::kVertex ? verdict.vertex_hash : verdict.fragment_hash) =
                    program.hash;
            if (texts[i].ok) {
                inputs.push_back({files[i].path, texts[i].text, files[i].stage, std::nullopt,
                                  defines});
            }
        }
        verdict.variant = Variant{fmt::format("{}", fmt::join(names, "+")), defines};
        if (stages_ok) {
            const LinkResult link = inputs.size() == 2 ? LinkStages(inputs[0], inputs[1])
                                                       : LinkSingleStage(inputs[0]);
            verdict.valid = link.ok;
            verdict.diagnostics.insert(verdict.diagnostics.end(), link.diagnostics.begin(),
                                       link.diagnostics.end());
            ++report.links;
        }
        report.verdicts.push_back(std::move(verdict));
    };
    if (vertex.size() == 1 && fragment.size() == 1) {
        link_group({vertex[0], fragment[0]});
    } else {
        for (std::size_t i = 0; i < files.size(); ++i) {
            link_group({i});
        }
    }
    return report;
}

}  // namespace tidepool
