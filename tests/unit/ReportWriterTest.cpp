// The report's writer on small hand-made runs: HTML, Markdown and data.json from one model, the
// folder replaced atomically, the stability tables, the Scenes section from plans.json and the
// reflection techniques section (reports/include/tidepool/report/ReportWriter.h).
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/report/ReportWriter.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "FakeReportRun.h"
#include "FileContents.h"
#include "TempDir.h"
#include <nlohmann/json.hpp>

namespace {

using namespace tidepool::report;
using namespace tidepool::testing;

// The HTML tags of a heading removed and its entities decoded: the text a reader sees.
std::string HeadingText(std::string html) {
    std::string text;
    bool in_tag = false;
    for (char c : html) {
        if (c == '<' || c == '>') {
            in_tag = c == '<';
        } else if (!in_tag) {
            text += c;
        }
    }
    for (const auto& [entity, plain] : {std::pair<std::string, std::string>{"&lt;", "<"},
                                        {"&gt;", ">"},
                                        {"&quot;", "\""},
                                        {"&amp;", "&"}}) {
        for (std::size_t at = text.find(entity); at != std::string::npos;
             at = text.find(entity, at + plain.size())) {
            text.replace(at, entity.size(), plain);
        }
    }
    return text;
}

// Both pages are rendered from one document, so every heading of index.html (section, sub-
// heading, image panel, folded table) is a heading of report.md too. Before the document model
// the Markdown lacked the failed-configuration and pruned-rule headings.
TEST(ReportWriterTest, MarkdownHasEveryHeadingTheHtmlHas) {
    TempDir dir;
    std::vector<FakeConfiguration> configurations = WhitepaperConfigurations();
    configurations[2].ok = false;  // a failed configuration adds its table and heading
    const FakeRun run = WriteFakeRun(dir, configurations);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string html = ReadText(written.folder / "index.html");
    const std::string md = ReadText(written.folder / "report.md");
    int headings = 0;
    for (const auto& [open, close, prefix] :
         {std::tuple<std::string, std::string, std::string>{"<h2", "</h2>", "## "},
          {"<h3", "</h3>", "### "},
          {"<summary>", "</summary>", "### "}}) {
        for (std::size_t at = html.find(open); at != std::string::npos;
             at = html.find(open, at + 1)) {
            const std::size_t start = html.find('>', at) + 1;
            const std::size_t end = html.find(close, start);
            ASSERT_NE(end, std::string::npos);
            const std::string text = HeadingText(html.substr(start, end - start));
            EXPECT_NE(md.find("\n" + prefix + text + "\n\n"), std::string::npos) << text;
            ++headings;
        }
    }
    EXPECT_GT(headings, 20);
    EXPECT_NE(md.find("### Failed configurations\n\n| configuration | status | why |"),
              std::string::npos)
            << md;
}

TEST(ReportWriterTest, WritesAllFormatsAndReplacesOnlyItsOwnFolder) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    ReportOptions options;
    options.name = "t";
    const ReportModelResult built = BuildReportModel(*loaded.inputs, options);
    ASSERT_TRUE(built.model) << built.error;
    WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    for (const char* file :
         {"index.html", "report.md", "data.json", "charts/accuracy.svg", "charts/whitepaper.svg",
          "charts/static_cost.svg", "images/reference-three_quarter.png"}) {
        EXPECT_TRUE(std::filesystem::is_regular_file(written.folder / file)) << file;
    }
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["schema"], "tidepool.report");
    EXPECT_EQ(data["version"], 2);
    EXPECT_EQ(data["whitepaper_rows"].size(), 11u);
    EXPECT_EQ(data["stability"]["present"], false);
    const std::string html = ReadText(written.folder / "index.html");
    EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
    EXPECT_NE(html.find("tidepool stability"), std::string::npos);
    // Rewriting replaces the earlier report; no staging folder is left behind.
    written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    for (const auto& entry : std::filesystem::directory_iterator(dir.Path() / "out")) {
        EXPECT_EQ(entry.path().filename(), "t");
    }
    // A folder the writer did not make is never replaced.
    dir.Write("out2/t/precious.txt", "keep me");
    written = WriteReport(*built.model, dir.Path() / "out2");
    EXPECT_NE(written.error.find("not written by tidepool"), std::string::npos) << written.error;
    EXPECT_TRUE(written.refused);
    EXPECT_TRUE(std::filesystem::exists(dir.Path() / "out2/t/precious.txt"));
    // Nor is one that merely holds a data.json: only the marker file says a report is ours.
    dir.Write("out3/t/data.json", "{}");
    written = WriteReport(*built.model, dir.Path() / "out3");
    EXPECT_TRUE(written.refused) << written.error;
    EXPECT_EQ(ReadText(dir.Path() / "out3/t/data.json"), "{}");
}

