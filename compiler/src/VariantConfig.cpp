// Loading variants.yaml on top of the shared YAML reading layer (YamlReader.h): no exception
// leaves the library and every position becomes a 1-based file:line:col.
#include "tidepool/VariantConfig.h"

#include "tidepool/TextFile.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "YamlReader.h"
#include <fmt/format.h>

namespace tidepool {

int TargetVersion(GlslTarget target) {
    return target == GlslTarget::kEs300 || target == GlslTarget::kWebGl2 ? 300 : 100;
}

bool IsWebGlTarget(GlslTarget target) {
    return target == GlslTarget::kWebGl1 || target == GlslTarget::kWebGl2;
}

std::string VersionDirective(GlslTarget target) {
    return TargetVersion(target) == 300 ? "#version 300 es" : "#version 100";
}

std::string TargetName(GlslTarget target) {
    switch (target) {
        case GlslTarget::kEs100:
            return "100";
        case GlslTarget::kEs300:
            return "300es";
        case GlslTarget::kWebGl1:
            return "webgl1";
        case GlslTarget::kWebGl2:
            return "webgl2";
    }
    return "100";
}

bool TargetFromName(std::string_view name, GlslTarget* target) {
    if (name == "100") {
        *target = GlslTarget::kEs100;
    } else if (name == "300" || name == "300es" || name == "300 es") {
        *target = GlslTarget::kEs300;
    } else if (name == "webgl1") {
        *target = GlslTarget::kWebGl1;
    } else if (name == "webgl2") {
        *target = GlslTarget::kWebGl2;
    } else {
        return false;
    }
    return true;
}

namespace {

// `A_V` for value `v` of axis `A`, whether or not the value is the axis default.
std::string ValueDefine(std::string_view axis, std::string_view value) {
    std::string define = std::string(axis) + "_";
    for (char c : value) {
        define += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return define;
}

// The axis whose default value would turn into `define` if defaults added defines, or nullptr.
const Axis* AxisDefaultingTo(const ProgramConfig& program, std::string_view define) {
    for (const Axis& axis : program.axes) {
        if (!axis.default_value.empty() && ValueDefine(axis.name, axis.default_value) == define) {
            return &axis;
        }
    }
    return nullptr;
}

// Rules and presets are written over define names, and a default has none to test or to set.
std::string DefaultNamedMessage(const std::string& define, const Axis& axis) {
    return fmt::format(
            "'{}' is the default of axis '{}' and adds no define; leave it out (a "
            "preset) or write the rule over the other values",
            define, axis.name);
}

}  // namespace

std::string Axis::DefineFor(std::string_view value) const {
    if (!default_value.empty() && value == default_value) {
        return {};
    }
    return ValueDefine(name, value);
}

std::string Rule::Describe() const {
    auto join = [](const std::vector<std::string>& names) {
        return fmt::format("{}", fmt::join(names, ", "));
    };
    switch (kind) {
        case RuleKind::kRequires:
            return fmt::format("{} requires {}", subject, join(others));
        case RuleKind::kExcludes:
            return fmt::format("{} excludes {}", subject, join(others));
        case RuleKind::kExcludeCombination:
            return fmt::format("excluded combination {}", join(others));
    }
    return {};
}

std::vector<std::string> ProgramConfig::AllDefines() const {
    std::vector<std::string> names;
    for (const Feature& feature : features) {
        names.push_back(feature.name);
    }
    for (const Axis& axis : axes) {
        for (const std::string& value : axis.values) {
            if (std::string define = axis.DefineFor(value); !define.empty()) {
                names.push_back(std::move(define));
            }
        }
    }
    return names;
}

int DemoTargetSize(int width, int height) {
    const int side = std::min(width, height);
    int size = 1;
    while (size <= side / 2) {
        size *= 2;
    }
    return size;
}

int ReflectionSize(const PassOptions& passes, int width, int height) {
    return passes.reflection_size > 0 ? passes.reflection_size : DemoTargetSize(width, height);
}

int RefractionSize(const PassOptions& passes, int width, int height) {
    return passes.refraction_size > 0 ? passes.refraction_size : DemoTargetSize(width, height);
}

const ProgramConfig* VariantConfig::FindProgram(std::string_view name) const {
    auto it = std::find_if(programs.begin(), programs.end(),
                           [&](const ProgramConfig& p) { return p.name == name; });
    return it == programs.end() ? nullptr : &*it;
}

const Preset* VariantConfig::FindPreset(std::string_view name) const {
    auto it = std::find_if(presets.begin(), presets.end(),
                           [&](const Preset& p) { return p.name == name; });
    return it == presets.end() ? nullptr : &*it;
}

std::filesystem::path VariantConfig::Resolve(const std::string& shader_path) const {
    std::filesystem::path p(shader_path);
    return p.is_absolute() ? p : base_dir / p;
}

bool IsValidDefineName(std::string_view name) {
    if (name.empty()) {
        return false;
    }
    auto is_start = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
    auto is_rest = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    if (!is_start(name.front()) || !std::all_of(name.begin(), name.end(), is_rest)) {
        return false;
    }
    return name.substr(0, 3) != "GL_" && name.find("__") == std::string_view::npos;
}

namespace {

// Collects diagnostics while walking the YAML tree; every check reports and carries on, so the
// user sees all problems of a file at once.
class ConfigParser : public YamlReader {
public:
    ConfigParser(std::string file_name, std::filesystem::path base_dir)
        : YamlReader(std::move(file_name)), base_dir_(std::move(base_dir)) {}

