#include "bcot/annotate/annotate_options.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

StatusOr<AnnotateOptions> ParseText(const std::string& text) {
  return ParseAnnotateOptions(YAML::Load(text), "run.yaml");
}

TEST(AnnotateOptionsTest, DefaultsRoundTripThroughYaml) {
  AnnotateOptions options;
  options.tracker.frame.rounds = 3;
  options.tracker.frame.cost.form = RegionResidualForm::kIrls;
  options.tracker.frame.energy = RegionEnergy::kCombined;
  options.tracker.frame.lines.num_lines = 150;
  options.tracker.frame.lines.weight = 0.5;
  options.tracker.color.kind = ColorModelKind::kLocal;
  options.tracker.color.refine_kind = ColorModelKind::kGlobal;
  options.views.cameras = {"left", "no"};
  options.views.weights = {1.0, 0.25};
  const std::string text = FormatAnnotateOptions(options);
  const StatusOr<AnnotateOptions> read = ParseText(text);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(FormatAnnotateOptions(*read), text);
  EXPECT_EQ(read->tracker.frame.rounds, 3);
  EXPECT_EQ(read->tracker.frame.cost.form, RegionResidualForm::kIrls);
  EXPECT_EQ(read->tracker.frame.energy, RegionEnergy::kCombined);
  EXPECT_EQ(read->tracker.frame.lines.num_lines, 150);
  EXPECT_EQ(read->tracker.frame.lines.weight, 0.5);
  EXPECT_EQ(read->tracker.color.refine_kind, ColorModelKind::kGlobal);
  EXPECT_EQ(read->views.cameras[1], "no");  // a string, not the YAML 1.1 boolean
  EXPECT_EQ(FormatAnnotateOptions(AnnotateOptions()),
            FormatAnnotateOptions(*ParseText(FormatAnnotateOptions(AnnotateOptions()))));
}

TEST(AnnotateOptionsTest, EveryShippedConfigLoads) {
  int loaded = 0;
  for (const char* name : {"configs/annotate.yaml", "configs/track.yaml"}) {
    const StatusOr<AnnotateOptions> options = ReadAnnotateOptions(test::SourcePath(name), {});
    ASSERT_TRUE(options.ok()) << name << ": " << options.status().message();
    ++loaded;
  }
  EXPECT_EQ(loaded, 2);
  // annotate.yaml spells out the defaults.
  EXPECT_EQ(
      FormatAnnotateOptions(*ReadAnnotateOptions(test::SourcePath("configs/annotate.yaml"), {})),
      FormatAnnotateOptions(AnnotateOptions()));
  EXPECT_EQ(ReadAnnotateOptions(test::SourcePath("configs/track.yaml"), {})->tracker.frame.rounds,
            1);
}

