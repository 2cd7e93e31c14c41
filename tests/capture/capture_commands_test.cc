// `bcot calibrate` and `bcot capture` end to end: exit codes and one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "bcot/capture/aravis_frame_source.h"
#include "bcot/core/rig_io.h"
#include "capture_test_util.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

std::string Bcot(const std::string& arguments) { return test::BcotBinary() + " " + arguments; }

TEST(CalibrateCommandTest, HelpListsTheOptions) {
  std::string output;
  EXPECT_EQ(test::RunCommand(Bcot("calibrate --help"), &output), 0);
  for (const char* flag : {"--config", "--set", "--images-dir", "--out"}) {
    EXPECT_THAT(output, HasSubstr(flag));
  }
}

TEST(CalibrateCommandTest, ConfigErrorsExitTwoWithOneLine) {
  test::TempDir dir;
  std::string output;
  // No images folder at all.
  EXPECT_EQ(
      test::RunCommand(Bcot("calibrate --config " + test::SourcePath("configs/calibrate.yaml") +
                            " --out " + dir.File("out")),
                       &output),
      2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("input.images_dir"));
  // An unknown key in an override.
  EXPECT_EQ(test::RunCommand(Bcot("calibrate --images-dir " + dir.path() + " --out " +
                                  dir.File("out") + " --set board.squares=3"),
                             &output),
            2);
  EXPECT_THAT(output, HasSubstr("squares"));
  EXPECT_FALSE(std::filesystem::exists(dir.File("out")));
}

TEST(CalibrateCommandTest, DataErrorsExitOneNamingTheFile) {
  test::TempDir dir;
  test::WriteText(dir.File("imgs/left01.png"), "garbage");
  test::WriteText(dir.File("imgs/right01.png"), "garbage");
  std::string output;
  EXPECT_EQ(test::RunCommand(Bcot("calibrate --quiet --images-dir " + dir.File("imgs") + " --out " +
                                  dir.File("out")),
                             &output),
            1);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("left01.png"));
}

// The README's example: the bundled sample, then a second run that must not replace the
// calibration silently.
TEST(CalibrateCommandTest, CalibratesTheStereoSample) {
  const std::string images = test::SourcePath("data/stereo_chessboard");
  test::TempDir dir;
  const std::string command =
      Bcot("calibrate --config " + test::SourcePath("configs/calibrate.yaml") + " --images-dir " +
           images + " --out " + dir.File("out"));
  std::string output;
  ASSERT_EQ(test::RunCommand(command, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("stereo RMS"));
  const StatusOr<Rig> rig = ReadRigYaml(dir.File("out/rig.yaml"));
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  EXPECT_EQ(rig->size(), 2);
  EXPECT_TRUE(std::filesystem::exists(dir.File("out/calibration_report.csv")));
  EXPECT_TRUE(std::filesystem::exists(dir.File("out/calibrate.resolved.yaml")));
  EXPECT_EQ(test::RunCommand(command, &output), 2) << output;
  EXPECT_THAT(output, HasSubstr("--overwrite"));
  EXPECT_EQ(test::RunCommand(command + " --overwrite --quiet", &output), 0) << output;
}

TEST(CaptureCommandTest, WithoutAravisTheMessageSaysSo) {
  if (AravisAvailable()) GTEST_SKIP() << "bcot built with Aravis";
  std::string output;
  EXPECT_EQ(test::RunCommand(Bcot("capture --out /tmp/never"), &output), 1);
  EXPECT_THAT(output, HasSubstr("built without Aravis"));
}

TEST(CaptureCommandTest, AnUnknownDeviceExitsOneNamingIt) {
  if (!AravisAvailable()) GTEST_SKIP() << "bcot built without Aravis";
  test::TempDir dir;
  std::string output;
  EXPECT_EQ(
      test::RunCommand(
          Bcot("capture --quiet --config " + test::SourcePath("configs/capture.yaml") + " --out " +
               dir.File("seq") + " --set 'cameras=[{name: c0, device_id: Missing-Cam-7}]'"),
          &output),
      1);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("Missing-Cam-7"));
  EXPECT_FALSE(std::filesystem::exists(dir.File("seq")));
}

TEST(CaptureCommandTest, BadConfigExitsTwo) {
  test::TempDir dir;
  const std::string config = dir.File("capture.yaml");
  test::WriteText(config, "cameras:\n  - name: c0\n    device_id: Fake_1\nrecording:\n  skew: 3\n");
  std::string output;
  const int code =
      test::RunCommand(Bcot("capture --config " + config + " --out " + dir.File("seq")), &output);
  if (!AravisAvailable()) {
    EXPECT_EQ(code, 1);  // the missing camera stack is reported first
    return;
  }
  EXPECT_EQ(code, 2);
  EXPECT_THAT(output, HasSubstr("capture.yaml:5"));
  EXPECT_THAT(output, HasSubstr("recording.skew"));
}

TEST(CaptureCommandTest, RecordsTheFakeCameraWithARig) {
  if (!AravisAvailable()) GTEST_SKIP() << "bcot built without Aravis";
  test::TempDir dir;
  Rig rig;
  RigCamera camera;
  camera.camera = Camera("cam0", 512, 512, 500.0, 500.0, 255.5, 255.5);
  rig.Add(camera);
  ASSERT_TRUE(WriteRigYaml(dir.File("rig.yaml"), rig).ok());
  std::string output;
  ASSERT_EQ(test::RunCommand(
                Bcot("capture --config " + test::SourcePath("configs/capture.yaml") +
                     " --frames 4 --rig " + dir.File("rig.yaml") + " --out " + dir.File("seq")),
                &output),
            0)
      << output;
  EXPECT_THAT(output, HasSubstr("frame sets"));
  test::ExpectValidRecording(dir.File("seq"), {"cam0"}, 4);
  EXPECT_TRUE(ReadRigYaml(dir.File("seq/rig.yaml")).ok());
  EXPECT_TRUE(std::filesystem::exists(dir.File("seq/capture.resolved.yaml")));
}

}  // namespace
}  // namespace bcot