    ConfigResult Parse(std::string_view text);

private:
    // The names of a name or a list of names; a name listed twice is an error unless
    // `repeats_checked` (the caller says so in its own words).
    std::vector<std::string> NameList(const YAML::Node& node, std::string_view what,
                                      bool repeats_checked = false);
    bool ReadBool(const YAML::Node& node, std::string_view what, bool fallback);
    int ReadInt(const YAML::Node& node, std::string_view what, int fallback);

    void ParseTargets(const YAML::Node& node, VariantConfig& config);
    ProgramConfig ParseProgram(const std::string& name, const YAML::Node& key,
                               const YAML::Node& node);
    Axis ParseAxis(const YAML::Node& key, const YAML::Node& node);
    void ParseRule(const YAML::Node& node, ProgramConfig& program);
    Preset ParsePreset(const std::string& name, const YAML::Node& key, const YAML::Node& node);
    PassOptions ParsePasses(const YAML::Node& node);
    void CheckProgram(const ProgramConfig& program);
    void CheckPreset(const Preset& preset, const VariantConfig& config);

    std::filesystem::path base_dir_;
};

std::vector<std::string> ConfigParser::NameList(const YAML::Node& node, std::string_view what,
                                                bool repeats_checked) {
    std::vector<std::string> names;
    if (!node || node.IsNull()) {
        return names;
    }
    if (node.IsScalar()) {
        names.push_back(node.Scalar());
        return names;
    }
    if (!node.IsSequence()) {
        Error(node, fmt::format("{} must be a name or a list of names", what));
        return names;
    }
    for (const YAML::Node& item : node) {
        if (!ExpectScalar(item, what)) {
            continue;
        }
        // A name twice says nothing more, and is often a typo for another name.
        if (!repeats_checked &&
            std::find(names.begin(), names.end(), item.Scalar()) != names.end()) {
            Error(item, fmt::format("'{}' is named twice in {}; remove one", item.Scalar(), what));
            continue;
        }
        names.push_back(item.Scalar());
    }
    return names;
}

bool ConfigParser::ReadBool(const YAML::Node& node, std::string_view what, bool fallback) {
    bool value = fallback;
    if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
        Error(node, fmt::format("{} must be true or false", what));
        return fallback;
    }
    return value;
}

int ConfigParser::ReadInt(const YAML::Node& node, std::string_view what, int fallback) {
    int value = fallback;
    if (!node.IsScalar() || !YAML::convert<int>::decode(node, value)) {
        Error(node, fmt::format("{} must be an integer", what));
        return fallback;
    }
    return value;
}

void ConfigParser::ParseTargets(const YAML::Node& node, VariantConfig& config) {
    for (const std::string& name : NameList(node, "targets")) {
        GlslTarget target = GlslTarget::kEs100;
        if (TargetFromName(name, &target)) {
            if (std::find(config.targets.begin(), config.targets.end(), target) !=
                config.targets.end()) {
                // NameList refuses a spelling twice; two spellings of one target ("300",
                // "300es") validated every variant twice.
                Error(node, fmt::format("targets names the target '{}' twice, by two of its "
                                        "spellings; list it once",
                                        name));
            }
            config.targets.push_back(target);
        } else {
            Error(node,
                  fmt::format("unknown GLSL ES target '{}'; use 100, 300, webgl1 or webgl2", name));
        }
    }
    if (std::find(config.targets.begin(), config.targets.end(), GlslTarget::kEs100) ==
        config.targets.end()) {
        Error(node, "targets must include 100 (GLSL ES 1.00 is the shaders' own language)");
    }
}

ProgramConfig ConfigParser::ParseProgram(const std::string& name, const YAML::Node& key,
                                         const YAML::Node& node) {
    ProgramConfig program;
    program.name = name;
    program.where = At(key);
    if (!IsValidDefineName(name)) {
        Error(key,
              fmt::format("program name '{}' must be an identifier (letters, digits, _)", name));
    }
    const std::string what = fmt::format("program '{}'", name);
    if (!ExpectMap(node, what)) {
        return program;
    }
    CheckKeys(node, what, {"vertex", "fragment", "features", "axes", "rules", "description"});
    for (const char* stage : {"vertex", "fragment"}) {
        const YAML::Node path = node[stage];
        if (!path) {
            Error(key, fmt::format("{} has no '{}' shader file; add `{}: shaders/FILE`", what,
                                   stage, stage));
            continue;
        }
        if (!ExpectScalar(path, fmt::format("{} '{}'", what, stage))) {
            continue;
        }
        const std::string value = path.Scalar();
        (std::string_view(stage) == "vertex" ? program.vertex_path : program.fragment_path) = value;
        if (value.empty()) {  // else it named the configuration's folder: "is a folder (vc/)"
            Error(path, fmt::format("{} '{}' is empty; give the shader file's path, e.g. `{}: "
                                    "shaders/FILE`",
                                    what, stage, stage));
            continue;
        }
        std::error_code ec;
        std::filesystem::path resolved(value);
        if (!resolved.is_absolute()) {
            resolved = base_dir_ / resolved;
        }
        const std::filesystem::file_status status = std::filesystem::status(resolved, ec);
        if (std::filesystem::is_directory(status)) {
            Error(path, fmt::format("{} shader file '{}' is a folder ({}), not a file", stage,
                                    value, resolved.string()));
        } else if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
            Error(path, fmt::format("{} shader file '{}' is not a regular file ({}); a FIFO or "
                                    "device cannot be validated",
                                    stage, value, resolved.string()));
        } else if (ec && ec != std::errc::no_such_file_or_directory) {
            // A loop of links, a folder on the way that cannot be searched: not "not found".
            Error(path, fmt::format("{} shader file '{}' cannot be read ({}): {}", stage, value,
                                    resolved.string(), ec.message()));
        } else if (!std::filesystem::is_regular_file(status)) {
            Error(path, fmt::format("{} shader file '{}' not found (looked for {}); paths are "
                                    "relative to the folder of {}",
                                    stage, value, resolved.string(), FileName()));
        }
    }

