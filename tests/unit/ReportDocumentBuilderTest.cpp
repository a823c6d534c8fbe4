// The report document built from a model (reports/src/ReportDocumentBuilder.h): the sections in
// order, the lead that warns of failed configurations, and where the reflection panels' files
// start. What each section says is checked on the written pages (ReportWriterTest).
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "FakeReportRun.h"
#include "ReportDocumentBuilder.h"
#include "TempDir.h"

namespace tidepool::report {
namespace {

using testing::BuildFrom;
using testing::FakeConfiguration;
using testing::TempDir;
using testing::WhitepaperConfigurations;
using testing::WriteFakeRun;

// One (empty) file and data: URI per panel, as BuildReportDocument expects.
doc::Document Build(const ReportModel& model) {
    const std::size_t panels = model.panels.size() + model.reflection_panels.size();
    return BuildReportDocument(model, std::vector<PanelFiles>(panels),
                               std::vector<std::array<std::string, 3>>(panels));
}

// The style of the lead's block `i`, or nullopt when that block is not a paragraph.
std::optional<doc::ParagraphStyle> LeadStyle(const doc::Document& document, std::size_t i) {
    const auto* paragraph = std::get_if<doc::Paragraph>(&document.lead.at(i));
    return paragraph != nullptr ? std::optional(paragraph->style) : std::nullopt;
}

TEST(ReportDocumentBuilderTest, SectionsComeInTheReportsOrderWithTheirAnchors) {
    const TempDir dir;
    std::optional<ReportInputs> inputs;
    const ReportModel model = BuildFrom(WriteFakeRun(dir, WhitepaperConfigurations()), &inputs);
    const doc::Document document = Build(model);
    std::vector<std::string> titles;
    for (const doc::Section& section : document.sections) {
        titles.push_back(section.title.substr(0, section.title.find(' ')));
        EXPECT_FALSE(section.id.empty()) << section.title;
    }
    EXPECT_EQ(titles,
              (std::vector<std::string>{"1.", "2.", "3.", "4.", "5.", "6.", "7.", "8.", "9."}));
    EXPECT_EQ(document.sections[4].id, "images");
    EXPECT_EQ(document.sections[6].id, "stability");
    EXPECT_EQ(document.sections[7].id, "scenes");
    EXPECT_EQ(document.title, "tidepool report: " + model.options.name);
}

TEST(ReportDocumentBuilderTest, FailedConfigurationsAreWarnedOfBeforeTheSummary) {
    const TempDir dir;
    std::optional<ReportInputs> inputs;
    const ReportModel good = BuildFrom(WriteFakeRun(dir, WhitepaperConfigurations()), &inputs);
    const doc::Document plain = Build(good);
    ASSERT_EQ(plain.lead.size(), 1U);
    EXPECT_EQ(LeadStyle(plain, 0), doc::ParagraphStyle::kLead);

    const TempDir failed_dir;
    std::vector<FakeConfiguration> configurations = WhitepaperConfigurations();
    configurations[2].ok = false;
    std::optional<ReportInputs> failed_inputs;
    const ReportModel failed = BuildFrom(WriteFakeRun(failed_dir, configurations), &failed_inputs);
    const doc::Document warned = Build(failed);
    ASSERT_EQ(warned.lead.size(), 2U);
    EXPECT_EQ(LeadStyle(warned, 0), doc::ParagraphStyle::kWarning);
    const auto& warning = std::get<doc::Paragraph>(warned.lead[0]);
    ASSERT_FALSE(warning.spans.empty());
    EXPECT_EQ(warning.spans[0].text, "1 configuration(s) FAILED");
    EXPECT_EQ(LeadStyle(warned, 1), doc::ParagraphStyle::kLead);
}

TEST(ReportDocumentBuilderTest, ReflectionPanelsFollowTheImagesSectionsPanels) {
    ReportModel model;
    EXPECT_EQ(ReflectionPanelOffset(model), 0U);
    model.panels.resize(3);
    model.reflection_panels.resize(2);
    EXPECT_EQ(ReflectionPanelOffset(model), 3U);
}

}  // namespace
}  // namespace tidepool::report
