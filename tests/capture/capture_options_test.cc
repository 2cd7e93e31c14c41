#include "bcot/capture/capture_options.h"

#include <gtest/gtest.h>

#include "bcot/core/yaml_util.h"
#include "test_util.h"

namespace bcot {
namespace {

TEST(CaptureOptionsTest, TheShippedConfigIsValid) {
  const StatusOr<CaptureOptions> options =
      ReadCaptureOptions(test::SourcePath("configs/capture.yaml"));
  ASSERT_TRUE(options.ok()) << options.status().message();
  ASSERT_EQ(options->cameras.size(), 1u);
  EXPECT_EQ(options->cameras[0].device_id, "Fake_1");
  EXPECT_EQ(options->trigger.mode, "software");
}

TEST(CaptureOptionsTest, UnknownCameraKeyNamesFileLineAndKey) {
  test::TempDir dir;
  const std::string path = dir.File("capture.yaml");
  test::WriteText(path, "cameras:\n  - name: c0\n    device_id: Fake_1\n    exposure: 100\n");
  const StatusOr<CaptureOptions> options = ReadCaptureOptions(path);
  ASSERT_FALSE(options.ok());
  test::ExpectErrorNaming(options.status(), StatusCode::kInvalidConfig,
                          {"capture.yaml:4", "cameras[0].exposure"});
}

TEST(CaptureOptionsTest, ValidateListsEveryViolation) {
  CaptureOptions options;
  options.trigger.mode = "sometimes";
  options.cameras.push_back({"c0", "Fake_1", "", -5.0, std::nullopt, std::nullopt, std::nullopt});
  options.cameras.push_back(
      {"c0", "", "", std::nullopt, std::nullopt, std::nullopt, std::array<int, 4>{0, 0, 0, 10}});
  options.recording.grab_timeout_ms = 0;
  test::ExpectErrorNaming(
      options.Validate(), StatusCode::kInvalidConfig,
      {"trigger.mode = 'sometimes'", "cameras[0].exposure_us = -5", "cameras[1].device_id",
       "cameras[1].region", "cameras[1] = 'c0'", "recording.grab_timeout_ms = 0"});
}

TEST(CaptureOptionsTest, OverridesApplyAndTheFormattedOptionsReadBack) {
  StatusOr<CaptureOptions> options = ReadCaptureOptions(
      test::SourcePath("configs/capture.yaml"), {"recording.max_frame_sets=7",
                                                 "cameras=[{name: x, device_id: Fake_1, gain: 2, "
                                                 "region: [0, 0, 64, 32]}]"});
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->recording.max_frame_sets, 7);
  ASSERT_TRUE(options->cameras[0].gain.has_value());
  EXPECT_EQ(*options->cameras[0].gain, 2.0);
  EXPECT_FALSE(options->cameras[0].exposure_us.has_value());

  const std::string text = FormatCaptureOptions(*options);
  StatusOr<YAML::Node> node = ParseYaml(text, "formatted");
  ASSERT_TRUE(node.ok());
  StatusOr<CaptureOptions> again = ParseCaptureOptions(*node, "formatted", "");
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(FormatCaptureOptions(*again), text);
}

}  // namespace
}  // namespace bcot
