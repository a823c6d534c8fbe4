#include "tidepool/pipeline/BuildOutputs.h"

#include "tidepool/TextFile.h"
#include "tidepool/pipeline/OutputFiles.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <map>
#include <string_view>

#include <fmt/format.h>

namespace tidepool::pipeline {

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

// A path as one word of a Make rule, for a path DepfileRefusal accepts: Make and Ninja's depfile
// parser both take "\ " for a space, "\#" for '#', "\:" for ':' and "$$" for '$'.
std::string DepfileWord(const std::filesystem::path& path) {
    std::string word;
    for (const char c : path.string()) {
        if (c == ' ' || c == '#' || c == ':') {
            word += '\\';
        } else if (c == '$') {
            word += '$';
        }
        word += c;
    }
    return word;
}

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

std::string DepfileRefusal(const std::filesystem::path& path) {
    const std::string text = path.string();
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        // Letters, digits, bytes of UTF-8, the four DepfileWord escapes, and punctuation that
        // both tools take as part of a name (tried with GNU Make 4.3 and Ninja 1.11).
        if (std::isalnum(byte) || byte >= 0x80 ||
            std::string_view(" #:$/._-+,@!~%{}()").find(c) != std::string_view::npos) {
            continue;
        }
        const std::string shown = c == '\n'   ? "a newline"
                                  : c == '\t' ? "a tab"
                                  : c == '\r' ? "a carriage return"
                                  : std::isprint(byte) != 0
                                          ? fmt::format("'{}'", c)
                                          : fmt::format("the byte 0x{:02x}", byte);
        return fmt::format(
                "{:?} has {} in its name, which Make or Ninja would read as "
                "something else in a depfile",
                text, shown);
    }
    if (!text.empty() && text.back() == ')' && text.find('(') != std::string::npos) {
        return text + " ends in a parenthesis, which Make reads as a member of an archive";
    }
    return {};
}

std::string DepfileText(const std::filesystem::path& target,
                        const std::vector<std::filesystem::path>& dependencies) {
    std::string text = DepfileWord(target) + ":";
    for (const std::filesystem::path& dependency : dependencies) {
        text += " \\\n  " + DepfileWord(dependency);
    }
    return text + "\n";
}

bool CheckDepfileNames(const std::filesystem::path& target,
                       const std::vector<std::filesystem::path>& dependencies, Outcome* outcome) {
    std::vector<std::filesystem::path> names{DepfileTarget(target)};
    names.insert(names.end(), dependencies.begin(), dependencies.end());
    for (const std::filesystem::path& name : names) {
        if (const std::string why = DepfileRefusal(name); !why.empty()) {
            outcome->Fail(Status::kUsage,
                          fmt::format("--depfile: {}; rename it, or leave out --depfile", why));
            return false;
        }
    }
    return true;
}

std::filesystem::path DepfileTarget(const std::filesystem::path& target) {
    return std::filesystem::absolute(target).lexically_normal();
}

bool WriteDepfile(const std::filesystem::path& depfile, const std::filesystem::path& target,
                  const std::vector<std::filesystem::path>& dependencies, Outcome* outcome,
                  std::string* written) {
    const std::string text = DepfileText(DepfileTarget(target), dependencies);
    if (written != nullptr) {
        *written = text;
    }
    return WriteFile(depfile, text, outcome, "--depfile: ");
}

std::filesystem::path VariantSourcePath(GlslTarget target, const Variant& variant, Stage stage) {
    std::string name;
    for (const char c : variant.Id()) {
        name += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '.';
    }
    return std::filesystem::path(TargetName(target)) / variant.program /
           (name + (stage == Stage::kVertex ? ".vert" : ".frag"));
}

bool CheckVariantFileNames(const VariantConfig& config, const std::vector<Variant>& variants,
                           Outcome* outcome) {
    for (GlslTarget target : config.targets) {
        for (const Variant& variant : variants) {
            // The vertex file's name (.vert) is as long as the fragment file's (.frag).
            for (const std::filesystem::path& part :
                 VariantSourcePath(target, variant, Stage::kFragment)) {
                const std::size_t length = part.native().size();
                if (length <= kLongestFileName) {
                    continue;
                }
                const ProgramConfig* program = config.FindProgram(variant.program);
                const SourceLocation where = program != nullptr ? program->where : SourceLocation{};
                outcome->diagnostics.push_back(MakeError(
                        where.file.empty() ? config.path : where.file, where.line, where.column,
                        fmt::format("variant '{}' would be written to a file name of {} bytes "
                                    "('{}...'), past the {} a file system takes: shorten the "
                                    "program's name or its feature and axis names",
                                    variant.Id(), length, part.native().substr(0, 40),
                                    kLongestFileName)));
                outcome->status = Status::kUsage;
                return false;
            }
        }
    }
    return true;
}

bool WriteVariantSources(const VariantConfig& config, const std::vector<Variant>& variants,
                         const std::filesystem::path& folder, Outcome* outcome) {
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
                        outcome->diagnostics.push_back(
                                MakeError(path, 0, 0, "cannot read shader file: " + read.error));
                        outcome->status = Status::kUsage;
                        return false;
                    }
                    sources[path] = std::move(read.text);
                }
                const std::filesystem::path file =
                        folder / VariantSourcePath(target, variant, stage);
                const std::string text =
                        AssembleDriverSource(sources[path], variant.defines, stage, target);
                if (!HoldsExactly(file, text) && !WriteFile(file, text, outcome)) {
                    return false;
                }
            }
        }
    }
    return true;
}

void AddSourcePaths(const std::vector<Variant>& variants, stagefiles::ManifestFile* manifest) {
    std::map<std::string, const Variant*> by_id;
    for (const Variant& variant : variants) {
        by_id[variant.Id()] = &variant;
    }
    for (stagefiles::ManifestVariant& entry : manifest->variants) {
        const Variant& variant = *by_id.at(entry.id);
        GlslTarget target = GlslTarget::kEs100;
        TargetFromName(entry.target.value(), &target);
        entry.sources = {VariantSourcePath(target, variant, Stage::kVertex).generic_string(),
                         VariantSourcePath(target, variant, Stage::kFragment).generic_string()};
    }
}

}  // namespace tidepool::pipeline
