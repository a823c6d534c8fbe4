// Output folders as a user and a crash see them: tidepool replaces only its own folders, a failed
// write is exit 3 with nothing half-written, and a killed run leaves the previous output intact.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "FileContents.h"
#include "TempDir.h"
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using tidepool::testing::FolderEntries;
using tidepool::testing::ReadText;
using tidepool::testing::TempDir;

struct Outcome {
    int exit_code = -1;   // -1 when killed
    bool killed = false;  // by the test's SIGKILL
    std::string out;
    std::string err;
};

struct RunSettings {
    fs::path cwd = TIDEPOOL_SOURCE_ROOT;
    rlim_t file_size_limit = RLIM_INFINITY;  // bytes; writes beyond fail with EFBIG
    int kill_after_us = -1;                  // SIGKILL this long after the start, if still running
};

// Runs the tidepool binary with `args`, stdout and stderr captured apart.
Outcome RunBinary(const std::vector<std::string>& args, const RunSettings& settings = {}) {
    TempDir capture;
    const fs::path out_path = capture.Path() / "out";
    const fs::path err_path = capture.Path() / "err";
    // Everything the child needs is made before fork: tests fork from several threads, and only
    // async-signal-safe calls are safe in the child then.
    std::string binary = TIDEPOOL_BINARY;
    std::vector<std::string> copies = args;
    std::vector<char*> argv;
    argv.push_back(binary.data());
    for (std::string& a : copies) {
        argv.push_back(a.data());
    }
    argv.push_back(nullptr);
    const rlimit limit{settings.file_size_limit, settings.file_size_limit};
    const pid_t child = ::fork();
    if (child == 0) {
        const int out_fd = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err_fd = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (::chdir(settings.cwd.c_str()) != 0 || out_fd < 0 || err_fd < 0 ||
            ::dup2(out_fd, 1) < 0 || ::dup2(err_fd, 2) < 0) {
            ::_exit(126);
        }
        if (settings.file_size_limit != RLIM_INFINITY) {
            // Ignored signals stay ignored across exec, so the write fails with EFBIG instead of
            // the process dying: a full disk without root or a special mount.
            ::signal(SIGXFSZ, SIG_IGN);
            ::setrlimit(RLIMIT_FSIZE, &limit);
        }
        ::execv(binary.c_str(), argv.data());
        ::_exit(127);
    }
    Outcome outcome;
    int status = 0;
    if (settings.kill_after_us >= 0) {
        const auto deadline = std::chrono::steady_clock::now() +
                              std::chrono::microseconds(settings.kill_after_us);
        while (::waitpid(child, &status, WNOHANG) == 0) {
            if (std::chrono::steady_clock::now() >= deadline) {
                ::kill(child, SIGKILL);
                ::waitpid(child, &status, 0);
                break;
            }
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
    } else {
        ::waitpid(child, &status, 0);
    }
    outcome.killed = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
    outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    outcome.out = ReadText(out_path);
    outcome.err = ReadText(err_path);
    return outcome;
}

// Every file under `folder` (relative path → content), to compare outputs byte for byte.
std::map<std::string, std::string> Snapshot(const fs::path& folder) {
    std::map<std::string, std::string> files;
    if (!fs::exists(folder)) {
        return files;
    }
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) {
            files[fs::relative(entry.path(), folder).string()] = ReadText(entry.path());
        }
    }
    return files;
}

const std::string kConfig = std::string(TIDEPOOL_SOURCE_ROOT) + "/variants.yaml";

std::vector<std::string> RenderArgs(const fs::path& out) {
    return {"render",   "--config",    kConfig,  "--preset",        "full",
            "--size",   "32x24",       "--view", "three_quarter",   "--min-pairs",
            "10",       "--max-pairs", "10",     "--coarse-frames", "1",
            "--warmup", "0",           "--out",  out.string()};
}

// A render folder is whole when results.json parses and every image it names is a PNG there,
// and nothing else is in it.
bool IsWholeRender(const std::map<std::string, std::string>& files) {
    auto results = files.find("results.json");
    if (results == files.end() || files.count(".tidepool-output") == 0) {
        return false;
    }
    const nlohmann::json json = nlohmann::json::parse(results->second, nullptr, false);
    if (!json.is_object() || !json.contains("configurations")) {
        return false;
    }
    std::size_t images = 0;
    for (const nlohmann::json& c : json["configurations"]) {
        for (const nlohmann::json& v : c.value("views", nlohmann::json::array())) {
            const std::string image = v.value("image", std::string());
            if (image.empty()) {
                continue;
            }
            auto png = files.find(image);
            if (png == files.end() || png->second.compare(0, 4, "\x89PNG") != 0) {
                return false;
            }
            ++images;
        }
    }
    return images > 0 && files.size() == images + 2;
}

