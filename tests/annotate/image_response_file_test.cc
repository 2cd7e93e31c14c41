#include "bcot/annotate/image_response_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "bcot/annotate/annotator.h"
#include "bcot/annotate/regenerate_report.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

const ImageResponse kLinear = ImageResponse::Gamma(1.0);

TEST(ImageResponseFileTest, RoundTripsEveryField) {
  const test::TempDir dir;
  ImageResponseRecord record;
  record.response = ImageResponse::Gamma(1.4);
  record.estimated = true;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  record.scores = {{ImageResponse(), 0.2034, 0.0312, 0.61, 0.025, 700},
                   {ImageResponse::Log(8.0), -0.0125, 0.0453, 0.5525, 0.0231, 690},
                   {kLinear, nan, nan, nan, nan, 3}};
  ASSERT_TRUE(WriteImageResponseFile(dir.path(), record).ok());
  const StatusOr<ImageResponseRecord> read = ReadImageResponseFile(dir.path());
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->response, record.response);
  EXPECT_TRUE(read->estimated);
  EXPECT_TRUE(read->estimate_error.empty());
  ASSERT_EQ(read->scores.size(), 3u);
  EXPECT_EQ(read->scores[0].response, ImageResponse());
  EXPECT_DOUBLE_EQ(read->scores[0].slope_px, 0.2034);
  EXPECT_DOUBLE_EQ(read->scores[0].slope_standard_error_px, 0.0312);
  EXPECT_EQ(read->scores[0].lines, 700);
  EXPECT_EQ(read->scores[1].response, ImageResponse::Log(8.0));
  EXPECT_DOUBLE_EQ(read->scores[1].slope_px, -0.0125);
  EXPECT_DOUBLE_EQ(read->scores[1].spread_px, 0.5525);
  EXPECT_DOUBLE_EQ(read->scores[1].spread_standard_error_px, 0.0231);
  EXPECT_EQ(read->scores[1].lines, 690);
  EXPECT_EQ(read->scores[2].response, kLinear);
  EXPECT_TRUE(std::isnan(read->scores[2].slope_px));
  EXPECT_TRUE(std::isnan(read->scores[2].slope_standard_error_px));
  EXPECT_TRUE(std::isnan(read->scores[2].spread_px));
  EXPECT_EQ(read->scores[2].lines, 3);

  record.response = ImageResponse::Log(12.0);
  ASSERT_TRUE(WriteImageResponseFile(dir.path(), record).ok());
  const StatusOr<ImageResponseRecord> read_log = ReadImageResponseFile(dir.path());
  ASSERT_TRUE(read_log.ok()) << read_log.status().message();
  EXPECT_EQ(read_log->response, ImageResponse::Log(12.0));

  ImageResponseRecord failed;
  failed.estimate_error = "no candidate response left 20 edge lines";
  ASSERT_TRUE(WriteImageResponseFile(dir.path(), failed).ok());
  const StatusOr<ImageResponseRecord> read_failed = ReadImageResponseFile(dir.path());
  ASSERT_TRUE(read_failed.ok()) << read_failed.status().message();
  EXPECT_EQ(read_failed->response, ImageResponse());
  EXPECT_FALSE(read_failed->estimated);
  EXPECT_EQ(read_failed->estimate_error, failed.estimate_error);
}