TEST(ReportWriterTest, StabilityTablesAreRenderedGenerically) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("render/stability.json", R"js({"schema": "tidepool.stability", "version": 1,
        "cases": [{"name": "grazing_fresnel", "description": "cos near 0", "kind": "fresnel",
                   "variants_checked": 4, "nan_count": 0, "inf_count": 0, "max_error": 0.001,
                   "bound": 0.01, "passed": true, "fix": "clamp"}],
        "precision": [{"expression": "pow(1-c,5)", "max_abs_error_float": 1e-7,
                       "max_abs_error_fp16": 0.002, "max_rel_error_fp16": 0.01,
                       "loses_precision": false, "note": "ok"}],
        "guards": [{"guard": "max(dot,0)", "max_channel_diff_normal_views": 0,
                    "tolerance": 1}]})js");
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    ASSERT_TRUE(loaded.inputs->stability);
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("| grazing_fresnel | cos near 0 | fresnel | 4 | 0 | 0 | 0.001 | 0.01 | true "
                      "| clamp |"),
              std::string::npos)
            << md;
    EXPECT_NE(md.find("pow(1-c,5)"), std::string::npos);
    EXPECT_NE(md.find("max(dot,0)"), std::string::npos);
}

// A plans.json of two scenes as `tidepool plan --all` writes it (docs/SCENES.md).
constexpr const char* kPlansJson = R"js({"schema": "tidepool.plans", "version": 1,
    "size": [160, 120], "timing": {"resolution_points": 3.0, "min_pairs": 20, "max_pairs": 400,
               "missed_target_pairs": 20, "contended_share": 0.5},
    "plans": [
    {"scene": "murky_pond", "description": "murky", "target": {"min_psnr_db": 30},
     "chosen": {"id": "water:ENABLE_FOG,ENABLE_WATER_COLOUR@refl128", "variant": "water:x",
                "passes": ["reflection", "main"]},
     "full": {"id": "water:FULL", "variant": "water:FULL",
              "passes": ["reflection", "refraction", "main"]},
     "time_ms_chosen": 8.06, "time_ms_full": 15.0, "time_change_percent": -46.3,
     "error": {"psnr_db": 41.1, "ssim": 0.998, "share_visible": 0.018}, "met": true,
     "dropped": [{"effect": "refraction", "reason": "fog hides the floor at 0.8",
                  "psnr_change_db": 41.1, "time_change_percent": -37}],
     "kept": [{"effect": "fog", "reason": "fog breaks the target without it",
               "psnr_change_db": 12.5, "time_change_percent": -2}],
     "passes_saved": 1, "draws_saved": 5, "pixels_saved": 19200},
    {"scene": "open_sea", "target": {"min_psnr_db": 30}, "chosen": {"id": "water:FULL"},
     "full": {"id": "water:FULL"}, "time_ms_chosen": 7.4, "time_ms_full": 7.4,
     "time_change_percent": 0, "error": {"psnr_db": 99, "ssim": 1, "share_visible": 0},
     "met": false, "dropped": [], "kept": [], "passes_saved": 0, "draws_saved": 0,
     "pixels_saved": 0}]})js";

