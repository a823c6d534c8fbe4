// `tidepool run` and `tidepool report` as a user runs them: a small run end to end, the page
// opened in headless Chromium (renders, every image loads, every whitepaper row present), the
// report rebuilt from saved files, and bad inputs rejected with exit 2 and the file named.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "FileContents.h"
#include "TempDir.h"
#include "TidepoolProcess.h"
#include <nlohmann/json.hpp>
#include <sys/wait.h>

namespace {

using tidepool::testing::TempDir;

using tidepool::testing::CommandResult;
using tidepool::testing::ReadText;
using tidepool::testing::RunShell;

// Runs the tidepool binary with `args` (a shell fragment) in the source root, on the two threads
// Mesa's llvmpipe may use here.
CommandResult RunTidepoolInSourceRoot(const std::string& args) {
    return tidepool::testing::RunTidepool(args, TIDEPOOL_SOURCE_ROOT, "LP_NUM_THREADS=2");
}

// One small `tidepool run` shared by every test of the suite (it is the slow part): 160x120,
// 2 rounds of 1 frame, no warm-up; the stability catalogue at its default 64x48 and the scene
// plans at 64x48 with 1 round of 1 frame (the test checks the sections, not the times). Under
// CTest a fixture (tests/cli/ReportRunFixture.cmake) makes it once and names its folder in
// TIDEPOOL_REPORT_RUN_DIR; run directly, the suite makes its own.
class ReportCliTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        run_ = new CommandResult();
        if (const char* made = std::getenv("TIDEPOOL_REPORT_RUN_DIR")) {
            out_ = new std::filesystem::path(made);
            const std::string exit_code = ReadText(out_->string() + ".exit");
            run_->exit_code = exit_code.empty() ? -1 : std::stoi(exit_code);
            run_->out = ReadText(out_->string() + ".out");
            run_->err = ReadText(out_->string() + ".err");
            return;
        }
        dir_ = new TempDir();
        out_ = new std::filesystem::path(dir_->Path() / "run");
        *run_ = RunTidepoolInSourceRoot(std::string(TIDEPOOL_REPORT_RUN_ARGS) + " --out '" +
                                        out_->string() + "' --progress-log '" +
                                        ProgressLog().string() + "'");
    }
    static void TearDownTestSuite() {
        delete run_;
        delete out_;
        delete dir_;
        run_ = nullptr;
        out_ = nullptr;
        dir_ = nullptr;
    }
    static std::filesystem::path Out() { return *out_; }
    // The run's --progress-log, beside its output folder (which must hold tidepool's files only).
    static std::filesystem::path ProgressLog() { return out_->string() + ".progress.jsonl"; }

    static TempDir* dir_;
    static std::filesystem::path* out_;
    static CommandResult* run_;
};

TempDir* ReportCliTest::dir_ = nullptr;
std::filesystem::path* ReportCliTest::out_ = nullptr;
CommandResult* ReportCliTest::run_ = nullptr;

TEST_F(ReportCliTest, RunWritesManifestResultsAndAllThreeReportFormats) {
    ASSERT_EQ(run_->exit_code, 0) << run_->err;
    EXPECT_TRUE(std::filesystem::is_regular_file(Out() / "manifest/manifest.json"));
    EXPECT_TRUE(std::filesystem::is_regular_file(Out() / "render/results.json"));
    EXPECT_TRUE(std::filesystem::is_regular_file(Out() / "render/stability.json"));
    EXPECT_TRUE(std::filesystem::is_regular_file(Out() / "render/plans.json"));
    for (const char* file : {"index.html", "report.md", "data.json"}) {
        EXPECT_TRUE(std::filesystem::is_regular_file(Out() / "default" / file)) << file;
    }
    const nlohmann::json data = nlohmann::json::parse(ReadText(Out() / "default/data.json"));
    EXPECT_EQ(data["schema"], "tidepool.report");
    EXPECT_EQ(data["version"], 2);
    ASSERT_EQ(data["whitepaper_rows"].size(), 11u);
    for (const nlohmann::json& row : data["whitepaper_rows"]) {
        EXPECT_NE(row["verdict"], "failed") << row.dump();
    }
    EXPECT_FALSE(data["pareto_frontier"].empty());
    // `run` measures CPU time beside wall time, so the report compares on it.
    EXPECT_EQ(data["method"]["clock"], "cpu");
    EXPECT_EQ(data["scenes"]["present"], true);
    EXPECT_FALSE(data["scenes"]["plans"].empty());
    EXPECT_TRUE(data["stability"].contains("cases")) << data["stability"].dump().substr(0, 500);
    // The whitepaper table is data, on stdout; progress and diagnostics are on stderr.
    EXPECT_NE(run_->out.find("reflection_refraction"), std::string::npos) << run_->out;
    EXPECT_NE(run_->err.find("run: "), std::string::npos) << run_->err;
    // Well under the ~10 MB a page should weigh.
    EXPECT_LT(std::filesystem::file_size(Out() / "default/index.html"), 10u * 1000u * 1000u);
}

