#include "tidepool/SarifLog.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <tuple>
#include <vector>

#include <fmt/format.h>

namespace tidepool {

std::string ArtifactUri(const std::filesystem::path& path) {
    const std::string text = path.lexically_normal().generic_string();
    std::string uri = path.is_absolute() ? "file://" : "";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isalnum(byte) != 0 || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            uri += c;
        } else {
            uri += fmt::format("%{:02X}", byte);
        }
    }
    return uri;
}

namespace {

struct RuleText {
    const char* id;
    const char* description;
};

// One rule per step, in the order results cite them.
constexpr RuleText kRules[] = {
        {"vertex", "The vertex shader of a variant does not compile as GLSL ES."},
        {"fragment", "The fragment shader of a variant does not compile as GLSL ES."},
        {"link", "The vertex and fragment shaders of a variant do not link into a program."},
        {"input", "A shader file cannot be used at all (unreadable, or refused before parsing)."},
};

// A distinct message: the same text at the same place from the same step is one result.
using ResultKey = std::tuple<std::string, std::string, int, int, int, std::string>;

struct Finding {
    const Diagnostic* diagnostic = nullptr;
    std::vector<std::string> variants;
};

std::string VariantsSuffix(const std::vector<std::string>& variants) {
    if (variants.empty()) {
        return {};
    }
    if (variants.size() == 1) {
        return fmt::format(" [variant {}]", variants.front());
    }
    return fmt::format(" [{} variants, e.g. {}]", variants.size(), variants.front());
}

}  // namespace

nlohmann::json BuildSarifLog(const ValidationReport& report, const std::filesystem::path& base_dir,
                             const std::string& tool_version) {
    std::map<ResultKey, Finding> findings;
    std::vector<ResultKey> order;  // first seen first, so the log follows the report
    auto add = [&](const char* rule, const Diagnostic& d) {
        ResultKey key{rule, d.file, d.line, d.column, static_cast<int>(d.severity), d.message};
        auto [it, inserted] = findings.try_emplace(key, Finding{&d, {}});
        if (inserted) {
            order.push_back(key);
        }
        // A variant validated for two targets reports the same message twice: named once.
        std::vector<std::string>& variants = it->second.variants;
        if (!d.variant.empty() &&
            std::find(variants.begin(), variants.end(), d.variant) == variants.end()) {
            variants.push_back(d.variant);
        }
    };
    for (const Diagnostic& d : report.diagnostics) {
        add("input", d);
    }
    for (const VariantVerdict& verdict : report.verdicts) {
        for (const auto& [rule, step] : verdict.NamedSteps()) {
            for (const Diagnostic& d : step->diagnostics) {
                add(rule, d);
            }
        }
    }

    nlohmann::json rules = nlohmann::json::array();
    std::map<std::string, int> rule_index;
    for (const RuleText& rule : kRules) {
        rule_index[rule.id] = static_cast<int>(rules.size());
        rules.push_back({{"id", rule.id}, {"shortDescription", {{"text", rule.description}}}});
    }
    nlohmann::json results = nlohmann::json::array();
    for (const ResultKey& key : order) {
        const Finding& finding = findings.at(key);
        const Diagnostic& d = *finding.diagnostic;
        const std::string& rule = std::get<0>(key);
        nlohmann::json physical = {{"artifactLocation",
                                    {{"uri", ArtifactUri(std::filesystem::path(d.file).is_absolute()
                                                                 ? std::filesystem::path(d.file)
                                                                 : base_dir / d.file)}}}};
        // SARIF lines and columns start at 1; an unknown one is left out, not written as 0.
        if (d.line > 0) {
            physical["region"] = {{"startLine", d.line}};
            if (d.column > 0) {
                physical["region"]["startColumn"] = d.column;
            }
        }
        nlohmann::json result = {
                {"ruleId", rule},
                {"ruleIndex", rule_index.at(rule)},
                {"level", SeverityName(d.severity)},  // SARIF names its levels as GCC does
                {"message", {{"text", d.message + VariantsSuffix(finding.variants)}}},
                {"locations", nlohmann::json::array({{{"physicalLocation", physical}}})}};
        if (!finding.variants.empty()) {
            result["properties"] = {{"variants", finding.variants}};
        }
        results.push_back(std::move(result));
    }
    return {{"version", kSarifVersion},
            {"$schema", kSarifSchema},
            {"runs",
             nlohmann::json::array(
                     {{{"tool",
                        {{"driver",
                          {{"name", "tidepool"}, {"version", tool_version}, {"rules", rules}}}}},
                       {"results", results}}})}};
}

}  // namespace tidepool