TEST(ReportWriterTest, PlansBesideTheResultsAreShownPerSceneWithEveryDecisionAndReason) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("render/plans.json", kPlansJson);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    ASSERT_TRUE(loaded.inputs->plans) << loaded.inputs->plans_error;
    const ReportModel model = BuildOrFail(*loaded.inputs);
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("## 8. Scenes"), std::string::npos);
    // The method as plans.json records it, not placeholders.
    EXPECT_NE(md.find("at 160x120, each candidate timed against the full effect pair by pair "
                      "until its 95% interval is within +/-3.0 points (20 to 400 pairs), as the "
                      "machine runs and, 0.5 pairs per as-run pair or more, with a thread of "
                      "tidepool's own on the rendering thread's core, the interval spanning both "
                      "states; in a scene with no frame budget, a candidate whose image misses "
                      "the target, which is then never chosen, only for 20 pairs as the machine "
                      "runs"),
              std::string::npos)
            << md;
    EXPECT_EQ(md.find("paired rounds of"), std::string::npos);
    EXPECT_NE(md.find("| murky_pond | water:ENABLE_FOG,ENABLE_WATER_COLOUR@refl128 | water:FULL | "
                      "8.06 / 15.00 | -46% | 41.1 dB, SSIM 0.998, 1.8% | min_psnr_db 30 | met | "
                      "1 / 5 / 19200 |"),
              std::string::npos)
            << md;
    EXPECT_NE(md.find("| refraction | dropped | 41.1 dB | -37% | fog hides the floor at 0.8 |"),
              std::string::npos);
    EXPECT_NE(md.find("| fog | kept | 12.5 dB | -2% | fog breaks the target without it |"),
              std::string::npos);
    EXPECT_NE(md.find("identical, SSIM 1.000"), std::string::npos);  // 99 dB = identical
    EXPECT_NE(md.find("1 scene(s) NOT met"), std::string::npos);
    const std::string html = ReadText(written.folder / "index.html");
    EXPECT_NE(html.find("<h2 id=\"scenes\">8. Scenes</h2>"), std::string::npos);
    EXPECT_NE(html.find("fog hides the floor at 0.8"), std::string::npos);
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["scenes"]["present"], true);
    EXPECT_EQ(data["scenes"]["plans"].size(), 2u);
    EXPECT_EQ(data["scenes"]["plans"][0]["dropped"][0]["effect"], "refraction");
    EXPECT_EQ(data["inputs"]["plans"], loaded.inputs->plans_path.string());
}

TEST(ReportWriterTest, MissingPlansSayHowToProduceThem) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    EXPECT_FALSE(loaded.inputs->plans);
    EXPECT_EQ(loaded.inputs->plans_error, "");
    const ReportModel model = BuildOrFail(*loaded.inputs);
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("## 8. Scenes\n\nNo scene plans were found"), std::string::npos) << md;
    EXPECT_NE(md.find("tidepool plan --all --out DIR"), std::string::npos);
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["scenes"]["present"], false);
    EXPECT_EQ(data["inputs"]["plans"], nullptr);
}

TEST(ReportWriterTest, CorruptOrForeignPlansAreAnErrorNamingTheFileInTheReport) {
    for (const std::string& content :
         {std::string("{\"schema\": \"tidepool.pla"), std::string(R"({"schema": "other"})"),
          std::string(R"({"schema": "tidepool.plans", "version": 1, "plans": [{"x": 1}]})")}) {
        TempDir dir;
        const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
        const std::filesystem::path plans = dir.Write("render/plans.json", content);
        const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
        ASSERT_TRUE(loaded.inputs) << loaded.error;  // the rest of the report is still built
        EXPECT_FALSE(loaded.inputs->plans);
        EXPECT_EQ(loaded.inputs->plans_error.rfind(plans.string() + ":", 0), 0u)
                << loaded.inputs->plans_error;
        const ReportModel model = BuildOrFail(*loaded.inputs);
        const WrittenReport written = WriteReport(model, dir.Path() / "out");
        ASSERT_EQ(written.error, "");
        const std::string md = ReadText(written.folder / "report.md");
        EXPECT_NE(md.find(loaded.inputs->plans_error), std::string::npos) << md;
        const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
        EXPECT_EQ(data["scenes"]["error"], loaded.inputs->plans_error);
    }
}