// `run` renders in a worker process and runs the stability catalogue and the plans in another,
// and each closes the descriptors it did not make: both append to the progress log all the same.
TEST_F(ReportCliTest, RunsProgressLogHoldsTheRendersStatesAndEveryProcesssLines) {
    ASSERT_EQ(run_->exit_code, 0) << run_->err;
    std::ifstream in(ProgressLog());
    std::string text;
    std::vector<std::string> lines;
    std::vector<nlohmann::json> states;
    while (std::getline(in, text)) {
        const nlohmann::json record = nlohmann::json::parse(text);  // each line whole
        if (record.contains("line")) {
            lines.push_back(record["line"]);
        } else {
            states.push_back(record);
        }
    }
    auto told = [&](const std::string& start) {
        return std::any_of(lines.begin(), lines.end(),
                           [&](const std::string& l) { return l.rfind(start, 0) == 0; });
    };
    EXPECT_TRUE(told("validate: ")) << "the parent's";
    EXPECT_TRUE(told("render: ")) << "the render process's";
    EXPECT_TRUE(told("stability and plans: ")) << "the second process's";
    ASSERT_FALSE(states.empty());
    EXPECT_TRUE(states.front()["parts"].contains("comparison_frames_left")) << states.front();
    EXPECT_NEAR(states.back()["percent"].get<double>(), 100.0, 1e-9) << states.back();
}

// One rendering thread by default (llvmpipe's contexts in one process share one rasteriser
// lock), and the stability and plan stages in a second process of their own beside it.
TEST_F(ReportCliTest, RunRendersOnOneThreadWithStabilityAndPlansInASecondProcess) {
    ASSERT_EQ(run_->exit_code, 0) << run_->err;
    const nlohmann::json results = nlohmann::json::parse(ReadText(Out() / "render/results.json"));
    EXPECT_EQ(results["settings"]["workers"], 1);
    EXPECT_NE(run_->err.find(", 1 workers, "), std::string::npos) << run_->err;
    EXPECT_NE(run_->err.find("\nstability and plans: "), std::string::npos) << run_->err;
    EXPECT_NE(run_->err.find(" s in a second process, beside the render\n"), std::string::npos)
            << run_->err;
}

TEST_F(ReportCliTest, PageRendersInHeadlessChromiumWithEveryImageAndEveryWhitepaperRow) {
    ASSERT_EQ(run_->exit_code, 0) << run_->err;
    if (RunShell("command -v chromium").exit_code != 0) {
        GTEST_SKIP() << "chromium is not installed (scripts/install-deps.sh installs it)";
    }
    TempDir profile;
    const CommandResult dom = RunShell(
            "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic "
            "--no-first-run --disable-background-networking --disable-component-update "
            "--disable-sync --user-data-dir='" +
            profile.Path().string() + "' --virtual-time-budget=5000 --dump-dom 'file://" +
            (Out() / "default/index.html").string() + "' 2>/dev/null");
    ASSERT_EQ(dom.exit_code, 0) << dom.out.substr(0, 2000);
    std::smatch loaded;
    ASSERT_TRUE(std::regex_search(dom.out, loaded,
                                  std::regex("data-images-loaded=\"([0-9]+)/([0-9]+)\"")))
            << "the page's load script did not run";
    EXPECT_EQ(loaded[1].str(), loaded[2].str()) << "images that did not load";
    EXPECT_GT(std::stoi(loaded[2].str()), 0);
    for (int row = 1; row <= 11; ++row) {
        EXPECT_NE(dom.out.find("wp-row-" + std::to_string(row) + "\""), std::string::npos)
                << "whitepaper row " << row;
    }
    EXPECT_NE(dom.out.find("<svg"), std::string::npos);
    EXPECT_NE(dom.out.find("Pareto frontier"), std::string::npos);
    // run wrote stability.json and plans.json, so both sections show their tables, not how-tos.
    EXPECT_NE(dom.out.find("<h2 id=\"stability\">7. Numerical stability</h2>"), std::string::npos);
    EXPECT_NE(dom.out.find("<h2 id=\"scenes\">8. Scenes</h2>"), std::string::npos);
    EXPECT_NE(dom.out.find("<h2 id=\"reflections\">9. Reflection techniques</h2>"),
              std::string::npos);
    EXPECT_EQ(dom.out.find("No numerical-stability catalogue was found"), std::string::npos);
    EXPECT_EQ(dom.out.find("No scene plans were found"), std::string::npos);
    EXPECT_NE(dom.out.find("murky_pond"), std::string::npos);
}

