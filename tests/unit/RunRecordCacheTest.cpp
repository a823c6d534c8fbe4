#include "tidepool/pipeline/CompilerStages.h"
#include "tidepool/pipeline/RunRecordCache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "FileContents.h"
#include "PipelineFixture.h"
#include "TempDir.h"

namespace tidepool::pipeline {
namespace {

using testing::ReadText;
using testing::TempDir;

// A time after every file the test wrote: the run "started" after its inputs were in place. The
// file system stamps writes with a coarse clock, so the time of the write itself may equal
// StartTime() taken just after it.
timespec AfterTheWrites() {
    timespec later = RunRecordCache::StartTime();
    later.tv_sec += 1;
    return later;
}

RunRecord SampleRecord() {
    RunRecord record;
    record.out = "5 variants: all valid\n";
    record.err = "s.fsh:5:3: warning: something\n";
    record.exit_code = 1;
    record.manifest = "{\n  \"schema\": \"x\"\n}\n";
    record.depfile = "";  // present but empty: kept apart from absent
    return record;
}

// Two programs over their own shader pairs, and a device limits file.
class RunRecordCacheTest : public ::testing::Test {
protected:
    RunRecordCacheTest() : cache_(dir_.Path() / "cache") {
        dir_.Write("s.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
        dir_.Write("s.fsh",
                   "#version 100\nprecision mediump float;\nvoid main() {\n#ifdef A\n"
                   "  gl_FragColor = vec4(0.5);\n#else\n  gl_FragColor = vec4(1.0);\n#endif\n}\n");
        dir_.Write("t.vsh", "#version 100\nvoid main() { gl_Position = vec4(0.0); }\n");
        dir_.Write("t.fsh",
                   "#version 100\nprecision mediump float;\n"
                   "void main() { gl_FragColor = vec4(1.0); }\n");
        dir_.Write("v.yaml",
                   "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n    features: [A]\n"
                   "  q:\n    vertex: t.vsh\n    fragment: t.fsh\n");
        dir_.Write("device.txt", "MaxVertexAttribs 16\n");
    }

    // The files a real `validate --program p --limits device.txt` run read.
    std::vector<std::filesystem::path> FilesOfARun() const {
        ValidateOptions options;
        options.config = (dir_.Path() / "v.yaml").string();
        options.program = "p";
        options.device_limits = (dir_.Path() / "device.txt").string();
        options.jobs = 1;
        options.cache.off = true;
        const ValidateResult result = ValidateMatrix(options);
        EXPECT_EQ(result.matrix.outcome.status, Status::kOk)
                << testing::Formatted(result.matrix.outcome.diagnostics);
        EXPECT_TRUE(result.repeatable);
        return result.files_read;
    }

    TempDir dir_;
    base::ContentCache cache_;
};

TEST_F(RunRecordCacheTest, EncodedRecordDecodesToTheSameRecordAndFiles) {
    const std::vector<ReadFileDigest> files = {{"/a b/v.yaml", std::string(64, 'a')},
                                               {"/s\n.vsh", std::string(64, 'b')}};
    const auto decoded = RunRecordCache::Decode(RunRecordCache::Encode(files, SampleRecord()));
    ASSERT_TRUE(decoded);
    EXPECT_TRUE(decoded->second == SampleRecord());
    ASSERT_EQ(decoded->first.size(), 2U);
    EXPECT_EQ(decoded->first[1].path, "/s\n.vsh");
    EXPECT_EQ(decoded->first[1].sha256, std::string(64, 'b'));
    EXPECT_FALSE(decoded->second.report_file);
    EXPECT_EQ(decoded->second.depfile, std::string());
}

TEST_F(RunRecordCacheTest, TruncatedOrExtendedEntryTextDoesNotDecode) {
    const std::string text = RunRecordCache::Encode({}, SampleRecord());
    for (std::size_t size = 0; size < text.size(); ++size) {
        EXPECT_FALSE(RunRecordCache::Decode(text.substr(0, size))) << size;
    }
    EXPECT_FALSE(RunRecordCache::Decode(text + "x"));
}

TEST_F(RunRecordCacheTest, HitRepeatsTheRecordTheMissKept) {
    RunRecordCache records(cache_, "validate --config v.yaml");
    EXPECT_FALSE(records.Find());
    ASSERT_TRUE(records.Keep(FilesOfARun(), AfterTheWrites(), SampleRecord()));
    const std::optional<RunRecord> hit = RunRecordCache(cache_, "validate --config v.yaml").Find();
    ASSERT_TRUE(hit);
    EXPECT_TRUE(*hit == SampleRecord());
    EXPECT_FALSE(RunRecordCache(cache_, "validate --config w.yaml").Find());
}

TEST_F(RunRecordCacheTest, RunReadsTheConfigurationEveryProgramsShadersAndTheLimits) {
    std::vector<std::string> names;
    for (const std::filesystem::path& file : FilesOfARun()) {
        names.push_back(file.filename().string());
    }
    EXPECT_EQ(names, (std::vector<std::string>{"v.yaml", "s.vsh", "s.fsh", "t.vsh", "t.fsh",
                                               "device.txt"}));
}

TEST_F(RunRecordCacheTest, ChangingTheBytesOfAnyFileReadIsAMiss) {
    RunRecordCache records(cache_, "key");
    ASSERT_TRUE(records.Keep(FilesOfARun(), AfterTheWrites(), SampleRecord()));
    for (const char* name : {"v.yaml", "s.vsh", "s.fsh", "t.vsh", "t.fsh", "device.txt"}) {
        const std::filesystem::path file = dir_.Path() / name;
        const std::string bytes = ReadText(file);
        dir_.Write(name, bytes + " ");
        EXPECT_FALSE(records.Find()) << name;
        dir_.Write(name, bytes);
        EXPECT_TRUE(records.Find()) << name;
        std::filesystem::remove(file);
        EXPECT_FALSE(records.Find()) << name << " removed";
        dir_.Write(name, bytes);
    }
}

TEST_F(RunRecordCacheTest, FileChangedAfterTheRunStartedIsNotKept) {
    const timespec started = RunRecordCache::StartTime();
    dir_.Write("s.fsh", "#version 100\nvoid main() {}\n");
    RunRecordCache records(cache_, "key");
    EXPECT_FALSE(
            records.Keep({dir_.Path() / "v.yaml", dir_.Path() / "s.fsh"}, started, SampleRecord()));
    EXPECT_FALSE(records.Find());
    EXPECT_FALSE(records.Keep({dir_.Path() / "missing.vsh"}, AfterTheWrites(), SampleRecord()));
    EXPECT_FALSE(records.Find());
}

TEST_F(RunRecordCacheTest, CorruptEntryIsDetectedAndTheNextKeepRewritesIt) {
    RunRecordCache records(cache_, "key");
    const std::vector<std::filesystem::path> files = {dir_.Path() / "v.yaml"};
    ASSERT_TRUE(records.Keep(files, AfterTheWrites(), SampleRecord()));
    const std::filesystem::path entry = cache_.EntryPath(records.Key());
    std::string bytes = ReadText(entry);
    bytes[bytes.size() - 3] ^= 1;  // inside the record, past the checksum line
    std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes;
    EXPECT_FALSE(records.Find());
    EXPECT_EQ(cache_.Stats().corrupt, 1U);
    ASSERT_TRUE(records.Keep(files, AfterTheWrites(), SampleRecord()));
    const std::optional<RunRecord> hit = records.Find();
    ASSERT_TRUE(hit);
    EXPECT_TRUE(*hit == SampleRecord());
}

}  // namespace
}  // namespace tidepool::pipeline