// --- Item 7: only tidepool's own folders are replaced -----------------------------------------

TEST(PublishCliTest, ExpandOutRefusesAFolderThatMerelyHoldsAManifest) {
    TempDir dir;
    dir.Write("D/manifest.json", "{\"name\": \"my web app\"}");
    dir.Write("D/index.html", "mine");
    const Outcome r =
            RunBinary({"expand", "--config", kConfig, "--out", (dir.Path() / "D").string()});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find((dir.Path() / "D").string() + ": exists and was not written by tidepool"),
              std::string::npos)
            << r.err;
    EXPECT_NE(r.err.find("Choose another --out folder"), std::string::npos) << r.err;
    EXPECT_EQ(Snapshot(dir.Path() / "D").size(), 2u);
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"D"});
}

TEST(PublishCliTest, ExpandOutReplacesItsOwnOutputAlsoWithATrailingSlash) {
    TempDir dir;
    const std::string out = (dir.Path() / "D").string();
    ASSERT_EQ(RunBinary({"expand", "--config", kConfig, "--out", out}).exit_code, 0);
    const Outcome again = RunBinary({"expand", "--config", kConfig, "--out", out + "/"});
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_TRUE(fs::exists(dir.Path() / "D/.tidepool-output"));
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"D"});
}

// Runs `command --config kConfig --out D` against a folder D that holds a user's `file`, and
// checks that it is refused before any work, naming the file as not a tidepool `what`, with the
// file unchanged.
void ExpectUsersFileRefused(const std::string& command, const std::string& file,
                            const std::string& what, const TempDir& dir) {
    const std::string mine = "{\"name\": \"my web app\"}";
    dir.Write("D/" + file, mine);
    const Outcome r =
            RunBinary({command, "--config", kConfig, "--out", (dir.Path() / "D").string()});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find((dir.Path() / "D" / file).string() + ": exists and is not a tidepool " +
                         what),
              std::string::npos)
            << r.err;
    EXPECT_EQ(ReadText(dir.Path() / "D" / file), mine);
    EXPECT_EQ(FolderEntries(dir.Path() / "D"), std::vector<std::string>{file});
}

TEST(PublishCliTest, ValidateOutRefusesToOverwriteAUsersManifest) {
    TempDir dir;
    ExpectUsersFileRefused("validate", "manifest.json", "manifest", dir);
    // Its own manifest it replaces.
    fs::remove(dir.Path() / "D/manifest.json");
    ASSERT_EQ(RunBinary({"validate", "--config", kConfig, "--out", (dir.Path() / "D").string()})
                      .exit_code,
              0);
    EXPECT_EQ(RunBinary({"validate", "--config", kConfig, "--out", (dir.Path() / "D").string()})
                      .exit_code,
              0);
}

// Runs the command `args_for(D)` makes against a folder D of a user's that holds `file` and an
// image, and checks that it is refused with nothing changed.
void ExpectUsersFolderRefused(std::vector<std::string> (*args_for)(const fs::path&),
                              const std::string& file) {
    TempDir dir;
    dir.Write("D/" + file, "mine");
    dir.Write("D/images/photo.png", "mine");
    const Outcome r = RunBinary(args_for(dir.Path() / "D"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("was not written by tidepool"), std::string::npos) << r.err;
    EXPECT_EQ(ReadText(dir.Path() / "D" / file), "mine");
    EXPECT_EQ(ReadText(dir.Path() / "D/images/photo.png"), "mine");
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"D"});
}

TEST(PublishCliTest, RenderOutRefusesAUsersResultsBeforeRendering) {
    ExpectUsersFolderRefused(RenderArgs, "results.json");
}

// `plan` writes plans.json and its candidates' images: a folder, published whole.
std::vector<std::string> PlanArgs(const fs::path& out) {
    return {"plan",  "--config",     kConfig, "--scene", "clear_lake", "--size",
            "16x16", "--resolution", "50",    "--out",   out.string()};
}

TEST(PublishCliTest, PlanOutRefusesAFolderTidepoolDidNotWriteBeforePlanning) {
    ExpectUsersFolderRefused(PlanArgs, "plans.json");
}

// `stability` writes one file, stability.json, into a folder it shares (by default the render
// folder): a stability.json that is not tidepool's is refused, the folder's other files kept.
TEST(PublishCliTest, StabilityOutRefusesAUsersStabilityJsonBeforeRunning) {
    TempDir dir;
    ExpectUsersFileRefused("stability", "stability.json", "stability report", dir);
}