// Every YAML file under configs/ loads with the reader of its command. capture.yaml and
// calibrate.yaml belong to the capture target and are loaded by tests/capture; a new config
// file must be added here.
TEST(AnnotateOptionsTest, QualitySectionRoundTripsAndIsValidated) {
  AnnotateOptions options;
  options.quality.threshold_px = 1.25;
  options.quality.statistic = QualityStatistic::kMedian;
  options.quality.allowed_bad_fraction = 0.05;
  const std::string text = FormatAnnotateOptions(options);
  EXPECT_THAT(text, HasSubstr("quality:\n  threshold_px: 1.25\n"));
  const StatusOr<AnnotateOptions> read = ParseText(text);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(FormatAnnotateOptions(*read), text);
  EXPECT_EQ(read->quality.statistic, QualityStatistic::kMedian);

  const StatusOr<AnnotateOptions> range =
      ParseText("frame:\n  rounds: 2\nquality:\n  statistic: p90\n  allowed_bad_fraction: 2\n");
  ASSERT_EQ(range.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(range.status().message(),
              HasSubstr("run.yaml:5: quality.allowed_bad_fraction = 2, must be in [0, 1]"));
  const StatusOr<AnnotateOptions> unknown = ParseText("quality:\n  treshold_px: 1\n");
  EXPECT_THAT(unknown.status().message(), HasSubstr("run.yaml:2"));
  EXPECT_THAT(unknown.status().message(), HasSubstr("treshold_px"));
  // --set overrides: same checks, named by `--set key` (not by the config file).
  const StatusOr<AnnotateOptions> set = ReadAnnotateOptions(
      test::SourcePath("configs/annotate.yaml"), {"quality.search_radius_px=0"});
  ASSERT_EQ(set.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(set.status().message(), HasSubstr("--set quality.search_radius_px = 0, must be > 0"));
  const StatusOr<AnnotateOptions> set_type =
      ReadAnnotateOptions(test::SourcePath("configs/track.yaml"), {"frame.rounds=abc"});
  EXPECT_EQ(set_type.status().message(), "--set frame.rounds: expected an integer, got 'abc'");
  const StatusOr<AnnotateOptions> type = ReadAnnotateOptions("", {"quality.threshold_px=[1, 2]"});
  ASSERT_EQ(type.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(type.status().message(), HasSubstr("quality.threshold_px"));
  const StatusOr<AnnotateOptions> key = ReadAnnotateOptions("", {"quality.nope=1"});
  EXPECT_THAT(key.status().message(), HasSubstr("nope"));
  const StatusOr<AnnotateOptions> good = ReadAnnotateOptions("", {"quality.threshold_px=3"});
  ASSERT_TRUE(good.ok()) << good.status().message();
  EXPECT_EQ(good->quality.threshold_px, 3.0);
}

TEST(AnnotateOptionsTest, UnknownKeyNamesFileLineAndKey) {
  const StatusOr<AnnotateOptions> options = ParseText("frame:\n  rounds: 2\n  roundz: 3\n");
  test::ExpectErrorNaming(options.status(), StatusCode::kInvalidConfig, {"run.yaml:3", "roundz"});
  const StatusOr<AnnotateOptions> section = ParseText("solver:\n  rounds: 2\n");
  ASSERT_EQ(section.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(section.status().message(), HasSubstr("solver"));
  // Every section is known, not only those present in the file (track.yaml has four).
  const StatusOr<AnnotateOptions> typo =
      ReadAnnotateOptions(test::SourcePath("configs/track.yaml"), {"windoww.size=3"});
  EXPECT_THAT(
      typo.status().message(),
      HasSubstr("--set windoww: unknown key (did you mean 'window'?); known keys: color, "
                "cost, edge, frame, lines, quality, region, symmetry, tracker, views, window"));
}

TEST(AnnotateOptionsTest, OutOfRangeValuesNameTheirLineAndKey) {
  const StatusOr<AnnotateOptions> options =
      ParseText("frame:\n  iterations: 4\n  rounds: 0\nregion:\n  band_px: -3\n");
  ASSERT_EQ(options.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(options.status().message(), HasSubstr("run.yaml:3: frame.rounds = 0, must be >= 1"));
  const StatusOr<AnnotateOptions> region = ParseText("region:\n  stride_px: 2\n  band_px: -3\n");
  EXPECT_THAT(region.status().message(), HasSubstr("run.yaml:3: region.band_px = -3"));
  const StatusOr<AnnotateOptions> color =
      ParseText("color:\n  kind: local\n  sample_margin_px: -1\n");
  EXPECT_THAT(color.status().message(), HasSubstr("run.yaml:3: color.sample_margin_px = -1"));
}

// The blurred-step fit needs 8 samples in its window: edge.step_px and edge.fit_half_px are
// checked together.
TEST(AnnotateOptionsTest, EdgeSamplingMustLeaveTheFitEnoughSamples) {
  const StatusOr<AnnotateOptions> coarse = ReadAnnotateOptions("", {"edge.step_px=0.5"});
  ASSERT_TRUE(coarse.ok()) << coarse.status().message();
  EXPECT_EQ(coarse->tracker.frame.edge.lines.step_px, 0.5);
  const StatusOr<AnnotateOptions> too_coarse = ReadAnnotateOptions("", {"edge.step_px=1"});
  ASSERT_EQ(too_coarse.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(too_coarse.status().message(),
              HasSubstr("edge.fit_half_px = 2.5 (default), must be in [3.5 × edge.step_px"));
  EXPECT_THAT(ReadAnnotateOptions("", {"edge.step_px=0"}).status().message(),
              HasSubstr("--set edge.step_px = 0, must be > 0"));
}

// The cameras' response: estimated (the annotation default), sRGB, a power law or a table.
TEST(AnnotateOptionsTest, ImageResponseParsesAndNamesBadValues) {
  EXPECT_EQ(AnnotateOptions().tracker.frame.edge.lines.response, ImageResponse::Auto());
  const StatusOr<AnnotateOptions> linear = ParseText("edge:\n  response: gamma\n  gamma: 1\n");
  ASSERT_TRUE(linear.ok()) << linear.status().message();
  EXPECT_EQ(linear->tracker.frame.edge.lines.response, ImageResponse::Gamma(1.0));
  const StatusOr<AnnotateOptions> automatic = ReadAnnotateOptions("", {"edge.response=auto"});
  ASSERT_TRUE(automatic.ok()) << automatic.status().message();
  EXPECT_EQ(automatic->tracker.frame.edge.lines.response.kind, ImageResponse::Kind::kAuto);
  EXPECT_THAT(ParseText("edge:\n  response: linear\n").status().message(),
              HasSubstr("'linear' is not one of srgb | gamma | log | table | auto"));
  const StatusOr<AnnotateOptions> log = ParseText("edge:\n  response: log\n  log_stops: 12\n");
  ASSERT_TRUE(log.ok()) << log.status().message();
  EXPECT_EQ(log->tracker.frame.edge.lines.response, ImageResponse::Log(12.0));
  EXPECT_THAT(ParseText("edge:\n  response: log\n  log_stops: 2\n").status().message(),
              HasSubstr("run.yaml:3: edge.log_stops = 2"));
  EXPECT_THAT(ParseText("edge:\n  response: gamma\n  gamma: 0.1\n").status().message(),
              HasSubstr("run.yaml:3: edge.gamma = 0.1"));

  const test::TempDir dir;
  std::string values;
  for (int code = 0; code < 256; ++code) values += std::to_string(code * code) + "\n";
  test::WriteText(dir.File("response.txt"), "# a squared response\n" + values);
  test::WriteText(dir.File("run.yaml"),
                  "edge:\n  response: table\n  response_file: response.txt\n");
  const StatusOr<AnnotateOptions> table = ReadAnnotateOptions(dir.File("run.yaml"), {});
  ASSERT_TRUE(table.ok()) << table.status().message();
  const ImageResponse& response = table->tracker.frame.edge.lines.response;
  EXPECT_EQ(response.kind, ImageResponse::Kind::kTable);
  EXPECT_EQ(response.table_file, dir.File("response.txt"));  // relative to the config file
  EXPECT_NEAR(LinearTable(response)[128], LinearTable(ImageResponse::Gamma(2.0))[128], 1e-6);
  EXPECT_THAT(ReadAnnotateOptions("", {"edge.response=table"}).status().message(),
              HasSubstr("--set edge.response = table, table needs edge.response_file"));
  test::WriteText(dir.File("short.txt"), "0 1\n2 x\n");
  EXPECT_THAT(ReadAnnotateOptions(
                  "", {"edge.response=table", "edge.response_file=" + dir.File("short.txt")})
                  .status()
                  .message(),
              AllOf(HasSubstr("--set edge.response_file"), HasSubstr("short.txt:2: 'x'")));
}

// How the frames store chroma: read from their headers unless set.
TEST(AnnotateOptionsTest, ChromaSamplingParsesAndNamesBadValues) {
  EXPECT_EQ(AnnotateOptions().chroma_sampling, ChromaSamplingSetting::kAuto);
  const StatusOr<AnnotateOptions> set = ReadAnnotateOptions("", {"edge.chroma_sampling=4:2:0"});
  ASSERT_TRUE(set.ok()) << set.status().message();
  EXPECT_EQ(set->chroma_sampling, ChromaSamplingSetting::kJpeg420);
  EXPECT_THAT(ParseText("edge:\n  chroma_sampling: 4:1:1\n").status().message(),
              HasSubstr("'4:1:1' is not one of auto | 4:4:4 | 4:2:0 | 4:2:2"));
}

TEST(AnnotateOptionsTest, WrongTypesAndEnumsAreErrors) {
  EXPECT_THAT(ParseText("frame:\n  rounds: many\n").status().message(), HasSubstr("rounds"));
  const StatusOr<AnnotateOptions> form = ParseText("cost:\n  form: squared\n");
  ASSERT_EQ(form.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(form.status().message(), HasSubstr("'squared' is not one of sqrt_energy | irls"));
  EXPECT_THAT(ParseText("cost:\n  energy: sparser\n").status().message(),
              HasSubstr("'sparser' is not one of dense | sparse | combined"));
  EXPECT_THAT(ParseText("color:\n  refine_kind: finer\n").status().message(),
              HasSubstr("'finer' is not one of same | global | local"));
  const StatusOr<AnnotateOptions> same = ParseText("color:\n  refine_kind: same\n");
  ASSERT_TRUE(same.ok()) << same.status().message();
  EXPECT_FALSE(same->tracker.color.refine_kind.has_value());
  EXPECT_THAT(ParseText("lines:\n  num_lines: 10\n  slope_px: 0\n").status().message(),
              HasSubstr("run.yaml:3: lines.slope_px = 0"));
  EXPECT_THAT(ParseText("cost:\n  energy: sparse\nlines:\n  weight: 0\n").status().message(),
              HasSubstr("lines.weight = 0, must be > 0 when the sparse energy is used"));
  EXPECT_THAT(ParseText("views:\n  cameras: [a, b]\n  weights: [1]\n").status().message(),
              HasSubstr("weights has 1 entries for 2 cameras"));
  EXPECT_THAT(ParseText("views:\n  weights: [0, 0]\n").status().message(),
              HasSubstr("run.yaml:2: views.weights"));
  EXPECT_THAT(ParseText("views:\n  weights: [0, 0]\n").status().message(),
              HasSubstr("at least one weight > 0"));
  EXPECT_THAT(ParseText("region:\n  contour_sample_spacing_px: 1e-9\n").status().message(),
              HasSubstr("run.yaml:2: region.contour_sample_spacing_px = 1e-09"));
}

TEST(AnnotateOptionsTest, WindowSectionParsesAndNamesBadValues) {
  const StatusOr<AnnotateOptions> options = ParseText(
      "window:\n  enabled: true\n  prior: se3\n  size: 12\n  overlap: 4\n  rotation_sigma_deg: "
      "[0.1, 0.2, "
      "0.3]\n  translation_sigma_mm: [1, 2, 3]\n  robust_translation_mm: 0\n  "
      "robust_rotation_deg: 0.7\n  translation_model: velocity\n  rotation_model: "
      "acceleration\n");
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_TRUE(options->window.enabled);
  EXPECT_EQ(options->window.size, 12);
  EXPECT_EQ(options->window.prior, MotionPriorForm::kSe3);
  EXPECT_EQ(options->window.overlap, 4);
  EXPECT_DOUBLE_EQ(options->window.rotation_sigma_deg[2], 0.3);
  EXPECT_DOUBLE_EQ(options->window.translation_sigma_mm[1], 2.0);
  EXPECT_DOUBLE_EQ(options->window.robust_translation_mm, 0.0);
  EXPECT_DOUBLE_EQ(options->window.robust_rotation_deg, 0.7);
  EXPECT_EQ(options->window.translation_model, MotionModel::kConstantVelocity);
  EXPECT_EQ(options->window.rotation_model, MotionModel::kConstantAcceleration);
  // Round trip of a non-default window section.
  EXPECT_EQ(FormatAnnotateOptions(*ParseText(FormatAnnotateOptions(*options))),
            FormatAnnotateOptions(*options));
  EXPECT_THAT(ParseText("window:\n  size: 8\n  overlap: 8\n").status().message(),
              HasSubstr("run.yaml:3: window.overlap = 8"));
  EXPECT_THAT(
      ParseText("window:\n  size: 8\n  translation_sigma_mm: [1, 0, 1]\n").status().message(),
      HasSubstr("run.yaml:3: window.translation_sigma_mm = 0 (y)"));
  EXPECT_THAT(ParseText("window:\n  rotation_sigma_deg: [1, 2]\n").status().message(),
              HasSubstr("run.yaml:2: window.rotation_sigma_deg: has 2 values, expected 3"));
  for (const auto& [text, message] :
       {std::pair{"window:\n  robust_translation_mm: -1\n", "window.robust_translation_mm = -1"},
        std::pair{"window:\n  translation_model: jerk\n",
                  "'jerk' is not one of velocity | acceleration"},
        std::pair{"window:\n  robust_scale: 2\n", "robust_scale"}}) {
    EXPECT_THAT(ParseText(text).status().message(), HasSubstr(message)) << text;
  }
  EXPECT_THAT(ParseText("window:\n  enabled: maybe\n").status().message(), HasSubstr("enabled"));
}

TEST(AnnotateOptionsTest, OverridesAreValidatedTheSameWay) {
  const StatusOr<AnnotateOptions> options =
      ReadAnnotateOptions(test::SourcePath("configs/annotate.yaml"),
                          {"frame.rounds=2", "color.kind=local", "cost.energy=sparse"});
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->tracker.frame.rounds, 2);
  EXPECT_EQ(options->tracker.frame.energy, RegionEnergy::kSparse);
  EXPECT_EQ(options->tracker.color.kind, ColorModelKind::kLocal);
  const StatusOr<AnnotateOptions> bad = ReadAnnotateOptions("", {"frame.rounds=-1"});
  ASSERT_EQ(bad.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(bad.status().message(), HasSubstr("frame.rounds = -1"));
  EXPECT_EQ(ReadAnnotateOptions("/nonexistent/run.yaml", {}).status().code(),
            StatusCode::kInvalidConfig);
}

}  // namespace
}  // namespace bcot
