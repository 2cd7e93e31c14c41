#include "bcot/capture/calibration_options.h"

#include <gtest/gtest.h>

#include "bcot/core/yaml_util.h"
#include "test_util.h"

namespace bcot {
namespace {

TEST(CalibrationOptionsTest, UnknownKeyNamesFileLineAndKey) {
  test::TempDir dir;
  const std::string path = dir.File("calibrate.yaml");
  test::WriteText(path, "input:\n  images_dir: imgs\nboard:\n  square_mm: 20\n");
  const StatusOr<CalibrationOptions> options = ReadCalibrationOptions(path);
  ASSERT_FALSE(options.ok());
  test::ExpectErrorNaming(options.status(), StatusCode::kInvalidConfig,
                          {"calibrate.yaml:4", "board.square_mm"});
}

TEST(CalibrationOptionsTest, ImagesDirIsResolvedAgainstTheConfigFolder) {
  test::TempDir dir;
  const std::string path = dir.File("sub/calibrate.yaml");
  test::WriteText(path, "input:\n  images_dir: imgs\n");
  const StatusOr<CalibrationOptions> options = ReadCalibrationOptions(path);
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->input.images_dir, dir.File("sub/imgs"));
}

TEST(CalibrationOptionsTest, ValidateListsEveryViolation) {
  CalibrationOptions options;
  options.board.inner_corners_x = 1;
  options.board.square_size_mm = 0.0;
  options.input.cameras = {"left", "left", "a/b"};
  test::ExpectErrorNaming(
      options.Validate(), StatusCode::kInvalidConfig,
      {"board.inner_corners_x = 1", "board.square_size_mm = 0", "input.images_dir",
       "input.cameras[1] = 'left', must not be listed twice",
       "input.cameras[2] = 'a/b', must be usable as a folder name"});
}

TEST(CalibrationOptionsTest, FormattedOptionsReadBackTheSame) {
  StatusOr<CalibrationOptions> options = ReadCalibrationOptions(
      test::SourcePath("configs/calibrate.yaml"),
      {"input.images_dir=/data/boards", "board.square_size_mm=30", "outliers.drop=true"});
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->board.square_size_mm, 30.0);
  const std::string text = FormatCalibrationOptions(*options);
  StatusOr<YAML::Node> node = ParseYaml(text, "formatted");
  ASSERT_TRUE(node.ok());
  StatusOr<CalibrationOptions> again = ParseCalibrationOptions(*node, "formatted", "");
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(FormatCalibrationOptions(*again), text);
}

}  // namespace
}  // namespace bcot
