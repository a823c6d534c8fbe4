// A hand-made run for the report's tests: manifest.json, results.json and flat images written
// into a TempDir, with the configurations each test chooses, and the report model built from it.
#pragma once

#include "tidepool/base/RgbaImage.h"
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/ReportModel.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "TempDir.h"
#include <nlohmann/json.hpp>

namespace tidepool::testing {

// A flat image of one colour, with a bright square when `mark` > 0 (a visible difference).
inline tidepool::base::RgbaImage Flat(std::uint8_t grey, int mark = 0) {
    tidepool::base::RgbaImage image;
    image.width = 32;
    image.height = 24;
    image.pixels.assign(static_cast<std::size_t>(image.width * image.height * 4), grey);
    for (int y = 0; y < mark; ++y) {
        for (int x = 0; x < mark; ++x) {
            const auto i = static_cast<std::size_t>((y * image.width + x) * 4);
            image.pixels[i] = image.pixels[i + 1] = image.pixels[i + 2] = 255;
        }
    }
    for (std::size_t i = 3; i < image.pixels.size(); i += 4) {
        image.pixels[i] = 255;
    }
    return image;
}

// One configuration of the hand-made results: id, presets, time per frame, image mark size.
struct FakeConfiguration {
    std::string id;
    std::vector<std::string> presets;
    double ms = 10;
    int mark = 0;  // 0: identical to the reference
    bool ok = true;
    std::string program = "water";
    int total_ops = 100;
    std::map<std::string, nlohmann::json> passes = {};
    double cpu_ms = 0;  // > 0: cpu_samples_ms and cpu_statistics are written at this time
    std::vector<std::string> pass_names = {};  // written per view when not empty
    int draw_calls = -1;                       // written per view when >= 0
    int grazing_mark = -1;                     // >= 0: a second view, "grazing", this mark
};

// Writes manifest.json, results.json and images for `configurations` into `dir`.
struct FakeRun {
    std::filesystem::path manifest;
    std::filesystem::path results;
};

inline FakeRun WriteFakeRun(const TempDir& dir,
                            const std::vector<FakeConfiguration>& configurations, int rounds = 24) {
    nlohmann::json variants = nlohmann::json::array();
    nlohmann::json entries = nlohmann::json::array();
    for (const FakeConfiguration& c : configurations) {
        const std::string variant = c.id.substr(0, c.id.find('@'));
        variants.push_back({{"id", variant},
                            {"program", c.program},
                            {"valid", true},
                            {"stages",
                             {{"vertex", {{"cost", {{"total_ops", 10}}}}},
                              {"fragment", {{"cost", {{"total_ops", c.total_ops - 10}}}}}}}});
        nlohmann::json samples = nlohmann::json::array();
        for (int r = 0; r < rounds; ++r) {
            // A little deterministic jitter so intervals have width.
            const double jitter = 1.0 + 0.002 * ((r % 3) - 1);
            samples.push_back({c.ms * jitter, c.ms * jitter * 1.001});
        }
        nlohmann::json cpu_samples = nlohmann::json::array();
        for (int r = 0; r < rounds; ++r) {
            // Jitter of another phase than the wall samples', as two clocks would give.
            const double jitter = 1.0 + 0.002 * (((r + 1) % 3) - 1);
            cpu_samples.push_back({c.cpu_ms * jitter, c.cpu_ms * jitter * 1.001});
        }
        nlohmann::json views = nlohmann::json::array();
        if (c.ok) {
            std::vector<std::pair<std::string, int>> marks = {{"three_quarter", c.mark}};
            if (c.grazing_mark >= 0) {
                marks.emplace_back("grazing", c.grazing_mark);
            }
            for (const auto& [view, mark] : marks) {
                const std::string image = "images/" + std::to_string(entries.size()) +
                                          (view == "three_quarter" ? "" : "-" + view) + ".png";
                EXPECT_EQ(tidepool::base::WritePngAtomically(dir.Path() / "render" / image,
                                                             Flat(100, mark)),
                          "");
                views.push_back({{"view", view}, {"image", image}});
                if (!c.pass_names.empty()) {
                    views.back()["pass_names"] = c.pass_names;
                    views.back()["passes"] = c.pass_names.size();
                }
                if (c.draw_calls >= 0) {
                    views.back()["draw_calls"] = c.draw_calls;
                }
            }
        }
        nlohmann::json passes = {{"reflection_size", 256},
                                 {"low_res_water", false},
                                 {"clip", "oblique"},
                                 {"culling", true}};
        for (const auto& [k, v] : c.passes) {
            passes[k] = v;
        }
        entries.push_back({{"id", c.id},
                           {"variant", variant},
                           {"program", c.program},
                           {"presets", c.presets},
                           {"passes", passes},
                           {"driver", {{"valid", c.ok}, {"diagnostics", nlohmann::json::array()}}},
                           {"views", views},
                           {"samples_ms", c.ok ? samples : nlohmann::json::array()},
                           {"statistics",
                            {{"count", c.ok ? rounds * 2 : 0},
                             {"median_ms", c.ms},
                             {"ci_low_ms", c.ms * 0.99},
                             {"ci_high_ms", c.ms * 1.01}}},
                           {"gl_error", ""},
                           {"ok", c.ok}});
        if (c.cpu_ms > 0) {
            entries.back()["cpu_samples_ms"] = c.ok ? cpu_samples : nlohmann::json::array();
            entries.back()["cpu_statistics"] = {{"count", c.ok ? rounds * 2 : 0},
                                                {"median_ms", c.cpu_ms},
                                                {"ci_low_ms", c.cpu_ms * 0.99},
                                                {"ci_high_ms", c.cpu_ms * 1.01}};
        }
    }
    const nlohmann::json manifest = {{"schema", "tidepool.manifest"},
                                     {"version", 1},
                                     {"variants", variants},
                                     {"pruned_by_rule", nlohmann::json::array()},
                                     {"counts", {{"variants", variants.size()}, {"pruned", 0}}}};
    const nlohmann::json results = {
            {"schema", "tidepool.render-results"},
            {"version", 1},
            {"environment", {{"gl_renderer", "llvmpipe (test)"}, {"lp_num_threads", "2"}}},
            {"settings",
             {{"timing_view", "three_quarter"},
              {"rounds", rounds},
              {"views", {{{"name", "three_quarter"}}}}}},
            {"configurations", entries},
            {"disagreements", nlohmann::json::array()},
            {"diagnostics", nlohmann::json::array()},
            {"ok", true}};
    FakeRun run;
    run.manifest = dir.Write("manifest/manifest.json", manifest.dump(2));
    run.results = dir.Write("render/results.json", results.dump(2));
    return run;
}

// Every preset of the whitepaper table plus the reference, with times chosen per row.
inline std::vector<FakeConfiguration> WhitepaperConfigurations() {
    return {
            {"water:", {"reflection_only"}, 10.0, 6, true, "water", 50},
            {"water:ENABLE_REFRACTION", {"reflection_refraction"}, 24.0, 4, true, "water", 80},
            {"water:ENABLE_WATER_COLOUR", {"reflection_water_colour"}, 10.9, 5, true, "water", 60},
            {"water:ENABLE_ALPHA_BLEND", {"reflection_alpha_blend"}, 11.0, 5, true, "water", 55},
            {"water:FULL", {"full"}, 30.0, 2, true, "water", 200},
            {"water:FULL_NO_FOG", {"full_no_fog"}, 29.0, 3, true, "water", 190},
            {"water:CONST", {"full_constant_mix"}, 25.0, 3, true, "water", 150},
            {"water:UNSCALED", {"full_unscaled_distortion"}, 29.9, 3, true, "water", 195},
            {"water:FULL@lowres",
             {"full_low_res_water"},
             26.0,
             3,
             true,
             "water",
             200,
             {{"low_res_water", true}}},
            {"water:CUBE", {"full_cubemap_normalise"}, 36.0, 2, true, "water", 190},
            {"water_uniform:FULL", {"full_uniform_bools"}, 30.3, 2, true, "water_uniform", 400},
            {"water:FULL@discard",
             {"full_clip_discard"},
             40.0,
             2,
             true,
             "water",
             200,
             {{"clip", "discard"}}},
            {"water:FULL@refl128",
             {"full_reflection_128"},
             27.0,
             3,
             true,
             "water",
             200,
             {{"reflection_size", 128}}},
            {"water:EXACT@refl512",
             {"reference"},
             45.0,
             0,
             true,
             "water",
             220,
             {{"reflection_size", 512}}},
    };
}

// The whitepaper configurations plus the reflection techniques and the depth optics, with the
// passes each runs: cube map and Fourier have no reflection pass. Images: reflection_only has
// mark 6 at both views; cubemap_reflection draws the same image (identical), fourier_reflection
// a different one (mark 0 at both); full has mark 2 at both views; full_cubemap_reflection
// matches it at three_quarter but not at grazing (the view where it breaks);
// full_fourier_reflection differs at both; full_depth_optics changes three_quarter only.
inline std::vector<FakeConfiguration> ReflectionConfigurations() {
    std::vector<FakeConfiguration> configurations = WhitepaperConfigurations();
    for (FakeConfiguration& c : configurations) {
        c.pass_names = {"reflection", "main"};
        c.draw_calls = 20;
        if (c.presets.front() == "reflection_only") {
            c.grazing_mark = 6;
        }
        if (c.presets.front() == "full") {
            c.pass_names = {"reflection", "refraction", "main"};
            c.draw_calls = 30;
            c.grazing_mark = 2;
        }
    }
    const std::vector<std::string> main_only = {"main"};
    const std::vector<std::string> refraction_main = {"refraction", "main"};
    configurations.push_back({"water:REFLECTION_CUBEMAP",
                              {"cubemap_reflection"},
                              8.0,
                              6,
                              true,
                              "water",
                              45,
                              {},
                              0,
                              main_only,
                              12,
                              6});
    configurations.push_back({"water:REFLECTION_FOURIER",
                              {"fourier_reflection"},
                              12.5,
                              0,
                              true,
                              "water",
                              70,
                              {},
                              0,
                              main_only,
                              12,
                              0});
    configurations.push_back({"water:CUBE_FULL",
                              {"full_cubemap_reflection"},
                              24.0,
                              2,
                              true,
                              "water",
                              190,
                              {},
                              0,
                              refraction_main,
                              22,
                              9});
    configurations.push_back({"water:FOURIER_FULL",
                              {"full_fourier_reflection"},
                              26.0,
                              5,
                              true,
                              "water",
                              230,
                              {},
                              0,
                              refraction_main,
                              22,
                              7});
    configurations.push_back({"water:OPTICS",
                              {"full_depth_optics"},
                              33.0,
                              4,
                              true,
                              "water",
                              260,
                              {},
                              0,
                              {"reflection", "refraction", "main"},
                              30,
                              2});
    return configurations;
}

inline report::ReportModel BuildOrFail(const report::ReportInputs& inputs) {
    report::ReportModelResult built = report::BuildReportModel(inputs, report::ReportOptions{});
    EXPECT_TRUE(built.model) << built.error;
    return built.model ? std::move(*built.model) : report::ReportModel{};
}

inline report::ReportModel BuildFrom(const FakeRun& run,
                                     std::optional<report::ReportInputs>* keep) {
    report::ReportInputsResult loaded = report::LoadReportInputs(run.manifest, run.results);
    EXPECT_TRUE(loaded.inputs) << loaded.error;
    if (!loaded.inputs) {
        return {};
    }
    *keep = std::move(loaded.inputs);
    return BuildOrFail(**keep);
}

}  // namespace tidepool::testing