// --- Item 10: a failed write is exit 3 with nothing half-written -----------------------------

TEST(PublishCliTest, ExpandOnAFullDiskExitsThreeAndLeavesNothing) {
    TempDir dir;
    RunSettings full;
    full.file_size_limit = 512;
    // Under a folder that does not exist yet: no empty folder may be left either.
    const Outcome r = RunBinary(
            {"expand", "--config", kConfig, "--out", (dir.Path() / "new/D").string()}, full);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    EXPECT_TRUE(FolderEntries(dir.Path()).empty());
}

TEST(PublishCliTest, ValidateOnAFullDiskExitsThreeAndKeepsTheOldManifest) {
    TempDir dir;
    const std::string out = (dir.Path() / "D").string();
    ASSERT_EQ(RunBinary({"validate", "--config", kConfig, "--out", out}).exit_code, 0);
    const std::string before = ReadText(dir.Path() / "D/manifest.json");
    RunSettings full;
    full.file_size_limit = 512;
    const Outcome r = RunBinary({"validate", "--config", kConfig, "--out", out}, full);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_EQ(ReadText(dir.Path() / "D/manifest.json"), before);
    EXPECT_EQ(FolderEntries(dir.Path() / "D"), (std::vector<std::string>{"manifest.json"}));
}

TEST(PublishCliTest, RenderOnAFullDiskExitsThreeAndKeepsThePreviousOutput) {
    TempDir dir;
    const fs::path out = dir.Path() / "D";
    const Outcome first = RunBinary(RenderArgs(out));
    ASSERT_EQ(first.exit_code, 0) << first.err;
    const auto before = Snapshot(out);
    RunSettings full;
    full.file_size_limit = 100;  // below any PNG
    const Outcome r = RunBinary(RenderArgs(out), full);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_EQ(Snapshot(out), before);
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"D"});
}

TEST(PublishCliTest, ReportRefusesAFolderHoldingDataJsonAndExitsThreeOnAFullDisk) {
    TempDir dir;
    ASSERT_EQ(RunBinary({"validate", "--config", kConfig, "--out", (dir.Path() / "m").string()})
                      .exit_code,
              0);
    ASSERT_EQ(RunBinary(RenderArgs(dir.Path() / "r")).exit_code, 0);
    const std::vector<std::string> report = {"report",
                                             "--manifest",
                                             (dir.Path() / "m/manifest.json").string(),
                                             "--results",
                                             (dir.Path() / "r/results.json").string(),
                                             "--out",
                                             (dir.Path() / "o").string()};
    dir.Write("o/default/data.json", "{\"mine\": true}");
    const Outcome refused = RunBinary(report);
    EXPECT_EQ(refused.exit_code, 2) << refused.err;
    EXPECT_NE(refused.err.find("was not written by tidepool"), std::string::npos) << refused.err;
    EXPECT_EQ(ReadText(dir.Path() / "o/default/data.json"), "{\"mine\": true}");
    EXPECT_EQ(FolderEntries(dir.Path() / "o"), std::vector<std::string>{"default"});

    fs::remove_all(dir.Path() / "o/default");
    RunSettings full;
    full.file_size_limit = 2000;
    const Outcome failed = RunBinary(report, full);
    EXPECT_EQ(failed.exit_code, 3) << failed.err;
    EXPECT_NE(failed.err.find("File too large"), std::string::npos) << failed.err;
    EXPECT_TRUE(FolderEntries(dir.Path() / "o").empty());
}

// --- Items 8 and 9: SIGKILL at random points never damages the previous output ---------------