    std::set<std::string> declared;
    auto declare = [&](const std::string& define, const YAML::Node& where) {
        if (!IsValidDefineName(define)) {
            Error(where, fmt::format("'{}' is not a valid GLSL define name: use letters, digits "
                                     "and _, start with a letter, no 'GL_' prefix and no '__'",
                                     define));
        }
        if (!declared.insert(define).second) {
            Error(where,
                  fmt::format("feature '{}' is declared twice in {}; remove one", define, what));
        }
    };
    if (const YAML::Node features = node["features"]) {
        if (!features.IsSequence()) {
            Error(features, "features must be a list of define names");
        } else {
            for (const YAML::Node& item : features) {
                if (ExpectScalar(item, "a feature")) {
                    declare(item.Scalar(), item);
                    program.features.push_back(Feature{item.Scalar(), At(item)});
                }
            }
        }
    }
    if (const YAML::Node axes = node["axes"]) {
        if (ExpectMap(axes, "axes")) {
            for (auto it = axes.begin(); it != axes.end(); ++it) {
                Axis axis = ParseAxis(it->first, it->second);
                const YAML::Node values_node = it->second.IsMap() && it->second["values"]
                                                       ? it->second["values"]
                                                       : it->second;
                std::set<std::string> values;
                for (const std::string& value : axis.values) {
                    if (!values.insert(value).second) {
                        Error(values_node,
                              fmt::format("axis '{}' lists value '{}' twice", axis.name, value));
                        continue;
                    }
                    // The default adds no define, so there is no name to declare or validate.
                    if (value != axis.default_value) {
                        declare(axis.DefineFor(value), values_node);
                    }
                }
                program.axes.push_back(std::move(axis));
            }
        }
    }
    if (const YAML::Node rules = node["rules"]) {
        if (!rules.IsSequence()) {
            Error(rules, "rules must be a list");
        } else {
            for (const YAML::Node& rule : rules) {
                ParseRule(rule, program);
            }
        }
    }
    return program;
}

// `A: [a, b]` (every value adds a define) or `A: { values: [a, b], default: a }` (the default adds
// none).
Axis ConfigParser::ParseAxis(const YAML::Node& key, const YAML::Node& node) {
    Axis axis;
    axis.name = key.IsScalar() ? key.Scalar() : "";
    axis.where = At(key);
    if (!IsValidDefineName(axis.name)) {
        // Its values' defines start with it: an empty or a list key made "_A" of value a.
        Error(key, fmt::format("an axis is named by an identifier (letters, digits and '_', not "
                               "starting with a digit), not {}",
                               key.IsScalar() ? fmt::format("'{}'", axis.name)
                                              : std::string("a list or a mapping")));
    }
    const std::string what = fmt::format("axis '{}'", axis.name);
    if (!node.IsMap()) {
        axis.values = NameList(node, what, /*repeats_checked=*/true);
    } else {
        CheckKeys(node, what, {"values", "default"});
        if (!node["values"]) {
            Error(key, fmt::format("{} has no 'values'; write `{}: {{ values: [a, b], default: a "
                                   "}}`",
                                   what, axis.name));
            return axis;
        }
        axis.values = NameList(node["values"], what, /*repeats_checked=*/true);
        if (const YAML::Node default_node = node["default"]) {
            if (ExpectScalar(default_node, fmt::format("the default of {}", what))) {
                const std::string value = default_node.Scalar();
                if (std::find(axis.values.begin(), axis.values.end(), value) == axis.values.end()) {
                    Error(default_node, fmt::format("the default '{}' of {} is not one of its "
                                                    "values: {}",
                                                    value, what, fmt::join(axis.values, ", ")));
                } else {
                    axis.default_value = value;
                }
            }
        }
    }
    if (axis.values.size() < 2) {
        Error(key, fmt::format("axis '{}' needs at least two values (a single value is a "
                               "feature that is always on)",
                               axis.name));
    }
    return axis;
}

void ConfigParser::ParseRule(const YAML::Node& node, ProgramConfig& program) {
    if (!ExpectMap(node, "a rule")) {
        return;
    }
    CheckKeys(node, "a rule", {"if", "requires", "excludes", "exclude", "reason"});
    Rule rule;
    rule.where = At(node);
    if (node["reason"] && ExpectScalar(node["reason"], "reason")) {
        rule.reason = node["reason"].Scalar();
    }
    const bool has_if = static_cast<bool>(node["if"]);
    const bool has_requires = static_cast<bool>(node["requires"]);
    const bool has_excludes = static_cast<bool>(node["excludes"]);
    const bool has_exclude = static_cast<bool>(node["exclude"]);
    if (has_exclude && !has_if && !has_requires && !has_excludes) {
        rule.kind = RuleKind::kExcludeCombination;
        rule.others = NameList(node["exclude"], "exclude");
        if (rule.others.size() < 2) {
            Error(node,
                  "an `exclude:` combination needs at least two defines; to forbid one "
                  "define, remove it from the features");
        }
    } else if (has_if && (has_requires != has_excludes) && !has_exclude) {
        if (ExpectScalar(node["if"], "if")) {
            rule.subject = node["if"].Scalar();
        }
        rule.kind = has_requires ? RuleKind::kRequires : RuleKind::kExcludes;
        rule.others = NameList(has_requires ? node["requires"] : node["excludes"],
                               has_requires ? "requires" : "excludes");
    } else {
        Error(node,
              "a rule is either `{if: A, requires: [B]}`, `{if: A, excludes: [B]}` or "
              "`{exclude: [A, B]}`");
        return;
    }
    const std::vector<std::string> known = program.AllDefines();
    auto check = [&](const std::string& name) {
        if (std::find(known.begin(), known.end(), name) != known.end()) {
            return;
        }
        if (const Axis* axis = AxisDefaultingTo(program, name)) {
            Error(node, DefaultNamedMessage(name, *axis));
        } else {
            Error(node, fmt::format("rule names unknown feature '{}' in program '{}'; known: {}",
                                    name, program.name, fmt::join(known, ", ")));
        }
    };
    if (!rule.subject.empty()) {
        check(rule.subject);
    }
    for (const std::string& name : rule.others) {
        check(name);
    }
    if (!rule.subject.empty() &&
        std::find(rule.others.begin(), rule.others.end(), rule.subject) != rule.others.end()) {
        // `{if: A, excludes: [A]}` pruned every variant with A without a word.
        Error(node, fmt::format("a rule names '{}' both in `if` and in `{}`, so it {}; name "
                                "other defines there",
                                rule.subject, has_requires ? "requires" : "excludes",
                                has_requires ? "does nothing"
                                             : "prunes every variant with it, as if it were "
                                               "not a feature"));
    }
    program.rules.push_back(std::move(rule));
}

PassOptions ConfigParser::ParsePasses(const YAML::Node& node) {
    PassOptions passes;
    if (!ExpectMap(node, "passes")) {
        return passes;
    }
    CheckKeys(node, "passes",
              {"reflection_size", "refraction_size", "low_res_water", "clip", "culling",
               "depth_fog"});
    // The reflection and refraction sizes are separate options so that a comparison of one
    // (whitepaper row 11) leaves the other alone.
    for (const char* key : {"reflection_size", "refraction_size"}) {
        if (!node[key]) {
            continue;
        }
        const int size = ReadInt(node[key], key, 256);
        if (size < 1 || size > 4096 || (size & (size - 1)) != 0) {
            Error(node[key], fmt::format("{} must be a power of two from 1 to 4096", key));
        }
        (std::string_view(key) == "reflection_size" ? passes.reflection_size
                                                    : passes.refraction_size) = size;
    }
    if (node["low_res_water"]) {
        passes.low_res_water = ReadBool(node["low_res_water"], "low_res_water", false);
    }
    if (node["culling"]) {
        passes.culling = ReadBool(node["culling"], "culling", true);
    }
    if (node["depth_fog"]) {
        passes.depth_fog = ReadBool(node["depth_fog"], "depth_fog", true);
    }
    if (node["clip"] && ExpectScalar(node["clip"], "clip")) {
        passes.clip = node["clip"].Scalar();
        if (passes.clip != "oblique" && passes.clip != "discard") {
            Error(node["clip"],
                  fmt::format("clip must be 'oblique' or 'discard', not '{}'", passes.clip));
        }
    }
    return passes;
}

Preset ConfigParser::ParsePreset(const std::string& name, const YAML::Node& key,
                                 const YAML::Node& node) {
    Preset preset;
    preset.name = name;
    preset.where = At(key);
    // `--preset NAME` and the configurations' ids name it.
    if (!IsValidDefineName(name)) {
        Error(key,
              fmt::format("preset name '{}' must be an identifier (letters, digits, _)", name));
    }
    const std::string what = fmt::format("preset '{}'", name);
    if (!ExpectMap(node, what)) {
        return preset;
    }
    CheckKeys(node, what, {"program", "defines", "runtime_features", "description", "passes"});
    if (!node["program"]) {
        Error(key, fmt::format("{} has no 'program'", what));
    } else if (ExpectScalar(node["program"], "program")) {
        preset.program = node["program"].Scalar();
        if (preset.program.empty()) {
            Error(node["program"], fmt::format("{} names no program: give the name of one", what));
        }
    }
    preset.defines = NameList(node["defines"], "defines");
    preset.runtime_features = NameList(node["runtime_features"], "runtime_features");
    for (const std::string& feature : preset.runtime_features) {
        if (!IsValidDefineName(feature)) {
            Error(node["runtime_features"],
                  fmt::format("'{}' is not a valid feature name in runtime_features", feature));
        }
    }
    if (node["description"] && ExpectScalar(node["description"], "description")) {
        preset.description = node["description"].Scalar();
    }
    if (node["passes"]) {
        preset.passes = ParsePasses(node["passes"]);
    }
    return preset;
}

void ConfigParser::CheckPreset(const Preset& preset, const VariantConfig& config) {
    // A runtime feature switches on, by a uniform bool, the effect another program compiles in by
    // its define (water_uniform's bools, water's defines); the renderer drops a name it does not
    // know without a word.
    std::set<std::string> declared;
    for (const ProgramConfig& any : config.programs) {
        for (const std::string& define : any.AllDefines()) {
            declared.insert(define);
        }
    }
    for (const std::string& feature : preset.runtime_features) {
        if (IsValidDefineName(feature) && declared.count(feature) == 0) {
            Error(preset.where,
                  fmt::format("preset '{}' switches on '{}' in runtime_features, which no program "
                              "declares; runtime features are the defines of the programs: {}",
                              preset.name, feature, fmt::join(declared, ", ")));
        }
    }
    const ProgramConfig* program = config.FindProgram(preset.program);
    if (program == nullptr) {
        if (!preset.program.empty()) {  // else ParsePreset said what is wrong with it
            std::vector<std::string> names;
            for (const ProgramConfig& any : config.programs) {
                names.push_back(any.name);
            }
            Error(preset.where, fmt::format("preset '{}' names unknown program '{}'; the programs "
                                            "are {}",
                                            preset.name, preset.program, fmt::join(names, ", ")));
        }
        return;
    }
    const std::vector<std::string> known = program->AllDefines();
    bool all_known = true;
    for (const std::string& define : preset.defines) {
        if (std::find(known.begin(), known.end(), define) != known.end()) {
            continue;
        }
        if (const Axis* axis = AxisDefaultingTo(*program, define)) {
            Error(preset.where, DefaultNamedMessage(define, *axis));
        } else {
            Error(preset.where,
                  fmt::format("preset '{}' uses unknown define '{}' of program "
                              "'{}'; known: {}",
                              preset.name, define, program->name, fmt::join(known, ", ")));
        }
        all_known = false;
    }
    if (!all_known) {
        return;
    }
    // A preset must name a variant that exists: every axis set exactly once (an axis with a
    // default at most once, none meaning the default), no rule broken.
    for (const Axis& axis : program->axes) {
        int chosen = 0;
        for (const std::string& value : axis.values) {
            const std::string define = axis.DefineFor(value);
            if (!define.empty()) {
                chosen += static_cast<int>(
                        std::count(preset.defines.begin(), preset.defines.end(), define));
            }
        }
        if (axis.default_value.empty() && chosen != 1) {
            Error(preset.where, fmt::format("preset '{}' must choose exactly one value of axis "
                                            "'{}' (it chose {})",
                                            preset.name, axis.name, chosen));
        } else if (!axis.default_value.empty() && chosen > 1) {
            Error(preset.where, fmt::format("preset '{}' must choose at most one value of axis "
                                            "'{}' (it chose {}); choosing none means its "
                                            "default '{}'",
                                            preset.name, axis.name, chosen, axis.default_value));
        }
    }
    std::vector<std::string> sorted = preset.defines;
    std::sort(sorted.begin(), sorted.end());
    for (const Rule& rule : program->rules) {
        auto has = [&](const std::string& d) {
            return std::binary_search(sorted.begin(), sorted.end(), d);
        };
        bool broken = false;
        switch (rule.kind) {
            case RuleKind::kRequires:
                broken = has(rule.subject) &&
                         !std::all_of(rule.others.begin(), rule.others.end(), has);
                break;
            case RuleKind::kExcludes:
                broken = has(rule.subject) &&
                         std::any_of(rule.others.begin(), rule.others.end(), has);
                break;
            case RuleKind::kExcludeCombination:
                broken = std::all_of(rule.others.begin(), rule.others.end(), has);
                break;
        }
        if (broken) {
            Error(preset.where, fmt::format("preset '{}' breaks rule '{}' (line {}); change its "
                                            "defines",
                                            preset.name, rule.Describe(), rule.where.line));
        }
    }
}

ConfigResult ConfigParser::Parse(std::string_view text) {
    ConfigResult result;
    const std::optional<YAML::Node> loaded = Load(text);
    if (!loaded) {
        result.diagnostics = std::move(diagnostics_);
        return result;
    }
    const YAML::Node& root = *loaded;
    if (!root || root.IsNull()) {
        Error(SourceLocation{FileName(), 1, 1},
              "the file is empty; it needs at least `programs:` "
              "(see the variants.yaml schema in README.md)");
        result.diagnostics = std::move(diagnostics_);
        return result;
    }
    if (!root.IsMap()) {
        Error(root, "the top level must be a mapping with keys such as `programs:`");
        result.diagnostics = std::move(diagnostics_);
        return result;
    }
    // yaml-cpp throws on conversions and odd trees; nothing may escape the library.
    try {
        CheckKeys(root, "the top level",
                  {"version", "targets", "max_variants", "programs", "presets", "description"});
        VariantConfig config;
        config.path = FileName();
        config.base_dir = base_dir_;
        if (root["version"]) {
            config.version = ReadInt(root["version"], "version", 1);
            if (config.version != 1) {
                Error(root["version"], fmt::format("unsupported schema version {}; this "
                                                   "tidepool reads version 1",
                                                   config.version));
            }
        }
        if (const YAML::Node limit_node = root["max_variants"]) {
            // Read wider than int so that 2^31 or 10^23 is named as out of range, not as "not a
            // number". Above the ceiling is legal here: the file may ask, and expansion refuses
            // it unless the command line passes --allow-large-matrix.
            long long limit = 0;
            if (!limit_node.IsScalar() || !YAML::convert<long long>::decode(limit_node, limit) ||
                limit < 1 || static_cast<unsigned long long>(limit) > kLargeVariantCeiling) {
                Error(limit_node,
                      fmt::format("max_variants must be a whole number from 1 to {} (valid "
                                  "variants; above {} only with --allow-large-matrix), not '{}'",
                                  kLargeVariantCeiling, kVariantCeiling,
                                  limit_node.IsScalar() ? limit_node.Scalar() : "a list or map"));
            } else {
                config.max_variants = static_cast<std::uint64_t>(limit);
                config.max_variants_where = At(limit_node);
            }
        }
        if (root["targets"]) {
            ParseTargets(root["targets"], config);
        } else {
            config.targets.push_back(GlslTarget::kEs100);
        }
        const YAML::Node programs = root["programs"];
        if (!programs) {
            Error(SourceLocation{FileName(), 1, 1},
                  "no `programs:` section; declare at least one "
                  "program with its vertex and fragment files");
        } else if (ExpectMap(programs, "programs")) {
            for (auto it = programs.begin(); it != programs.end(); ++it) {
                config.programs.push_back(ParseProgram(it->first.Scalar(), it->first, it->second));
            }
            if (config.programs.empty()) {
                Error(programs, "`programs:` is empty; declare at least one program");
            }
        }
        if (const YAML::Node presets = root["presets"]) {
            if (ExpectMap(presets, "presets")) {
                for (auto it = presets.begin(); it != presets.end(); ++it) {
                    config.presets.push_back(
                            ParsePreset(it->first.Scalar(), it->first, it->second));
                }
            }
        }
        for (const Preset& preset : config.presets) {
            CheckPreset(preset, config);
        }
        if (!HasErrors(diagnostics_)) {
            result.config = std::move(config);
        }
    } catch (const YAML::Exception& e) {
        Error(At(e.mark), fmt::format("unexpected YAML structure: {}", e.msg));
        result.config.reset();
    }
    result.diagnostics = std::move(diagnostics_);
    return result;
}

}  // namespace

ConfigResult ParseVariantConfig(std::string_view text, const std::string& file_name,
                                const std::filesystem::path& base_dir) {
    ConfigParser parser(file_name, base_dir);
    return parser.Parse(text);
}

ConfigResult LoadVariantConfig(const std::filesystem::path& path) {
    const TextFileRead read = ReadTextFile(path);
    if (!read.ok) {
        ConfigResult result;
        result.diagnostics.push_back(MakeError(
                path.string(), 0, 0,
                fmt::format("cannot read the configuration file: {}; check the path or pass "
                            "--config PATH",
                            read.error)));
        return result;
    }
    return ParseVariantConfig(read.text, path.string(), path.parent_path());
}

}  // namespace tidepool