TEST_F(ReportCliTest, ReportRebuildsFromSavedFilesWithoutRendering) {
    ASSERT_EQ(run_->exit_code, 0) << run_->err;
    const CommandResult r = RunTidepoolInSourceRoot(
            "report --manifest '" + (Out() / "manifest/manifest.json").string() + "' --results '" +
            (Out() / "render/results.json").string() + "' --name again --out '" + Out().string() +
            "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(Out() / "again/index.html"));
    EXPECT_EQ(r.err.find("render:"), std::string::npos) << "report must not render";
    EXPECT_NE(r.out.find("reflection_refraction"), std::string::npos) << r.out;
}

// --name is one folder under --out, and --out a folder: anything else is exit 2, nothing written.
TEST_F(ReportCliTest, ReportRefusesANameOutsideOutAndAnOutThatIsAFile) {
    ASSERT_EQ(run_->exit_code, 0) << run_->err;
    TempDir dir;
    const std::filesystem::path file = dir.Write("afile", "x");
    const std::string inputs = "report --manifest '" + (Out() / "manifest/manifest.json").string() +
                               "' --results '" + (Out() / "render/results.json").string() + "'";
    const std::string out = " --out '" + (dir.Path() / "out").string() + "'";
    for (const char* name : {"../escaped", "a/b", ".hidden"}) {
        SCOPED_TRACE(name);
        const CommandResult r =
                RunTidepoolInSourceRoot(inputs + out + " --name " + std::string(name));
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_EQ(r.err.rfind("error: --name must be a plain folder name, not '", 0), 0U) << r.err;
    }
    const CommandResult long_name =
            RunTidepoolInSourceRoot(inputs + out + " --name " + std::string(256, 'n'));
    EXPECT_EQ(long_name.exit_code, 2) << long_name.err;
    EXPECT_EQ(long_name.err, "error: --name must be a folder name of at most 255 bytes, not 256\n");
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "out"));
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "escaped"));
    const CommandResult r = RunTidepoolInSourceRoot(inputs + " --out '" + file.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "error: " + file.string() +
                             " is a file, not a folder; nothing was changed. Choose another --out "
                             "folder.\n");
    EXPECT_EQ(ReadText(file), "x");
}

