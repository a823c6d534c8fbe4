#include "BuildOutputs.h"

#include "tidepool/TextFile.h"
#include "tidepool/base/AtomicFile.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>

#include "Commands.h"
#include <fmt/format.h>

namespace tidepool::cli {

bool KeepOnlyProgram(LoadedMatrix* loaded, const std::string& name) {
    VariantConfig& config = *loaded->config;
    if (config.FindProgram(name) == nullptr) {
        std::vector<std::string> names;
        for (const ProgramConfig& program : config.programs) {
            names.push_back(program.name);
        }
        std::fprintf(stderr, "error: --program %s: %s has no such program; it has %s\n",
                     name.c_str(), config.path.c_str(),
                     fmt::format("{}", fmt::join(names, ", ")).c_str());
        return false;
    }
    auto other = [&name](const auto& item) { return item.program != name; };
    std::erase_if(config.programs,
                  [&name](const ProgramConfig& program) { return program.name != name; });
    std::erase_if(config.presets, other);
    ExpansionResult& expansion = loaded->expansion;
    std::erase_if(expansion.variants, other);
    std::erase_if(expansion.pruned_by_rule, other);
    std::erase_if(expansion.pruned,
                  [&name](const PrunedCombination& p) { return p.combination.program != name; });
    expansion.pruned_total = 0;
    for (const RulePruneCount& rule : expansion.pruned_by_rule) {
        // Saturating, as the expander's own total.
        expansion.pruned_total = rule.count > UINT64_MAX - expansion.pruned_total
                                         ? UINT64_MAX
                                         : expansion.pruned_total + rule.count;
    }
    return true;
}

std::vector<std::filesystem::path> FilesRead(const VariantConfig& config) {
    std::vector<std::filesystem::path> files{std::filesystem::absolute(config.path)};
    for (const ProgramConfig& program : config.programs) {
        for (const std::string& path : {program.vertex_path, program.fragment_path}) {
            std::filesystem::path file =
                    std::filesystem::absolute(config.Resolve(path)).lexically_normal();
            if (std::find(files.begin(), files.end(), file) == files.end()) {
                files.push_back(std::move(file));
            }
        }
    }
    return files;
}

namespace {

// A path as one word of a Make rule: Make and Ninja's depfile parser both take "\ " for a space,
// "\#" for '#' and "$$" for '$'.
std::string DepfileWord(const std::filesystem::path& path) {
    std::string word;
    for (const char c : path.string()) {
        if (c == ' ' || c == '#') {
            word += '\\';
        } else if (c == '$') {
            word += '$';
        }
        word += c;
    }
    return word;
}

}  // namespace

std::string DepfileText(const std::filesystem::path& target,
                        const std::vector<std::filesystem::path>& dependencies) {
    std::string text = DepfileWord(target) + ":";
    for (const std::filesystem::path& dependency : dependencies) {
        text += " \\\n  " + DepfileWord(dependency);
    }
    return text + "\n";
}

int WriteDepfile(const std::filesystem::path& depfile, const std::filesystem::path& target,
                 const VariantConfig& config) {
    const std::string text =
            DepfileText(std::filesystem::absolute(target).lexically_normal(), FilesRead(config));
    if (const std::string error = base::WriteFileAtomically(depfile, text); !error.empty()) {
        std::fprintf(stderr, "error: --depfile: %s\n", error.c_str());
        return kExitEnvironment;
    }
    return kExitOk;
}

std::filesystem::path VariantSourcePath(GlslTarget target, const Variant& variant, Stage stage) {
    std::string name;
    for (const char c : variant.Id()) {
        name += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '.';
    }
    return std::filesystem::path(TargetName(target)) / variant.program /
           (name + (stage == Stage::kVertex ? ".vert" : ".frag"));
}

namespace {

// True when `path` already holds exactly `content`.
bool HoldsExactly(const std::filesystem::path& path, const std::string& content) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        return false;
    }
    const std::string existing{std::istreambuf_iterator<char>(in),
                               std::istreambuf_iterator<char>()};
    return existing == content;
}

}  // namespace

int WriteVariantSources(const VariantConfig& config, const std::vector<Variant>& variants,
                        const std::filesystem::path& folder) {
    std::map<std::string, std::string> sources;  // path → text, read once
    for (GlslTarget target : config.targets) {
        for (const Variant& variant : variants) {
            const ProgramConfig* program = config.FindProgram(variant.program);
            for (Stage stage : {Stage::kVertex, Stage::kFragment}) {
                const std::string& path =
                        stage == Stage::kVertex ? program->vertex_path : program->fragment_path;
                if (sources.count(path) == 0) {
                    TextFileRead read = ReadShaderFile(config.Resolve(path));
                    if (!read.ok) {
                        std::fprintf(stderr, "%s: error: cannot read shader file: %s\n",
                                     path.c_str(), read.error.c_str());
                        return kExitUsage;
                    }
                    sources[path] = std::move(read.text);
                }
                const std::filesystem::path file =
                        folder / VariantSourcePath(target, variant, stage);
                const std::string text =
                        AssembleDriverSource(sources[path], variant.defines, stage, target);
                if (HoldsExactly(file, text)) {
                    continue;
                }
                if (const std::string error = base::WriteFileAtomically(file, text);
                    !error.empty()) {
                    std::fprintf(stderr, "error: %s\n", error.c_str());
                    return kExitEnvironment;
                }
            }
        }
    }
    return kExitOk;
}

}  // namespace tidepool::cli
