#include "tidepool/pipeline/OutputFiles.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/AtomicFile.h"

#include <fstream>

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

bool WriteFile(const std::filesystem::path& path, const std::string& text, Outcome* outcome,
               const std::string& prefix) {
    if (const std::string error = base::WriteFileAtomically(path, text); !error.empty()) {
        outcome->Fail(Status::kEnvironment, prefix + error);
        return false;
    }
    return true;
}

}  // namespace tidepool::pipeline
