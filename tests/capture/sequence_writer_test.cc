#include "bcot/capture/sequence_writer.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <filesystem>

#include "bcot/core/rig_io.h"
#include "capture_test_util.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

std::vector<Frame> FrameSet(int index, int width = 32, int height = 24) {
  return {test::ScriptedFrame(0, index, 1000 * index, width, height).frame,
          test::ScriptedFrame(1, index, 1000 * index + 7, width, height).frame};
}

std::string WriteRig(const test::TempDir& dir, const std::vector<std::string>& names, int width,
                     int height) {
  Rig rig;
  for (const std::string& name : names) {
    RigCamera camera;
    camera.camera = Camera(name, width, height, 100.0, 100.0, width / 2.0, height / 2.0);
    rig.Add(camera);
  }
  const std::string path = dir.File("rig.yaml");
  EXPECT_TRUE(WriteRigYaml(path, rig).ok());
  return path;
}

TEST(SequenceWriterTest, WritesFramesTimestampsAndRig) {
  test::TempDir dir;
  const std::string rig = WriteRig(dir, {"a", "b"}, 32, 24);
  const std::string out = dir.File("seq");
  auto writer = SequenceWriter::Create(out, {"a", "b"}, rig, 1);
  ASSERT_TRUE(writer.ok()) << writer.status().message();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE((*writer)->Append(FrameSet(i)).ok());
  EXPECT_EQ((*writer)->num_frames(), 3);
  test::ExpectValidRecording(out, {"a", "b"}, 3);
  const auto rows = test::ReadCsvRows(out + "/timestamps.csv");
  EXPECT_EQ(rows[2][1], "2000");
  EXPECT_EQ(rows[2][2], "2007");
  // Pixels survive losslessly; the rig is copied.
  const cv::Mat image = cv::imread(out + "/b/000002.png", cv::IMREAD_UNCHANGED);
  EXPECT_EQ(image.at<uchar>(0, 0), 102);
  EXPECT_TRUE(ReadRigYaml(out + "/rig.yaml").ok());
  // No temporary files remain.
  for (const auto& entry : std::filesystem::recursive_directory_iterator(out)) {
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
  }
}

TEST(SequenceWriterTest, RejectsANonEmptyOutputAndARigWithOtherCameras) {
  test::TempDir dir;
  test::WriteText(dir.File("full/file.txt"), "x");
  auto full = SequenceWriter::Create(dir.File("full"), {"a"}, "", 1);
  ASSERT_FALSE(full.ok());
  EXPECT_EQ(full.status().code(), StatusCode::kInvalidConfig);

  const std::string rig = WriteRig(dir, {"b", "a"}, 32, 24);
  auto mismatch = SequenceWriter::Create(dir.File("seq"), {"a", "b"}, rig, 1);
  ASSERT_FALSE(mismatch.ok());
  EXPECT_THAT(mismatch.status().message(), HasSubstr("rig.yaml"));
  EXPECT_THAT(mismatch.status().message(), HasSubstr("[b, a]"));
}

TEST(SequenceWriterTest, RejectsFramesOfAnotherSizeThanTheRig) {
  test::TempDir dir;
  const std::string rig = WriteRig(dir, {"a", "b"}, 64, 48);
  auto writer = SequenceWriter::Create(dir.File("seq"), {"a", "b"}, rig, 1);
  ASSERT_TRUE(writer.ok());
  const Status status = (*writer)->Append(FrameSet(0));
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_THAT(status.message(), HasSubstr("32x24"));
  EXPECT_THAT(status.message(), HasSubstr("[64, 48]"));
}

// A full disk, simulated with a file-size limit: the frame set that does not fit is removed
// completely and the earlier ones stay valid.
TEST(SequenceWriterTest, AFailedWriteLeavesTheEarlierFrameSetsValid) {
  test::TempDir dir;
  const std::string out = dir.File("seq");
  auto writer = SequenceWriter::Create(out, {"a", "b"}, "", 0);  // level 0: PNG size ~ pixels
  ASSERT_TRUE(writer.ok());
  for (int i = 0; i < 2; ++i) ASSERT_TRUE((*writer)->Append(FrameSet(i)).ok());

  rlimit old_limit{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old_limit), 0);
  struct sigaction ignore = {}, old_action = {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGXFSZ, &ignore, &old_action);
  rlimit limit = old_limit;
  limit.rlim_cur = 8192;  // a 32x24 frame fits, a 200x200 frame does not
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  std::vector<Frame> big = FrameSet(2);
  big[1].image = cv::Mat(200, 200, CV_8UC1, cv::Scalar(7));
  const Status status = (*writer)->Append(big);
  setrlimit(RLIMIT_FSIZE, &old_limit);
  sigaction(SIGXFSZ, &old_action, nullptr);

  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(status.message(), HasSubstr("000002.png"));
  EXPECT_EQ((*writer)->num_frames(), 2);
  test::ExpectValidRecording(out, {"a", "b"}, 2);
  EXPECT_FALSE(std::filesystem::exists(out + "/a/000002.png"));
  // Writing goes on once there is room again.
  ASSERT_TRUE((*writer)->Append(FrameSet(2)).ok());
  test::ExpectValidRecording(out, {"a", "b"}, 3);
}

}  // namespace
}  // namespace bcot
