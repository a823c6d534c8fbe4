// The variant matrix as data: programs, their features and axes, the rules that prune them,
// presets and GLSL ES targets. Loaded from variants.yaml (schema in README.md).
#pragma once

#include "tidepool/Diagnostic.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool {

/// Where a value was written in the configuration file (1-based; 0 when unknown).
struct SourceLocation {
    std::string file;
    int line = 0;
    int column = 0;
};

/// A GLSL ES language version a variant is validated and rendered for; the WebGL targets are
/// GLSL ES 1.00 (WebGL 1) and 3.00 (WebGL 2) with the rules browsers add on top.
enum class GlslTarget { kEs100, kEs300, kWebGl1, kWebGl2 };

/// The GLSL ES version a target compiles as: 100 or 300.
int TargetVersion(GlslTarget target);

/// True for kWebGl1 and kWebGl2.
bool IsWebGlTarget(GlslTarget target);

/// The `#version` line text for a target, e.g. "#version 100".
std::string VersionDirective(GlslTarget target);

/// The short name used in ids and JSON: "100", "300es", "webgl1" or "webgl2".
std::string TargetName(GlslTarget target);

/// The target a name of `targets:` or `--target` stands for ("100"; "300", "300es" or
/// "300 es"; "webgl1"; "webgl2"); false for any other name.
bool TargetFromName(std::string_view name, GlslTarget* target);

/// A boolean feature: either absent or `#define NAME 1`.
struct Feature {
    std::string name;
    SourceLocation where;
};

/// An enumerated axis: exactly one value is chosen; value `v` of axis `A` becomes `#define A_V 1`
/// with `V` upper-cased (`REFLECTION: [planar, cubemap]` → `REFLECTION_PLANAR`,
/// `REFLECTION_CUBEMAP`). An axis may name a default value that adds no define: the shader reads
/// "no `A_*` define" as the default, so adding such an axis to a program leaves the ids of its
/// existing variants unchanged.
struct Axis {
    std::string name;
    std::vector<std::string> values;
    SourceLocation where;
    // One of `values`, or empty when every value adds a define. The initializer lets
    // `Axis{name, values, where}` leave it out without a -Wmissing-field-initializers warning.
    std::string default_value = {};

    /// The define a value of this axis turns into; "" for the default value, which adds none.
    std::string DefineFor(std::string_view value) const;
};

/// The three kinds of pruning rule.
enum class RuleKind {
    kRequires,            // `if: A, requires: [B, ...]`: A is only valid when every B is present
    kExcludes,            // `if: A, excludes: [B, ...]`: A is only valid when no B is present
    kExcludeCombination,  // `exclude: [A, B, ...]`: this exact set of defines together is invalid
};

/// A pruning rule over define names (features or axis-value defines).
struct Rule {
    RuleKind kind = RuleKind::kRequires;
    std::string subject;              // the `if:` define (empty for kExcludeCombination)
    std::vector<std::string> others;  // required / excluded defines, or the excluded combination
    std::string reason;               // optional, written by the user
    SourceLocation where;

    /// A one-line human description, e.g. "ENABLE_FRESNEL requires ENABLE_REFRACTION".
    std::string Describe() const;
};

/// One shader program: a vertex and a fragment file plus its variant axes.
struct ProgramConfig {
    std::string name;
    std::string vertex_path;  // as written in the YAML, relative to the YAML file's folder
    std::string fragment_path;
    std::vector<Feature> features;
    std::vector<Axis> axes;
    std::vector<Rule> rules;
    SourceLocation where;

    /// Every define name this program can emit (features, then axis values but not defaults).
    std::vector<std::string> AllDefines() const;
};

