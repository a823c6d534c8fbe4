// Loads one shader variant by its feature set, as an engine would at run time: find the
// program's manifest, pick the valid variant whose defines are exactly the features asked for
// (in any order), and read its driver-ready sources.
//
//   variant_loader PROGRAM [FEATURE...]      e.g.  variant_loader tint FOG TINT
//
// Prints the variant id and the two sources' paths and sizes; exit code 1 when the program or the
// feature set has no valid variant (the message lists the feature sets there are).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace {

std::string ReadFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s PROGRAM [FEATURE...]\n", argv[0]);
        return 2;
    }
    const std::string program = argv[1];
    std::vector<std::string> features(argv + 2, argv + argc);
    std::sort(features.begin(), features.end());

    const std::filesystem::path folder = std::filesystem::path(EXAMPLE_SHADER_DIR) / program;
    const nlohmann::json manifest =
            nlohmann::json::parse(ReadFile(folder / "manifest.json"), nullptr, false);
    if (!manifest.is_object() || !manifest.contains("variants")) {
        std::fprintf(stderr, "error: %s: no manifest; is '%s' a program of variants.yaml?\n",
                     (folder / "manifest.json").c_str(), program.c_str());
        return 1;
    }
    for (const nlohmann::json& variant : manifest["variants"]) {
        // Defines are stored sorted, so equal sets compare equal as lists.
        if (variant["defines"].get<std::vector<std::string>>() != features ||
            !variant["valid"].get<bool>()) {
            continue;
        }
        const std::string vertex =
                ReadFile(folder / variant["sources"]["vertex"].get<std::string>());
        const std::string fragment =
                ReadFile(folder / variant["sources"]["fragment"].get<std::string>());
        std::printf("%s\n  vertex   %s (%zu bytes)\n  fragment %s (%zu bytes)\n",
                    variant["id"].get<std::string>().c_str(),
                    variant["sources"]["vertex"].get<std::string>().c_str(), vertex.size(),
                    variant["sources"]["fragment"].get<std::string>().c_str(), fragment.size());
        return vertex.empty() || fragment.empty() ? 1 : 0;
    }
    std::fprintf(stderr, "error: %s has no valid variant with exactly those features; it has:\n",
                 program.c_str());
    for (const nlohmann::json& variant : manifest["variants"]) {
        std::fprintf(stderr, "  %s\n", variant["id"].get<std::string>().c_str());
    }
    return 1;
}
