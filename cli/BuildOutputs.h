// What `expand` and `validate` write for a build system (the CMake module
// cmake/TidepoolShaderVariants.cmake): one program's slice of a matrix, driver-ready sources that
// keep their time stamp when unchanged, and a depfile naming every file the command read.
#pragma once

#include "tidepool/SourceAssembler.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "CliSupport.h"

namespace tidepool::cli {

/// Narrows `loaded` to the program `name`: its variants, rules' counts, presets and shader files
/// only, so that a build can run one command per program and touching one program's shader
/// reruns only that command. Prints "error: ..." naming the programs there are and returns false
/// when the configuration has no such program.
bool KeepOnlyProgram(LoadedMatrix* loaded, const std::string& name);

/// Every file a command reads for `config`: the configuration itself, then each program's vertex
/// and fragment shader, once each, as absolute paths.
std::vector<std::filesystem::path> FilesRead(const VariantConfig& config);

/// A Make-syntax depfile (Ninja and Make both read it): `target: dep dep ...`, spaces, '#' and
/// '$' escaped as both tools expect.
std::string DepfileText(const std::filesystem::path& target,
                        const std::vector<std::filesystem::path>& dependencies);

/// Writes DepfileText(target, FilesRead(config)) to `depfile` atomically; prints why not and
/// returns kExitEnvironment when it cannot, kExitOk otherwise.
int WriteDepfile(const std::filesystem::path& depfile, const std::filesystem::path& target,
                 const VariantConfig& config);

/// Where a variant's driver-ready stage source lives below an output folder:
/// `<target>/<program>/<variant id, made a safe file name>.vert|.frag`.
std::filesystem::path VariantSourcePath(GlslTarget target, const Variant& variant, Stage stage);

/// Writes every variant's driver-ready vertex and fragment source for every target of `config`
/// below `folder` (at VariantSourcePath), each atomically and only when its content changed, so
/// that whatever depends on an unchanged variant is not rebuilt. Returns kExitOk, or prints why
/// not and returns kExitUsage (a shader file cannot be read) or kExitEnvironment (a write failed).
int WriteVariantSources(const VariantConfig& config, const std::vector<Variant>& variants,
                        const std::filesystem::path& folder);

}  // namespace tidepool::cli