/// Render-pass options of a render configuration (the runner reads them; the compiler checks them).
struct PassOptions {
    // Texture sizes, powers of two; 0 follows the window by the demo's rule (DemoTargetSize).
    int reflection_size = 0;
    int refraction_size = 0;
    bool low_res_water = false;    // render the water into a small texture, then apply it
    std::string clip = "oblique";  // "oblique" (modified projection) or "discard"
    bool culling = true;           // CPU culling of objects per pass
    // With ENABLE_FOG: the underwater depth fog on the models of the refraction pass
    // (whitepaper 2.4.1). Off leaves the water's distance fog, the sky's fog, the refraction's
    // clear colour and its omitted sky as they are, so that it alone is whitepaper row 4.
    bool depth_fog = true;
};

/// The demo's render-to-texture size for a window: the largest power of two not above the
/// window's smaller side (256 at 640x480, 128 at 320x240). Fails (returns 1) for an empty window.
int DemoTargetSize(int width, int height);

/// The reflection texture's size in a width x height window: passes.reflection_size, or
/// DemoTargetSize when that is 0. Never fails.
int ReflectionSize(const PassOptions& passes, int width, int height);

/// The refraction texture's size, by the same rule as ReflectionSize. Never fails.
int RefractionSize(const PassOptions& passes, int width, int height);

/// A named configuration: a program, its defines and pass options (e.g. the whitepaper's setups).
struct Preset {
    std::string name;
    std::string description;
    std::string program;
    std::vector<std::string> defines;
    /// For a program that picks its features at run time (water_uniform): the `water` defines
    /// whose `uniform bool`s are switched on, e.g. ENABLE_FOG → bFog (shaders/INTERFACE.md).
    std::vector<std::string> runtime_features;
    PassOptions passes;
    SourceLocation where;
};

/// The limit that no variants.yaml and no --max-variants lifts without --allow-large-matrix.
/// Every valid variant is compiled (two stages and a link, about a millisecond each) and rendered
/// and timed by `run`, so 65,536 variants already cost minutes to validate and hours to render;
/// a larger matrix is almost always a missing rule, not a wish.
inline constexpr std::uint64_t kVariantCeiling = 65536;

/// The limit even --allow-large-matrix cannot lift: 2^24 variants (about 100 bytes each as ids
/// and defines) already hold 1.6 GB before one stage is compiled.
inline constexpr std::uint64_t kLargeVariantCeiling = 16777216;

/// The whole configuration file.
struct VariantConfig {
    std::string path;                // the file as named by the user
    std::filesystem::path base_dir;  // shader paths are relative to this folder
    int version = 1;
    std::uint64_t max_variants = 4096;  // valid variants (after pruning), all programs together
    SourceLocation max_variants_where;  // where the file sets max_variants; empty when it does not
    std::vector<GlslTarget> targets;
    std::vector<ProgramConfig> programs;
    std::vector<Preset> presets;

    /// The program with this name, or nullptr.
    const ProgramConfig* FindProgram(std::string_view name) const;
    /// The preset with this name, or nullptr.
    const Preset* FindPreset(std::string_view name) const;
    /// A shader path as the file system sees it (base_dir / path).
    std::filesystem::path Resolve(const std::string& shader_path) const;
};

/// A configuration, or why there is none: every problem found, not just the first.
struct ConfigResult {
    std::optional<VariantConfig> config;
    std::vector<Diagnostic> diagnostics;
};

/// Reads and checks a variants.yaml; fails (no config, diagnostics at file:line:col) on unreadable
/// or malformed YAML, unknown keys, duplicate keys, unknown names in rules or presets (including
/// the would-be define of an axis default), invalid define names, an axis default that is not one
/// of its values, missing shader files, or rules that leave a program with no variant.
ConfigResult LoadVariantConfig(const std::filesystem::path& path);

/// The same as LoadVariantConfig for text already in memory; `file_name` is used in diagnostics
/// and `base_dir` to resolve shader paths.
ConfigResult ParseVariantConfig(std::string_view text, const std::string& file_name,
                                const std::filesystem::path& base_dir);

/// True when `name` can be a GLSL ES macro name: an identifier that neither starts with `GL_`
/// nor contains `__` (both reserved by the GLSL ES preprocessor).
bool IsValidDefineName(std::string_view name);

}  // namespace tidepool
