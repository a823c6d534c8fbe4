// The first step of every stage: a configuration file loaded and expanded into its valid
// variants, within the limits the command was given.
#pragma once

#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/pipeline/Outcome.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tidepool::pipeline {

/// How many valid variants a stage may expand, and how many pruned combinations it lists.
struct MatrixLimits {
    std::optional<std::string> max_variants;  // --max-variants as typed; none: the file's
    bool allow_large_matrix = false;          // --allow-large-matrix: limits above kVariantCeiling
    std::uint64_t pruned_limit = 0;           // pruned combinations to list (expand --pruned)
};

/// A configuration loaded and expanded; `config` is empty when the outcome stopped.
struct LoadedMatrix {
    Outcome outcome;  // the loader's and expander's diagnostics, in that order
    std::optional<VariantConfig> config;
    ExpansionResult expansion;
};

/// Parses a whole number in [min, max], refusing signs, fractions, exponents and values that
/// overflow (which strtoull would wrap or cut short); false otherwise.
bool ParseWholeNumber(std::string_view text, std::uint64_t min, std::uint64_t max,
                      std::uint64_t* value);

/// "FLAG must be a whole number from MIN to MAX[ HINT], not 'TEXT'": why ParseWholeNumber refused
/// `text` for option `flag`.
std::string WholeNumberError(std::string_view flag, std::string_view text, std::uint64_t min,
                             std::uint64_t max, std::string_view hint);

/// Loads `config_path` and expands it (to at most `limits.max_variants` valid variants, or the
/// file's own max_variants). Stops with kUsage when --max-variants is out of range, the file does
/// not load or the expansion has errors.
LoadedMatrix LoadMatrix(const std::string& config_path, const MatrixLimits& limits = {});

/// Narrows `loaded` to the program `name`: its variants, rules' counts, presets and shader files
/// only, so that a build can run one command per program and touching one program's shader
/// reruns only that command. Stops `loaded` with kUsage, naming the programs there are, when the
/// configuration has no such program.
void KeepOnlyProgram(LoadedMatrix* loaded, const std::string& name);

}  // namespace tidepool::pipeline
