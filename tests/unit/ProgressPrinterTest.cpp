// The render's progress printer as a log sees it (cli/GlCliSupport.h, MakeProgressPrinter):
// which calls print a line, and what the line says.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "GlCliSupport.h"

namespace tidepool::cli {
namespace {

// A printer writing into a temporary file, and the lines it has written so far.
class PrinterLog {
public:
    PrinterLog() : file_(std::tmpfile()), print_(MakeProgressPrinter(file_, false)) {}
    ~PrinterLog() {
        if (file_ != nullptr) {
            std::fclose(file_);
        }
    }
    PrinterLog(const PrinterLog&) = delete;
    PrinterLog& operator=(const PrinterLog&) = delete;

    bool Open() const { return file_ != nullptr; }
    void Tell(const runner::RunProgress& progress) const { print_(progress); }

    std::vector<std::string> Lines() const {
        std::fflush(file_);
        std::rewind(file_);
        std::vector<std::string> lines;
        char buffer[512];
        while (std::fgets(buffer, sizeof buffer, file_) != nullptr) {
            lines.emplace_back(buffer);
        }
        std::fseek(file_, 0, SEEK_END);
        return lines;
    }

private:
    std::FILE* file_;
    runner::ProgressCallback print_;
};

runner::RunProgress At(const std::string& stage, long done, double elapsed, double eta) {
    runner::RunProgress p;
    p.stage = stage;
    p.configuration = stage == "waiting for" ? "the second process's units" : "row 2";
    p.done = done;
    p.total = 100;
    p.elapsed_seconds = elapsed;
    p.eta_seconds = eta;
    p.percent = static_cast<double>(done);
    return p;
}

TEST(ProgressPrinterTest, ALogGetsALineAtEachStageAndAtMostEveryTenSeconds) {
    const PrinterLog log;
    ASSERT_TRUE(log.Open());
    log.Tell(At("images", 1, 0.4, 90));
    log.Tell(At("images", 2, 3.0, 88));       // same stage, 2.5 s later: no line
    log.Tell(At("comparisons", 3, 4.0, 87));  // a new stage: a line
    log.Tell(At("comparisons", 10, 13.9, 80));
    log.Tell(At("comparisons", 11, 14.0, 79));  // 10 s after the last line
    const std::vector<std::string> lines = log.Lines();
    ASSERT_EQ(lines.size(), 3U);
    EXPECT_EQ(lines[0], "[  1%] images row 2 (elapsed 0s, ETA 1m30s)\n");
    EXPECT_EQ(lines[1], "[  3%] comparisons row 2 (elapsed 4s, ETA 1m27s)\n");
    EXPECT_EQ(lines[2], "[ 11%] comparisons row 2 (elapsed 14s, ETA 1m19s)\n");
}

TEST(ProgressPrinterTest, TheCompleteLineIsPrintedOnceThoughTheRenderIsToldItAgain) {
    const PrinterLog log;
    ASSERT_TRUE(log.Open());
    log.Tell(At("comparisons", 99, 50.0, 1));
    // Done, but waiting for the second process: told every half second, counting down.
    log.Tell(At("waiting for", 100, 50.5, 3));
    log.Tell(At("waiting for", 100, 51.0, 2.5));
    log.Tell(At("waiting for", 100, 52.0, 0));  // the wait is over: complete, printed once
    log.Tell(At("waiting for", 100, 52.5, 0));
    log.Tell(At("waiting for", 100, 53.0, 0));
    const std::vector<std::string> lines = log.Lines();
    ASSERT_EQ(lines.size(), 3U);
    EXPECT_EQ(lines[0], "[ 99%] comparisons row 2 (elapsed 50s, ETA 1s)\n");
    EXPECT_EQ(lines[1], "[100%] waiting for the second process's units (elapsed 51s, ETA 3s)\n");
    EXPECT_EQ(lines[2], "[100%] waiting for the second process's units (elapsed 52s, ETA 0s)\n");
}

TEST(ProgressPrinterTest, ATerminalGetsOneLineRewrittenInPlace) {
    std::FILE* file = std::tmpfile();
    ASSERT_NE(file, nullptr);
    const runner::ProgressCallback print = MakeProgressPrinter(file, true);
    print(At("images", 1, 0.5, 90));
    print(At("images", 2, 3.0, 88));
    std::fflush(file);
    std::rewind(file);
    std::string text(256, '\0');
    text.resize(std::fread(text.data(), 1, text.size(), file));
    std::fclose(file);
    EXPECT_EQ(text,
              "\r\033[K[  1%] images      row 2  ETA 1m30s\r\033[K[  2%] images      row 2  ETA "
              "1m28s");
}

TEST(ProgressPrinterTest, DurationsReadInSecondsThenMinutes) {
    EXPECT_EQ(FormatDuration(0), "0s");
    EXPECT_EQ(FormatDuration(59.4), "59s");
    EXPECT_EQ(FormatDuration(59.6), "1m00s");
    EXPECT_EQ(FormatDuration(185), "3m05s");
}

}  // namespace
}  // namespace tidepool::cli
