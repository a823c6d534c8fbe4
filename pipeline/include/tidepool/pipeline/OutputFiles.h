// Where the stages write: output folders published whole, and the stage files (manifest.json,
// stability.json, ...) that tidepool replaces only when they are its own.
#pragma once

#include "tidepool/base/FolderPublisher.h"
#include "tidepool/pipeline/Outcome.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace tidepool::pipeline {

/// The status of a failed publication: kUsage when the folder is someone else's (choose
/// another), kEnvironment when the file system failed (disk full, permissions).
Status PublishStatus(const base::PublishError& error);

/// Begins publishing the output folder `target` for `writer` ("tidepool expand"); on failure
/// records why in `outcome` (PublishStatus) and returns null.
std::unique_ptr<base::FolderPublisher> BeginPublishing(const std::filesystem::path& target,
                                                       const std::string& writer, Outcome* outcome);

/// Publishes what `publisher` staged; on failure records why in `outcome` (PublishStatus) and
/// returns false.
bool Publish(base::FolderPublisher& publisher, Outcome* outcome);

/// Writes `text` to `folder`/`file_name` atomically, refusing (kUsage, the file named as not a
/// tidepool `what`, nothing changed) to overwrite a file there whose "schema" is not `schema`,
/// unless the folder carries tidepool's marker. kEnvironment when the write fails. With
/// `check_only`, writes nothing.
Outcome WriteOwnJson(const std::filesystem::path& folder, const std::string& file_name,
                     const std::string& schema, const std::string& what, const std::string& text,
                     bool check_only = false);

/// WriteOwnJson for `folder`/manifest.json (schema stagefiles::kManifestSchemaName).
Outcome WriteManifest(const std::filesystem::path& folder, const std::string& text,
                      bool check_only = false);

/// A file a command is about to write, and the flag that named it ("--depfile").
struct PlannedOutput {
    std::string flag;
    std::filesystem::path path;
};

/// Checks, before any work, the files a command will write: none may be a folder, lie below a
/// file, be the same file as one of `inputs` (the files the command reads) or as another output,
/// or be a folder another output is written into. Otherwise records why, naming the flag and the
/// fix (kUsage), in `outcome` and returns false. A device or pipe (`--output-file /dev/stdout`) is
/// written as a stream and not compared.
bool CheckPlannedOutputs(const std::vector<PlannedOutput>& outputs,
                         const std::vector<std::filesystem::path>& inputs, Outcome* outcome);

/// Writes `text` to `path` atomically; on failure records "error: PREFIXwhy" (kEnvironment) in
/// `outcome` and returns false.
bool WriteFile(const std::filesystem::path& path, const std::string& text, Outcome* outcome,
               const std::string& prefix = "");

}  // namespace tidepool::pipeline
