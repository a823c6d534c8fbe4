// `tidepool validate` with its validation cache, as a user runs it: --cache, --no-cache, the
// default folder, concurrent processes.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "FileContents.h"
#include "TempDir.h"
#include "TidepoolProcess.h"

namespace {

using tidepool::testing::CommandResult;
using tidepool::testing::ReadText;
using tidepool::testing::RunShell;
using tidepool::testing::RunTidepool;
using tidepool::testing::TempDir;

std::string Quoted(const std::filesystem::path& path) {
    std::string quoted(1, '\'');  // appended, not `"'" + string`: GCC 12 warns falsely (-Wrestrict)
    quoted += path.string();
    quoted += '\'';
    return quoted;
}

std::size_t EntryCount(const std::filesystem::path& folder) {
    std::size_t count = 0;
    std::error_code ec;
    for (std::filesystem::recursive_directory_iterator it(folder, ec), end; !ec && it != end;
         it.increment(ec)) {
        count += it->is_regular_file() ? 1U : 0U;
    }
    return count;
}

class CacheCliTest : public ::testing::Test {
protected:
    CacheCliTest() {
        dir_.Write("s.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
        dir_.Write("s.fsh",
                   "#version 100\nprecision mediump float;\nvoid main() {\n#ifdef B\n"
                   "  gl_FragColor = vec4(oops);\n#else\n  gl_FragColor = vec4(1.0);\n#endif\n}\n");
        dir_.Write(
                "v.yaml",
                "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n    features: [A, B]\n");
    }
    TempDir dir_;
};

TEST_F(CacheCliTest, WarmCacheGivesTheSameDiagnosticsAndExitCodeAsNoCache) {
    const std::string cache = Quoted(dir_.Path() / "cache");
    const CommandResult uncached = RunTidepool("validate --config v.yaml --no-cache", dir_.Path());
    const CommandResult cold =
            RunTidepool("validate --config v.yaml --cache " + cache, dir_.Path());
    const CommandResult warm =
            RunTidepool("validate --config v.yaml --cache " + cache, dir_.Path());
    EXPECT_EQ(uncached.exit_code, 1) << uncached.err;
    EXPECT_NE(uncached.err.find("s.fsh:5:23: error: 'oops' : undeclared identifier [p:B]"),
              std::string::npos)
            << uncached.err;
    EXPECT_NE(uncached.out.find("2 INVALID"), std::string::npos) << uncached.out;
    EXPECT_EQ(cold.exit_code, 1);
    EXPECT_EQ(warm.exit_code, 1);
    EXPECT_EQ(cold.err, uncached.err);
    EXPECT_EQ(warm.err, uncached.err);
    EXPECT_EQ(cold.out, uncached.out);
    EXPECT_EQ(warm.out, uncached.out);
    EXPECT_GT(EntryCount(dir_.Path() / "cache"), 0U);
}

TEST_F(CacheCliTest, NoCacheWritesNothing) {
    dir_.Write("xdg/keep", "");
    const CommandResult r = RunTidepool("validate --config v.yaml --no-cache", dir_.Path());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const CommandResult with_env = RunTidepool("validate --config v.yaml --no-cache", dir_.Path(),
                                               "XDG_CACHE_HOME=" + Quoted(dir_.Path() / "xdg"));
    EXPECT_EQ(with_env.exit_code, 1) << with_env.err;
    EXPECT_FALSE(std::filesystem::exists(dir_.Path() / "xdg" / "tidepool"));
}

TEST_F(CacheCliTest, DefaultFolderIsTidepoolUnderXdgCacheHome) {
    const CommandResult r = RunTidepool("validate --config v.yaml", dir_.Path(),
                                        "XDG_CACHE_HOME=" + Quoted(dir_.Path() / "xdg"));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_GT(EntryCount(dir_.Path() / "xdg" / "tidepool" / "v1"), 0U);
}

TEST_F(CacheCliTest, CacheAndNoCacheTogetherAreAUsageError) {
    const CommandResult r =
            RunTidepool("validate --config v.yaml --no-cache --cache c", dir_.Path());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--no-cache"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST_F(CacheCliTest, UnwritableCacheFolderWarnsAndStillValidates) {
    dir_.Write("file", "a file where the cache folder should be");
    const CommandResult r = RunTidepool(
            "validate --config v.yaml --cache " + Quoted(dir_.Path() / "file" / "cache"),
            dir_.Path());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("warning: validation cache"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("2 INVALID"), std::string::npos) << r.out;
}

TEST_F(CacheCliTest, PlainFilesWithAWarmCacheGiveTheSameDiagnosticsAndExitCodeAsNoCache) {
    const std::string cache = Quoted(dir_.Path() / "cache");
    for (const char* files : {"s.vsh s.fsh", "-D B s.vsh s.fsh", "--json -D B s.vsh s.fsh",
                              "--format sarif -D B s.fsh"}) {
        SCOPED_TRACE(files);
        const std::string args = std::string("validate ") + files;
        const CommandResult uncached = RunTidepool(args + " --no-cache", dir_.Path());
        const CommandResult cold = RunTidepool(args + " --cache " + cache, dir_.Path());
        const std::size_t entries = EntryCount(dir_.Path() / "cache");
        const CommandResult warm = RunTidepool(args + " --cache " + cache, dir_.Path());
        EXPECT_EQ(cold.exit_code, uncached.exit_code);
        EXPECT_EQ(warm.exit_code, uncached.exit_code);
        EXPECT_EQ(cold.out, uncached.out);
        EXPECT_EQ(warm.out, uncached.out);
        EXPECT_EQ(cold.err, uncached.err);
        EXPECT_EQ(warm.err, uncached.err);
        EXPECT_GT(entries, 0U);
        EXPECT_EQ(EntryCount(dir_.Path() / "cache"), entries) << "the warm run wrote entries";
    }
    const CommandResult broken =
            RunTidepool("validate -D B s.vsh s.fsh --cache " + cache, dir_.Path());
    EXPECT_EQ(broken.exit_code, 1);
    EXPECT_NE(broken.err.find("s.fsh:5:23: error: 'oops' : undeclared identifier"),
              std::string::npos)
            << broken.err;
    // The default folder and --no-cache, as for a configuration.
    const CommandResult home = RunShell("cd " + Quoted(dir_.Path()) +
                                        " && XDG_CACHE_HOME=" + Quoted(dir_.Path() / "xdg") +
                                        " '" TIDEPOOL_BINARY "' validate s.vsh s.fsh 2>&1");
    EXPECT_EQ(home.exit_code, 0) << home.out;
    EXPECT_GT(EntryCount(dir_.Path() / "xdg" / "tidepool" / "v1"), 0U);
    const CommandResult off = RunShell("cd " + Quoted(dir_.Path()) +
                                       " && XDG_CACHE_HOME=" + Quoted(dir_.Path() / "xdg2") +
                                       " '" TIDEPOOL_BINARY "' validate --no-cache s.vsh 2>&1");
    EXPECT_EQ(off.exit_code, 0) << off.out;
    EXPECT_FALSE(std::filesystem::exists(dir_.Path() / "xdg2" / "tidepool"));
}

// glslang refuses `##` in ES and pastes all the same, so a define the text never spells changes
// its messages: a cached result keyed without it was another define's (found by review).
TEST_F(CacheCliTest, ATextThatPastesTokensKeysEveryDefine) {
    dir_.Write("paste.fsh",
               "#version 100\nprecision mediump float;\n#define CAT(a, b) a##b\n"
               "void main() { float x = CAT(VAL, UE); gl_FragColor = vec4(x); }\n");
    dir_.Write("pv.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: paste.fsh\n"
               "    axes:\n      VALUE: [one, two]\n");
    const std::string cache = Quoted(dir_.Path() / "cache");
    for (const char* args : {"validate paste.fsh -D VALUE=1.0", "validate paste.fsh -D VALUE=1",
                             "validate paste.fsh -D VALUE=1.0", "validate --config pv.yaml"}) {
        SCOPED_TRACE(args);
        const CommandResult fresh = RunTidepool(std::string(args) + " --no-cache", dir_.Path());
        const CommandResult cached =
                RunTidepool(std::string(args) + " --cache " + cache, dir_.Path());
        EXPECT_EQ(cached.exit_code, fresh.exit_code);
        EXPECT_EQ(cached.err, fresh.err);
        EXPECT_EQ(cached.out, fresh.out);
    }
    // Each value of the axis is its own stage program: the message names each variant's own.
    const CommandResult config = RunTidepool("validate --config pv.yaml --no-cache", dir_.Path());
    EXPECT_NE(config.err.find("[p:VALUE_ONE]"), std::string::npos) << config.err;
    EXPECT_NE(config.err.find("[p:VALUE_TWO]"), std::string::npos) << config.err;
}

// How many entries of `folder` are whole-run records (RunRecordCache.h).
std::size_t RunRecordCount(const std::filesystem::path& folder) {
    std::size_t count = 0;
    std::error_code ec;
    for (std::filesystem::recursive_directory_iterator it(folder, ec), end; !ec && it != end;
         it.increment(ec)) {
        if (it->is_regular_file() &&
            ReadText(it->path()).find("tidepool run record 1\n") != std::string::npos) {
            ++count;
        }
    }
    return count;
}

TEST_F(CacheCliTest, RunRecordRepeatsOutputExitCodeAndWrittenFilesByteForByte) {
    const std::string cache = Quoted(dir_.Path() / "cache");
    const std::vector<std::string> written = {"m/manifest.json", "m.d", "r.sarif"};
    // What a run printed, returned and wrote, the written files removed for the next run.
    auto run = [&](const std::string& args) {
        const CommandResult r = RunTidepool(args, dir_.Path());
        std::string all = std::to_string(r.exit_code) + "\n--out\n" + r.out + "--err\n" + r.err;
        for (const std::string& name : written) {
            const std::filesystem::path file = dir_.Path() / name;
            all += "--" + name + "\n" +
                   (std::filesystem::exists(file) ? ReadText(file) : std::string("(none)"));
            std::filesystem::remove(file);
        }
        return all;
    };
    std::size_t records = 0;
    for (const char* options :
         {"", "--json", "--format sarif", "--out m --depfile m.d", "--json --out m",
          "--format sarif --output-file r.sarif", "--program p --target webgl1"}) {
        SCOPED_TRACE(options);
        const std::string args = std::string("validate --config v.yaml ") + options;
        const std::string uncached = run(args + " --no-cache");
        EXPECT_EQ(run(args + " --cache " + cache), uncached);  // the miss, which keeps a record
        EXPECT_EQ(RunRecordCount(dir_.Path() / "cache"), ++records);
        EXPECT_EQ(run(args + " --cache " + cache), uncached);  // the hit
        EXPECT_EQ(run(args + " --cache " + cache), uncached);
    }
    // A shader's new bytes are a miss: the fixed shader validates.
    dir_.Write("s.fsh",
               "#version 100\nprecision mediump float;\n"
               "void main() { gl_FragColor = vec4(1.0); }\n");
    const std::string fixed = run("validate --config v.yaml --no-cache");
    EXPECT_NE(fixed.find("all valid"), std::string::npos) << fixed;
    EXPECT_EQ(run("validate --config v.yaml --cache " + cache), fixed);
    EXPECT_EQ(run("validate --config v.yaml --cache " + cache), fixed);
}

TEST_F(CacheCliTest, ConcurrentProcessesShareOneCacheFolderWithoutError) {
    // The default matrix, cold: both processes miss, store the same entries and race on every
    // rename; then two warm processes read what the first two wrote.
    const std::string cache = Quoted(dir_.Path() / "cache");
    for (const char* round : {"cold", "warm"}) {
        SCOPED_TRACE(round);
        // Both in the background, each with its own output files; `wait` for both.
        std::string script;
        for (const char* name : {"a", "b"}) {
            const std::filesystem::path out = dir_.Path() / (std::string(round) + name);
            script += "( '" TIDEPOOL_BINARY "' validate --json --config '" TIDEPOOL_SOURCE_ROOT
                      "/variants.yaml' --cache " +
                      cache + " > " + Quoted(out.string() + ".out") + " 2> " +
                      Quoted(out.string() + ".err") + "; echo $? > " +
                      Quoted(out.string() + ".code") + " ) & ";
        }
        script += "wait";
        ASSERT_EQ(RunShell(script).exit_code, 0);
        const std::filesystem::path a = dir_.Path() / (std::string(round) + "a");
        const std::filesystem::path b = dir_.Path() / (std::string(round) + "b");
        EXPECT_EQ(ReadText(a.string() + ".code"), "0\n") << ReadText(a.string() + ".err");
        EXPECT_EQ(ReadText(b.string() + ".code"), "0\n") << ReadText(b.string() + ".err");
        EXPECT_EQ(ReadText(a.string() + ".err"), "");
        EXPECT_EQ(ReadText(b.string() + ".err"), "");
        // EXPECT_TRUE, not EXPECT_EQ: a failure must not print two manifests of 400 kB.
        const std::string manifest = ReadText(a.string() + ".out");
        EXPECT_TRUE(manifest == ReadText(b.string() + ".out")) << "the two processes disagree";
        EXPECT_TRUE(manifest == ReadText((dir_.Path() / "colda").string() + ".out"))
                << "the warm processes disagree with the cold ones";
        EXPECT_NE(manifest.find("\"invalid\": 0"), std::string::npos);
    }
    EXPECT_GT(EntryCount(dir_.Path() / "cache"), 0U);
}

}  // namespace
