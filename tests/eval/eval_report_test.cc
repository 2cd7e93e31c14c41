#include "bcot/eval/eval_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/status.h"
#include "benchmark_test_data.h"
#include "test_util.h"

namespace bcot {
namespace {

using test::MakeScoredFrame;
using ::testing::HasSubstr;

std::vector<SequenceResult> TwoSequences() {
  SequenceResult a{
      "indoor", "Cat", {MakeScoredFrame(1, 1, 1, 10), MakeScoredFrame(6, 1, 20, 20)}, 1};
  SequenceResult b{
      "outdoor, 1", "3D <Touch>", {MakeScoredFrame(1, 30, 4, 30), MakeScoredFrame(1, 1, 1, 40)}, 0};
  return {a, b};
}

TEST(EvalReportTest, MarkdownTableFollowsTable6ColumnOrder) {
  const EvalReport report = BuildEvalReport(TwoSequences(), "online");
  const std::string markdown = FormatReportMarkdown(report);
  EXPECT_THAT(markdown,
              HasSubstr("| All | ADD-0.02d | ADD-0.05d | ADD-0.1d | 5°5cm | 5° | 5cm | 2°2cm | 2° "
                        "| 2cm | Time(ms) | ADD AUC | Frames | Lost |"));
  // Pooled: 4 frames; ADD ≤ 2 mm: frames 0 and 3 → 50.0; 5°5cm: 3 of 4; time mean 25.0.
  EXPECT_THAT(markdown, HasSubstr("| all | 50.0 | 75.0 | 75.0 | 75.0 | 75.0 | 100.0 | 50.0 | 75.0 "
                                  "| 75.0 | 25.0 |"));
  EXPECT_THAT(markdown, HasSubstr("## Per scene"));
  EXPECT_THAT(markdown, HasSubstr("| indoor |"));
  EXPECT_THAT(markdown, HasSubstr("## Per object"));
  EXPECT_THAT(markdown, HasSubstr("| 3D <Touch> |"));
  EXPECT_THAT(markdown, HasSubstr("4 scored frames, 1 lost"));
}

TEST(EvalReportTest, CsvJsonAndSvg) {
  const EvalReport report = BuildEvalReport(TwoSequences(), "offline");
  const std::string csv = FormatReportCsv(report);
  const std::vector<std::string> lines = SplitLines(csv);
  ASSERT_EQ(lines.size(), 1u + 1u + 2u + 2u);  // header, all, 2 scenes, 2 objects
  EXPECT_EQ(lines[0],
            "kind,name,sequences,frames,lost,ADD-0.02d,ADD-0.05d,ADD-0.1d,5°5cm,5°,5cm,2°2cm,2°,"
            "2cm,Time(ms),ADD AUC");
  EXPECT_THAT(lines[1], ::testing::StartsWith("all,all,2,4,1,50,75,75,75,75,100,50,75,75,25,"));
  EXPECT_THAT(csv, HasSubstr("scene,\"outdoor, 1\",1,2,0,"));

  const nlohmann::json json = nlohmann::json::parse(FormatReportJson(report));
  EXPECT_EQ(json["mode"], "offline");
  EXPECT_EQ(json["all"]["frames"], 4);
  EXPECT_EQ(json["all"]["metrics"]["5cm"], 100.0);
  EXPECT_EQ(json["per_object"].size(), 2u);
  EXPECT_EQ(json["all"]["add_curve"]["threshold_d"].size(), 101u);

  const std::string svg = FormatSuccessCurveSvg(report);
  EXPECT_THAT(svg, ::testing::StartsWith("<svg xmlns=\"http://www.w3.org/2000/svg\""));
  EXPECT_THAT(svg, HasSubstr("3D &lt;Touch&gt;"));
  size_t polylines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos;
       at = svg.find("<polyline", at + 1)) {
    ++polylines;
  }
  EXPECT_EQ(polylines, 3u);  // pooled + one per object
  EXPECT_THAT(svg, HasSubstr("</svg>"));

  test::TempDir dir;
  ASSERT_TRUE(WriteEvalReport(report, dir.File("out")).ok());
  for (const char* name : {"eval.md", "eval.csv", "eval.json", "add_curve.svg"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.File(std::string("out/") + name))) << name;
  }
}

TEST(EvalReportTest, UnknownTimesAreDashesNullsAndEmptyCells) {
  std::vector<SequenceResult> results = TwoSequences();
  for (SequenceResult& r : results) {
    for (ScoredFrame& f : r.frames) f.time_ms = std::numeric_limits<double>::quiet_NaN();
  }
  const EvalReport report = BuildEvalReport(results, "offline");
  EXPECT_THAT(FormatReportMarkdown(report), HasSubstr("| 75.0 | – |"));
  EXPECT_TRUE(
      nlohmann::json::parse(FormatReportJson(report))["all"]["metrics"]["Time(ms)"].is_null());
  EXPECT_THAT(SplitLines(FormatReportCsv(report))[1], HasSubstr(",75,,"));
}

}  // namespace
}  // namespace bcot
