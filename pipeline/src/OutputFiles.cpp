#include "tidepool/pipeline/OutputFiles.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/AtomicFile.h"

#include <fstream>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace tidepool::pipeline {

Status PublishStatus(const base::PublishError& error) {
    return error.failure == base::PublishFailure::kRefused ? Status::kUsage : Status::kEnvironment;
}

std::unique_ptr<base::FolderPublisher> BeginPublishing(const std::filesystem::path& target,
                                                       const std::string& writer,
                                                       Outcome* outcome) {
    base::PublishError begin;
    std::unique_ptr<base::FolderPublisher> publisher =
            base::FolderPublisher::Begin(target, writer, &begin);
    if (!publisher) {
        outcome->Fail(PublishStatus(begin), begin.message);
    }
    return publisher;
}

bool Publish(base::FolderPublisher& publisher, Outcome* outcome) {
    if (const base::PublishError error = publisher.Publish(); error.Failed()) {
        outcome->Fail(PublishStatus(error), error.message);
        return false;
    }
    return true;
}

Outcome WriteOwnJson(const std::filesystem::path& folder, const std::string& file_name,
                     const std::string& schema, const std::string& what, const std::string& text,
                     bool check_only) {
    Outcome outcome;
    const std::filesystem::path path = folder / file_name;
    std::error_code ec;
    if (std::filesystem::exists(path, ec) && !base::IsTidepoolOutput(folder)) {
        // A file named manifest.json is common (web apps, packages); the schema key inside it
        // is what says it is ours.
        std::ifstream in(path, std::ios::binary);
        const nlohmann::json existing = nlohmann::json::parse(in, nullptr, false);
        const bool ours =
                existing.is_object() && existing.contains("schema") && existing["schema"] == schema;
        if (!ours) {
            outcome.Fail(Status::kUsage,
                         fmt::format("{}: exists and is not a tidepool {} (no \"schema\": "
                                     "\"{}\"); nothing was changed. Choose another --out folder, "
                                     "or move the file yourself.",
                                     path.string(), what, schema));
            return outcome;
        }
    }
    if (!check_only) {
        WriteFile(path, text, &outcome);
    }
    return outcome;
}

Outcome WriteManifest(const std::filesystem::path& folder, const std::string& text,
                      bool check_only) {
    return WriteOwnJson(folder, "manifest.json", std::string(stagefiles::kManifestSchemaName),
                        "manifest", text, check_only);
}

namespace {

// Whether `a` and `b` name one file: the same file when both exist (links included), else the
// same path once the links of its existing part are followed.
bool SameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code ec;
    if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec)) {
        return std::filesystem::equivalent(a, b, ec) && !ec;
    }
    const std::filesystem::path canonical_a = std::filesystem::weakly_canonical(a, ec);
    if (ec) {
        return false;
    }
    const std::filesystem::path canonical_b = std::filesystem::weakly_canonical(b, ec);
    return !ec && canonical_a == canonical_b;
}

// Whether writing `path` creates `folder` (or uses it): `folder` is one of `path`'s folders,
// once the links of their existing parts are followed.
bool IsFolderOf(const std::filesystem::path& folder, const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::path outer = std::filesystem::weakly_canonical(folder, ec);
    if (ec) {
        return false;
    }
    const std::filesystem::path inner = std::filesystem::weakly_canonical(path, ec).parent_path();
    if (ec) {
        return false;
    }
    auto o = outer.begin();
    auto i = inner.begin();
    for (; o != outer.end() && i != inner.end() && *o == *i; ++o, ++i) {
    }
    return o == outer.end();
}

// Why `path` cannot be written as a file ("" when it can): it is a folder, or a file stands
// where one of its folders belongs.
std::string NotAFilePath(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        return path.string() + " is a folder; give the path of a file";
    }
    if (const std::optional<std::filesystem::path> file =
                base::FileInPlaceOfFolder(path.parent_path())) {
        return fmt::format("{}: {} is a file, not a folder; choose another path", path.string(),
                           file->string());
    }
    return {};
}

// Whether `path` is a device, a pipe or a socket: written as a stream, never replaced.
bool IsStream(const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    return !ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
           !std::filesystem::is_directory(status);
}

}  // namespace

bool CheckPlannedOutputs(const std::vector<PlannedOutput>& outputs,
                         const std::vector<std::filesystem::path>& inputs, Outcome* outcome) {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const PlannedOutput& output = outputs[i];
        if (const std::string why = NotAFilePath(output.path); !why.empty()) {
            outcome->Fail(Status::kUsage, fmt::format("{}: {}", output.flag, why));
            return false;
        }
        if (IsStream(output.path)) {
            continue;
        }
        for (const std::filesystem::path& input : inputs) {
            if (SameFile(output.path, input)) {
                outcome->Fail(Status::kUsage,
                              fmt::format("{}: {} is a file this command reads; writing it "
                                          "would replace it: choose another path",
                                          output.flag, output.path.string()));
                return false;
            }
        }
        for (std::size_t j = 0; j < outputs.size(); ++j) {
            if (j < i && SameFile(output.path, outputs[j].path)) {
                outcome->Fail(Status::kUsage,
                              fmt::format("{}: {} is also where {} writes; give each output "
                                          "its own path",
                                          output.flag, output.path.string(), outputs[j].flag));
                return false;
            }
            if (j != i && IsFolderOf(output.path, outputs[j].path)) {
                outcome->Fail(Status::kUsage,
                              fmt::format("{}: {} is the folder {} writes {} into; give the "
                                          "path of a file beside it",
                                          output.flag, output.path.string(), outputs[j].flag,
                                          outputs[j].path.filename().string()));
                return false;
            }
        }
    }
    return true;
}

bool WriteFile(const std::filesystem::path& path, const std::string& text, Outcome* outcome,
               const std::string& prefix) {
    if (const std::string error = base::WriteFileAtomically(path, text); !error.empty()) {
        outcome->Fail(Status::kEnvironment, prefix + error);
        return false;
    }
    return true;
}

}  // namespace tidepool::pipeline