// Kills `args` `rounds` times at random points (fixed seed) within the time one whole run takes,
// and checks each time that `out` is the previous output or a whole new one; then one run to
// completion must leave no staging folder beside it.
void KillAtRandomPoints(const std::vector<std::string>& args, const fs::path& out, int rounds,
                        bool (*is_whole)(const std::map<std::string, std::string>&)) {
    // Kill times are drawn over the shortest whole run seen so far (three before the kills, and
    // every round that finished before its kill): on a busy machine a slow run would otherwise
    // put most kills after the end, and the test would then test nothing.
    const auto timed_run = [&](const RunSettings& settings, long* micros) {
        const auto start = std::chrono::steady_clock::now();
        Outcome outcome = RunBinary(args, settings);
        *micros = std::chrono::duration_cast<std::chrono::microseconds>(
                          std::chrono::steady_clock::now() - start)
                          .count();
        return outcome;
    };
    long took = std::numeric_limits<long>::max();
    for (int run = 0; run < 3; ++run) {
        long micros = 0;
        const Outcome whole = timed_run(RunSettings{}, &micros);
        ASSERT_EQ(whole.exit_code, 0) << whole.err;
        took = std::min(took, micros);
    }
    auto previous = Snapshot(out);
    ASSERT_TRUE(is_whole(previous));
    std::mt19937 random(15);
    int killed = 0;
    for (int round = 0; round < rounds; ++round) {
        RunSettings settings;
        settings.kill_after_us =
                static_cast<int>(std::uniform_int_distribution<long>(0, took)(random));
        long micros = 0;
        const Outcome r = timed_run(settings, &micros);
        killed += r.killed ? 1 : 0;
        if (!r.killed) {
            took = std::min(took, micros);
        }
        const auto now = Snapshot(out);
        if (now != previous) {
            // Killed after the publishing rename, or it finished: then the new output is whole.
            EXPECT_TRUE(is_whole(now)) << "round " << round << " at " << settings.kill_after_us
                                       << " us left a damaged output";
            previous = now;
        }
    }
    EXPECT_GT(killed, rounds / 2) << "the kills mostly came too late to test anything";
    const Outcome last = RunBinary(args);
    ASSERT_EQ(last.exit_code, 0) << last.err;
    EXPECT_EQ(FolderEntries(out.parent_path()), std::vector<std::string>{out.filename().string()});
}

TEST(PublishCliTest, KilledExpandNeverDamagesThePreviousOutputNorLeaksStaging) {
    TempDir dir;
    const fs::path out = dir.Path() / "D";
    KillAtRandomPoints(
            {"expand", "--config", kConfig, "--out", out.string()}, out, 25,
            [](const std::map<std::string, std::string>& files) {
                auto manifest = files.find("manifest.json");
                return manifest != files.end() && files.count(".tidepool-output") &&
                       nlohmann::json::parse(manifest->second, nullptr, false).is_object();
            });
}

TEST(PublishCliTest, KilledRenderNeverDamagesThePreviousOutputNorLeaksStaging) {
    TempDir dir;
    const fs::path out = dir.Path() / "D";
    KillAtRandomPoints(RenderArgs(out), out, 20, IsWholeRender);
}

// A plan folder is whole when it carries the marker, plans.json parses, and every file besides
// them is a PNG that plans.json names.
bool IsWholePlan(const std::map<std::string, std::string>& files) {
    auto plans = files.find("plans.json");
    if (plans == files.end() || files.count(".tidepool-output") == 0) {
        return false;
    }
    const nlohmann::json json = nlohmann::json::parse(plans->second, nullptr, false);
    if (!json.is_object() || json.value("schema", "") != "tidepool.plans") {
        return false;
    }
    std::vector<std::string> named;
    const std::function<void(const nlohmann::json&)> collect = [&](const nlohmann::json& j) {
        if (j.is_object() && j.contains("image") && j["image"].is_string() &&
            !j["image"].get<std::string>().empty()) {
            named.push_back(j["image"]);
        }
        if (j.is_structured()) {
            for (const nlohmann::json& child : j) {
                collect(child);
            }
        }
    };
    collect(json);
    for (const auto& [name, content] : files) {
        if (name == "plans.json" || name == ".tidepool-output") {
            continue;
        }
        if (std::find(named.begin(), named.end(), name) == named.end() ||
            content.compare(0, 4, "\x89PNG") != 0) {
            return false;
        }
    }
    return !named.empty();
}

TEST(PublishCliTest, KilledPlanNeverDamagesThePreviousOutputNorLeaksStaging) {
    TempDir dir;
    const fs::path out = dir.Path() / "D";
    KillAtRandomPoints(PlanArgs(out), out, 8, IsWholePlan);
}

// Before, two `expand --out D` at once failed about 1 run in 60 with "Directory not empty".
TEST(PublishCliTest, ConcurrentExpandsOfOneFolderAllSucceedAndLeaveNothingBehind) {
    TempDir dir;
    const std::string out = (dir.Path() / "D").string();
    std::vector<std::thread> runs;
    std::vector<int> codes(12, -2);
    for (std::size_t i = 0; i < codes.size(); ++i) {
        runs.emplace_back([&, i] {
            codes[i] = RunBinary({"expand", "--config", kConfig, "--out", out}).exit_code;
        });
    }
    for (std::thread& t : runs) {
        t.join();
    }
    for (int code : codes) {
        EXPECT_EQ(code, 0);
    }
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"D"});
}

}  // namespace