TEST_F(ReportCliTest, MissingImageExitsTwoNamingTheFileAndWritesNothing) {
    ASSERT_EQ(run_->exit_code, 0) << run_->err;
    TempDir copy;
    std::filesystem::copy(Out() / "render", copy.Path() / "render",
                          std::filesystem::copy_options::recursive);
    const nlohmann::json results =
            nlohmann::json::parse(ReadText(copy.Path() / "render/results.json"));
    const std::string image = results["configurations"][0]["views"][0]["image"];
    const std::filesystem::path missing = copy.Path() / "render" / image;
    ASSERT_TRUE(std::filesystem::remove(missing));
    const CommandResult r = RunTidepoolInSourceRoot(
            "report --manifest '" + (Out() / "manifest/manifest.json").string() + "' --results '" +
            (copy.Path() / "render/results.json").string() + "' --out '" +
            (copy.Path() / "out").string() + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(std::filesystem::exists(copy.Path() / "out" / "default"));
}

// Issue 14: a wrongly typed field in any of the four stage files, as the real writers laid
// them out, is exit 2 with the file and the field's path on stderr, and no report is written.
TEST_F(ReportCliTest, WronglyTypedFieldInAnyStageFileExitsTwoNamingTheFileAndField) {
    ASSERT_EQ(run_->exit_code, 0) << run_->out;
    struct Case {
        const char* file;  // relative to the run's folder
        const char* pointer;
        nlohmann::json value;
        const char* message;
    };
    const std::vector<Case> cases = {
            {"manifest/manifest.json", "/counts/variants", "many",
             "'counts.variants' has the wrong type (expected number, found string)"},
            {"manifest/manifest.json", "/variants/0/stages/fragment/cost/total_ops", "9",
             "'variants[0].stages.fragment.cost.total_ops' has the wrong type (expected number, "
             "found string)"},
            {"manifest/manifest.json", "/variants/0/valid", 1,
             "'variants[0].valid' has the wrong type (expected bool, found number)"},
            {"render/results.json", "/comparisons/0/baseline_ms/0", true,
             "'comparisons[0].baseline_ms[0]' has the wrong type (expected number, found bool)"},
            {"render/results.json", "/configurations/0/ok", "true",
             "'configurations[0].ok' has the wrong type (expected bool, found string)"},
            {"render/results.json", "/settings/width", "160",
             "'settings.width' has the wrong type (expected number, found string)"},
            {"render/results.json", "/environment/timer_query", nullptr,
             "'environment.timer_query' has the wrong type (expected bool, found null)"},
            {"render/stability.json", "/cases/0/passed", "yes",
             "'cases[0].passed' has the wrong type (expected bool, found string)"},
            {"render/plans.json", "/plans/0/candidates/0/psnr_db", "high",
             "'plans[0].candidates[0].psnr_db' has the wrong type (expected number, found "
             "string)"},
    };
    for (const Case& c : cases) {
        TempDir copy;
        for (const char* folder : {"manifest", "render"}) {
            std::filesystem::copy(Out() / folder, copy.Path() / folder,
                                  std::filesystem::copy_options::recursive);
        }
        const std::filesystem::path file = copy.Path() / c.file;
        nlohmann::json document = nlohmann::json::parse(ReadText(file));
        document[nlohmann::json::json_pointer(c.pointer)] = c.value;
        std::ofstream(file, std::ios::trunc) << document.dump();
        const CommandResult r = tidepool::testing::RunTidepool(
                "report --manifest '" + (copy.Path() / "manifest/manifest.json").string() +
                        "' --results '" + (copy.Path() / "render/results.json").string() +
                        "' --out '" + (copy.Path() / "out").string() + "'",
                copy.Path());
        EXPECT_EQ(r.exit_code, 2) << c.file << ": " << r.err;
        EXPECT_NE(r.err.find(file.string() + ": " + c.message), std::string::npos)
                << c.file << ": " << r.err;
        EXPECT_EQ(r.out, "") << c.file;
        EXPECT_FALSE(std::filesystem::exists(copy.Path() / "out")) << c.file;
    }
}

TEST_F(ReportCliTest, CorruptManifestOrMissingResultsExitTwoNamingTheFile) {
    TempDir dir;
    const std::filesystem::path manifest = dir.Write("manifest.json", "{\"schema\": \"tidep");
    CommandResult r =
            RunTidepoolInSourceRoot("report --manifest '" + manifest.string() + "' --results '" +
                                    (dir.Path() / "results.json").string() + "' --out '" +
                                    (dir.Path() / "out").string() + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(manifest.string() + ":1:18: not valid JSON: "), std::string::npos)
            << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "out"));

    if (run_->exit_code == 0) {
        r = RunTidepoolInSourceRoot("report --manifest '" +
                                    (Out() / "manifest/manifest.json").string() + "' --results '" +
                                    (dir.Path() / "nope.json").string() + "' --out '" +
                                    (dir.Path() / "out").string() + "'");
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find((dir.Path() / "nope.json").string() + ": no such file"),
                  std::string::npos)
                << r.err;
    }
}

// Before, a bad scene was found beside the render, minutes in, and counted as a plan that missed
// its target (exit 1); a missing scenes folder was exit 3 after the render.
TEST_F(ReportCliTest, RunReadsEverySceneBeforeAnyWork) {
    TempDir dir;
    dir.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n");
    dir.Write("s.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
    dir.Write("s.fsh",
              "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = vec4(1.0); "
              "}\n");
    const std::string command = "run --config '" + (dir.Path() / "v.yaml").string() + "' --out '" +
                                (dir.Path() / "out").string() + "'";
    CommandResult r = RunTidepoolInSourceRoot(command);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "error: plans: no scenes/*.yaml in " + (dir.Path() / "scenes").string() +
                             "; add one, or run with --no-plans\n");
    dir.Write("scenes/bad.yaml", "version: 1\nwater: {depth: 9999}\n");
    r = RunTidepoolInSourceRoot(command);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind((dir.Path() / "scenes/bad.yaml").string() +
                                  ":2:16: error: water.depth must be between 0.5 and 200, not "
                                  "9999",
                          0),
              0U)
            << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "out"));
}

TEST_F(ReportCliTest, RunRejectsBadFlagsWithExitTwo) {
    EXPECT_EQ(RunTidepoolInSourceRoot("run --size 0x0 --out /tmp/never").exit_code, 2);
    EXPECT_EQ(RunTidepoolInSourceRoot("run --name render --out /tmp/never").exit_code, 2);
    EXPECT_EQ(RunTidepoolInSourceRoot(
                      "run --no-stability --no-plans --plan-size 8x8 --out /tmp/never")
                      .exit_code,
              2);
    EXPECT_FALSE(std::filesystem::exists("/tmp/never"));
}

}  // namespace