TEST(ReportWriterTest, SectionAppearsInHtmlMarkdownAndDataJson) {
    TempDir dir;
    std::optional<ReportInputs> inputs;
    const ReportModel model = BuildFrom(WriteFakeRun(dir, ReflectionConfigurations()), &inputs);
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");

    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("## 9. Reflection techniques"), std::string::npos);
    EXPECT_NE(md.find("| cube-map reflection (reflection only) | reflection_only [water:] → "
                      "cubemap_reflection [water:REFLECTION_CUBEMAP] | measured | reflection, "
                      "main → main (no reflection pass) | 20 → 12 | 10.00 / 8.00 | +25.0%, "
                      "faster |"),
              std::string::npos)
            << md;
    EXPECT_NE(md.find("| identical | 1.0000 | 0.00% | three_quarter: identical; grazing: "
                      "identical |"),
              std::string::npos);
    EXPECT_NE(md.find("grazing: "), std::string::npos);
    EXPECT_NE(md.find("(worst)"), std::string::npos);
    EXPECT_NE(md.find("### Depth optics"), std::string::npos);
    EXPECT_NE(md.find("| depth optics (full effect) | full [water:FULL] → full_depth_optics "
                      "[water:OPTICS] | measured |"),
              std::string::npos);
    EXPECT_NE(md.find("| this configuration | planar reflection (full) | difference |"),
              std::string::npos);
    EXPECT_NE(md.find("images/reflection-full_fourier_reflection-three_quarter.png"),
              std::string::npos);
    EXPECT_TRUE(std::filesystem::is_regular_file(written.folder /
                                                 "images/planar-full-three_quarter.png"));
    EXPECT_TRUE(std::filesystem::is_regular_file(
            written.folder / "images/reflection-full_cubemap_reflection-three_quarter-diff.png"));

    const std::string html = ReadText(written.folder / "index.html");
    EXPECT_NE(html.find("<h2 id=\"reflections\">9. Reflection techniques</h2>"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"#reflections\">Reflection techniques</a>"), std::string::npos);
    EXPECT_NE(html.find("<h3 id=\"depth-optics\">Depth optics</h3>"), std::string::npos);
    EXPECT_NE(html.find("<tr class=\"technique-cubemap-full\">"), std::string::npos);
    EXPECT_NE(html.find("<figcaption>planar reflection (full)</figcaption>"), std::string::npos);
    // Every tag the section opens is closed (the page stays valid), and its panels' images
    // are embedded like the others.
    const std::string section = html.substr(html.find("<h2 id=\"reflections\">"));
    for (const auto& [open, close] :
         std::vector<std::pair<std::string, std::string>>{{"<table", "</table>"},
                                                          {"<tr", "</tr>"},
                                                          {"<div", "</div>"},
                                                          {"<figure>", "</figure>"},
                                                          {"<p", "</p>"},
                                                          {"<h3", "</h3>"}}) {
        std::size_t opened = 0;
        std::size_t closed = 0;
        for (std::size_t at = section.find(open); at != std::string::npos;
             at = section.find(open, at + 1)) {
            // "<p" also starts "<path"; the section has no SVG, but count only <p> and <p ...>.
            const char next = section[at + open.size()];
            if (open != "<p" || next == '>' || next == ' ') {
                ++opened;
            }
        }
        for (std::size_t at = section.find(close); at != std::string::npos;
             at = section.find(close, at + 1)) {
            ++closed;
        }
        EXPECT_EQ(opened, closed) << open;
    }
    std::size_t embedded = 0;
    for (std::size_t at = section.find("src=\"data:image/png;base64,"); at != std::string::npos;
         at = section.find("src=\"data:image/png;base64,", at + 1)) {
        ++embedded;
    }
    EXPECT_EQ(embedded, 6u);  // two panels of three images

    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    const nlohmann::json& section_json = data["reflection_techniques"];
    ASSERT_EQ(section_json["comparisons"].size(), 4u);
    const nlohmann::json& cubemap = section_json["comparisons"][0];
    EXPECT_EQ(cubemap["kind"], "cubemap");
    EXPECT_EQ(cubemap["baseline"]["pass_names"], nlohmann::json({"reflection", "main"}));
    EXPECT_EQ(cubemap["candidate"]["pass_names"], nlohmann::json({"main"}));
    EXPECT_EQ(cubemap["candidate"]["draw_calls"], 12);
    EXPECT_EQ(cubemap["passes_dropped"], nlohmann::json({"reflection"}));
    EXPECT_NEAR(cubemap["measured_percent"].get<double>(), 25.0, 0.05);
    EXPECT_EQ(cubemap["direction"], "faster");
    EXPECT_EQ(cubemap["error"]["identical"], true);
    EXPECT_EQ(cubemap["error"]["psnr_db"], nullptr);
    const nlohmann::json& fourier = section_json["comparisons"][1];
    EXPECT_EQ(fourier["error"]["identical"], false);
    EXPECT_TRUE(fourier["error"]["psnr_db"].is_number());
    EXPECT_EQ(section_json["comparisons"][2]["error"]["worst_view"], "grazing");
    EXPECT_EQ(section_json["comparisons"][2]["error"]["per_view"].size(), 2u);
    EXPECT_EQ(section_json["images"].size(), 2u);
    EXPECT_EQ(section_json["images"][0]["compared_with"], "full");
    ASSERT_EQ(data["depth_optics"]["comparisons"].size(), 1u);
    EXPECT_EQ(data["depth_optics"]["comparisons"][0]["candidate"]["configuration"], "water:OPTICS");
}

}  // namespace