TEST(ImageResponseFileTest, BadFilesAreErrorsNamingTheFileAndField) {
  const test::TempDir dir;
  const std::string path = dir.File(kImageResponseFileName);
  const auto error_of = [&](const std::string& text) {
    test::WriteText(path, text);
    const StatusOr<ImageResponseRecord> read = ReadImageResponseFile(dir.path());
    EXPECT_FALSE(read.ok());
    return read.status().message();
  };
  EXPECT_THAT(
      error_of("response: linear\nestimated: false\n"),
      AllOf(HasSubstr(path), HasSubstr("response"), HasSubstr("srgb | gamma | table | log")));
  EXPECT_THAT(error_of("response: gamma\ngamma: 9\nestimated: true\n"),
              AllOf(HasSubstr(path + ":2"), HasSubstr("gamma"), HasSubstr("outside")));
  EXPECT_THAT(error_of("response: log\nlog_stops: 40\nestimated: true\n"),
              AllOf(HasSubstr(path + ":2"), HasSubstr("log_stops"), HasSubstr("outside")));
  EXPECT_THAT(error_of("response: srgb\n"), HasSubstr("estimated"));
  const std::string candidate = "response: srgb\nestimated: true\ncandidates:\n  - {response: ";
  const std::string scores =
      ", slope_px: 0.1, slope_standard_error_px: 0.01, spread_px: 0.5, "
      "spread_standard_error_px: 0.02, lines: 5}\n";
  EXPECT_THAT(error_of(candidate + "gamma x" + scores),
              AllOf(HasSubstr("candidates[0].response"), HasSubstr("'gamma x'")));
  EXPECT_THAT(error_of(candidate + "log 1" + scores),
              AllOf(HasSubstr("candidates[0].response"), HasSubstr("'log 1'")));
  EXPECT_THAT(error_of("response: srgb\nestimated: true\ncolour: red\n"), HasSubstr("colour"));
  // A configured response needs no file; auto needs one.
  const StatusOr<ImageResponseRecord> configured =
      RecordedImageResponse(dir.File("nowhere"), kLinear);
  ASSERT_TRUE(configured.ok());
  EXPECT_EQ(configured->response, kLinear);
  EXPECT_FALSE(configured->estimated);
  EXPECT_EQ(RecordedImageResponse(dir.File("nowhere"), ImageResponse::Auto()).status().code(),
            StatusCode::kNotFound);
}

// A linear camera annotated with edge.response auto: the estimate is written and used again
// when frames are re-annotated (--frames) and when the report is regenerated.
TEST(ImageResponseFileTest, AnAutomaticResponseIsRecordedAndReused) {
  const test::TempDir dir;
  const StatusOr<SynthOptions> synth = ReadSynthOptions(
      test::SourcePath("configs/synth/demo.yaml"),
      {"cameras.width=480", "cameras.height=384", "motion.num_frames=3", "sensor.gamma=1"});
  ASSERT_TRUE(synth.ok());
  ASSERT_TRUE(Synthesize(*synth, dir.File("seq")).ok());
  AnnotateOptions options;
  options.tracker.frame.edge.lines.response.kind = ImageResponse::Kind::kAuto;
  ASSERT_TRUE(AnnotateSequenceDir(dir.File("seq"), dir.File("ann"), options).ok());
  StatusOr<ImageResponseRecord> recorded = ReadImageResponseFile(dir.File("ann"));
  ASSERT_TRUE(recorded.ok()) << recorded.status().message();
  EXPECT_EQ(recorded->response, kLinear);
  EXPECT_TRUE(recorded->estimated);
  EXPECT_EQ(recorded->scores.size(), DefaultResponseCandidates().size());

  AnnotateInputs inputs;
  inputs.frames = "1:1";
  ASSERT_TRUE(AnnotateSequenceDir(dir.File("seq"), dir.File("ann"), options, inputs).ok());
  recorded = ReadImageResponseFile(dir.File("ann"));
  ASSERT_TRUE(recorded.ok()) << recorded.status().message();
  EXPECT_EQ(recorded->response, kLinear);
  EXPECT_TRUE(recorded->estimated);

  EXPECT_TRUE(RegenerateQualityReport(dir.File("ann"), "", "", {}).ok());
  std::filesystem::remove(dir.File("ann") + "/" + kImageResponseFileName);
  const StatusOr<QualityReport> missing = RegenerateQualityReport(dir.File("ann"), "", "", {});
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(missing.status().message(), HasSubstr(kImageResponseFileName));
}

}  // namespace
}  // namespace bcot
