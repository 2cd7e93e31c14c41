#include "bcot/review/review_annotation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "bcot/core/pose_io.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// quality.json of two views and three frames: frame 1 bad in view a, frame 2 bad in view b and
// not measurable in view a.
const char* kQuality = R"({
 "options": {"threshold_px": 2.5, "statistic": "p90"},
 "views": [{"name": "a"}, {"name": "b"}],
 "frames": [
  {"frame": 0, "views": [{"p90_px": 0.5, "bad": false, "verifiable": true},
                         {"p90_px": 0.7, "bad": false, "verifiable": true}]},
  {"frame": 1, "views": [{"p90_px": 3.5, "bad": true, "verifiable": true},
                         {"p90_px": 0.7, "bad": false, "verifiable": true}]},
  {"frame": 2, "views": [{"p90_px": null, "bad": false, "verifiable": false},
                         {"p90_px": 9.0, "bad": true, "verifiable": true}]}]})";

TEST(ParseQualityTimelineTest, ReadsTheJudgedStatisticPerViewAndFrame) {
  const StatusOr<QualityTimeline> timeline = ParseQualityTimeline(kQuality, "q.json", 3);
  ASSERT_TRUE(timeline.ok()) << timeline.status().message();
  EXPECT_EQ(timeline->threshold_px, 2.5);
  EXPECT_EQ(timeline->statistic, "p90");
  EXPECT_THAT(timeline->view_names, ElementsAre("a", "b"));
  EXPECT_EQ(timeline->error_px[0][1], 3.5);
  EXPECT_TRUE(std::isnan(timeline->error_px[0][2]));
  EXPECT_FALSE(timeline->verifiable[0][2]);
  EXPECT_EQ(timeline->error_px[1][2], 9.0);
  EXPECT_THAT(timeline->BadFrames(), ElementsAre(1, 2));
}

TEST(ParseQualityTimelineTest, RejectsOtherFilesWithTheirName) {
  for (const std::string text : {"", "{", "[]", "{\"options\": {}}",
                                 R"({"options": {"threshold_px": 1, "statistic": "mean"}})"}) {
    const StatusOr<QualityTimeline> timeline = ParseQualityTimeline(text, "q.json", 3);
    ASSERT_FALSE(timeline.ok()) << text;
    EXPECT_THAT(timeline.status().message(), HasSubstr("q.json")) << text;
  }
  const StatusOr<QualityTimeline> wrong_length = ParseQualityTimeline(kQuality, "q.json", 4);
  ASSERT_FALSE(wrong_length.ok());
  EXPECT_THAT(wrong_length.status().message(), HasSubstr("3 frames, the sequence has 4"));
}

TEST(ParseFrameDiagnosticsTest, ReadsOneRowPerFrame) {
  const StatusOr<FrameDiagnostics> diagnostics = ParseFrameDiagnostics(
      "frame,termination,rounds\n0,converged,3\n1,max_rounds,8\n", "frames.csv", 2);
  ASSERT_TRUE(diagnostics.ok()) << diagnostics.status().message();
  EXPECT_THAT(diagnostics->columns, ElementsAre("frame", "termination", "rounds"));
  EXPECT_THAT(diagnostics->rows[1], ElementsAre("1", "max_rounds", "8"));
}

TEST(ParseFrameDiagnosticsTest, RejectsMalformedTables) {
  for (const std::string csv : {"", "index,x\n0,1\n", "frame,x\n0,1\n", "frame,x\n0,1\n2,1\n",
                                "frame,x\n0,1\n1\n", "frame,x\n0,1\n1,2,3\n"}) {
    const StatusOr<FrameDiagnostics> diagnostics = ParseFrameDiagnostics(csv, "frames.csv", 2);
    ASSERT_FALSE(diagnostics.ok()) << csv;
    EXPECT_THAT(diagnostics.status().message(), HasSubstr("frames.csv")) << csv;
  }
}

TEST(LoadReviewAnnotationTest, NeedsOnePosePerFrame) {
  test::TempDir dir;
  ASSERT_TRUE(WritePoseFile(dir.File("rig_from_object.txt"),
                            {Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity()})
                  .ok());
  const StatusOr<ReviewAnnotation> two = LoadReviewAnnotation(dir.path(), 2);
  ASSERT_TRUE(two.ok()) << two.status().message();
  EXPECT_FALSE(two->quality.has_value());
  EXPECT_FALSE(two->diagnostics.has_value());
  const StatusOr<ReviewAnnotation> three = LoadReviewAnnotation(dir.path(), 3);
  ASSERT_FALSE(three.ok());
  EXPECT_THAT(three.status().message(), HasSubstr("2 poses, the sequence has 3 frames"));
  EXPECT_FALSE(LoadReviewAnnotation(dir.File("missing"), 2).ok());
}

}  // namespace
}  // namespace bcot
