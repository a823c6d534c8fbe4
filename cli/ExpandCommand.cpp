// `tidepool expand`: flags → pipeline::Expand → the variant list (text or JSON) → exit code.
#include "tidepool/Manifest.h"
#include "tidepool/pipeline/CompilerStages.h"

#include <cstdio>
#include <memory>

#include "CliSupport.h"
#include "Commands.h"
#include <fmt/format.h>

namespace tidepool::cli {
namespace {

struct ExpandCommandOptions {
    pipeline::ExpandOptions expand;
    bool json = false;
    bool pruned = false;                // list pruned combinations
    std::string pruned_limit = "1000";  // at most this many
};

// The listing: every variant, the pruned combinations asked for, the counts per rule.
void PrintExpansion(const ExpandCommandOptions& options, const pipeline::ExpandResult& result) {
    const ExpansionResult& expansion = result.matrix.expansion;
    // Listed combinations go to the printed JSON only: the manifest keeps counts per rule.
    const std::uint64_t unlisted = expansion.pruned_total - expansion.pruned.size();
    if (options.json) {
        nlohmann::json printed = result.manifest;
        if (options.pruned) {
            nlohmann::json list = nlohmann::json::array();
            for (const PrunedCombination& p : expansion.pruned) {
                list.push_back({{"id", p.combination.Id()},
                                {"program", p.combination.program},
                                {"defines", p.combination.defines},
                                {"rule", p.rule},
                                {"file", p.where.file},
                                {"line", p.where.line}});
            }
            printed["pruned"] = list;
            printed["pruned_unlisted"] = unlisted;
        }
        std::printf("%s\n", JsonText(printed, 2).c_str());
        return;
    }
    for (const Variant& variant : expansion.variants) {
        std::printf("%s\n", variant.Id().c_str());
    }
    for (const PrunedCombination& p : expansion.pruned) {
        std::printf("pruned %s  (%s, %s:%d)\n", p.combination.Id().c_str(), p.rule.c_str(),
                    p.where.file.c_str(), p.where.line);
    }
    if (options.pruned && unlisted > 0) {
        std::printf("... %llu more pruned combinations not listed (raise --pruned-limit)\n",
                    static_cast<unsigned long long>(unlisted));
    }
    for (const RulePruneCount& rule : expansion.pruned_by_rule) {
        std::printf("%llu pruned by %s: %s  (%s:%d)\n", static_cast<unsigned long long>(rule.count),
                    rule.program.c_str(), rule.rule.c_str(), rule.where.file.c_str(),
                    rule.where.line);
    }
    std::printf("%zu variants, %llu pruned combinations\n", expansion.variants.size(),
                static_cast<unsigned long long>(expansion.pruned_total));
}

int RunExpand(ExpandCommandOptions options) {
    if (options.pruned &&
        !ParseCountOption("--pruned-limit", options.pruned_limit, 1, kVariantCeiling, "",
                          &options.expand.limits.pruned_limit)) {
        return kExitUsage;
    }
    const pipeline::ExpandResult result = pipeline::Expand(options.expand);
    const int code = PrintOutcome(result.matrix.outcome);
    // A run that stopped (an --out folder it may not replace, a failed write) lists nothing: a
    // listing on stdout above the error would read as done, and a script would take it.
    if (!result.matrix.config || result.matrix.outcome.Stopped()) {
        return code;
    }
    PrintExpansion(options, result);
    if (code == kExitOk && !options.expand.out.empty() && !options.json) {
        std::printf("wrote %s/<target>/<program>/<variant>.vert|.frag and %s/manifest.json\n",
                    options.expand.out.c_str(), options.expand.out.c_str());
    }
    return code;
}

}  // namespace

void RegisterExpandCommand(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<ExpandCommandOptions>();
    CLI::App* expand = app.add_subcommand(
            "expand",
            "List every variant and how many combinations each rule pruned (with "
            "--pruned, the combinations too); with --out, write each variant's "
            "driver-ready sources");
    AddMatrixFlags(expand, &options->expand.config, &options->json, &options->expand.limits);
    CLI::Option* pruned =
            expand->add_flag("--pruned", options->pruned,
                             "also list pruned combinations, each with the first rule it breaks");
    expand->add_option(
                  "--pruned-limit", options->pruned_limit,
                  fmt::format("list at most this many pruned combinations, 1..{}", kVariantCeiling))
            ->capture_default_str()
            ->needs(pruned);
    CLI::Option* out = expand->add_option("--out", options->expand.out,
                                          "folder for <target>/<program>/<variant>.vert|.frag and "
                                          "manifest.json")
                               ->transform(NormaliseOutPath);
    expand->add_option("--program", options->expand.program,
                       "expand only this program of the configuration");
    expand->add_option("--depfile", options->expand.depfile,
                       "with --out, write a Make/Ninja depfile naming the configuration and "
                       "every shader read")
            ->needs(out);
    expand->callback([options, &exit_code] { exit_code = RunExpand(*options); });
}

}  // namespace tidepool::cli
