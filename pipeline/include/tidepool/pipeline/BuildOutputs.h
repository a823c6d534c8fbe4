// What `expand` and `validate` write for a build system (the CMake module
// cmake/TidepoolShaderVariants.cmake): driver-ready sources that keep their time stamp when
// unchanged, and a depfile naming every file the command read.
#pragma once

#include "tidepool/SourceAssembler.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/pipeline/Outcome.h"
#include "tidepool/stagefiles/ManifestFile.h"

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::pipeline {

/// Every file a command reads for `config`: the configuration itself, then each program's vertex
/// and fragment shader, once each, as absolute paths.
std::vector<std::filesystem::path> FilesRead(const VariantConfig& config);

/// Why `path` cannot be named in a depfile that both Make and Ninja read as that path ("" when
/// it can): a character either tool splits a name at or gives a meaning to (a tab, a newline,
/// '\\', ';', '|', '*', '=', quotes, ...), or a name Make takes for an archive member.
std::string DepfileRefusal(const std::filesystem::path& path);

/// A Make-syntax depfile (Ninja and Make both read it): `target: dep dep ...`, spaces, '#', ':'
/// and '$' escaped as both tools expect. Every path must pass DepfileRefusal.
std::string DepfileText(const std::filesystem::path& target,
                        const std::vector<std::filesystem::path>& dependencies);

/// The depfile's target for the output `target`: its absolute, normal path.
std::filesystem::path DepfileTarget(const std::filesystem::path& target);

/// Checks, before any work, that a depfile can name `target` and every dependency; otherwise
/// records "error: --depfile: why; rename it, or leave out --depfile" (kUsage) in `outcome` and
/// returns false.
bool CheckDepfileNames(const std::filesystem::path& target,
                       const std::vector<std::filesystem::path>& dependencies, Outcome* outcome);

/// Writes DepfileText(DepfileTarget(target), dependencies) to `depfile` atomically (and, when
/// `written` is given, the text there); on failure records "error: --depfile: why"
/// (kEnvironment) in `outcome` and returns false.
bool WriteDepfile(const std::filesystem::path& depfile, const std::filesystem::path& target,
                  const std::vector<std::filesystem::path>& dependencies, Outcome* outcome,
                  std::string* written = nullptr);

/// Where a variant's driver-ready stage source lives below an output folder:
/// `<target>/<program>/<variant id, made a safe file name>.vert|.frag`.
std::filesystem::path VariantSourcePath(GlslTarget target, const Variant& variant, Stage stage);

/// The longest file name (one path component) Linux file systems take, in bytes.
inline constexpr std::size_t kLongestFileName = 255;

/// False, with an error in `outcome` (Status::kUsage) at the program of the first one, when a
/// variant's source file (VariantSourcePath) would have a name longer than kLongestFileName: the
/// write would fail with "File name too long" after the work, naming a staging folder.
bool CheckVariantFileNames(const VariantConfig& config, const std::vector<Variant>& variants,
                           Outcome* outcome);

/// Writes every variant's driver-ready vertex and fragment source for every target of `config`
/// below `folder` (at VariantSourcePath), each atomically and only when its content changed, so
/// that whatever depends on an unchanged variant is not rebuilt. On failure records why in
/// `outcome` (kUsage: a shader file cannot be read; kEnvironment: a write failed) and returns
/// false.
bool WriteVariantSources(const VariantConfig& config, const std::vector<Variant>& variants,
                         const std::filesystem::path& folder, Outcome* outcome);

/// Records in each variant of `manifest` where WriteVariantSources put its stages (`sources`,
/// relative to the manifest's folder). Every variant of the manifest must be among `variants`
/// and have its target.
void AddSourcePaths(const std::vector<Variant>& variants, stagefiles::ManifestFile* manifest);

}  // namespace tidepool::pipeline
