// The recorder's logic with scripted sources: sync, re-pairing after a drop, a lost camera,
// a stop request. Aravis cameras are covered in aravis_capture_test.cc.
#include "bcot/capture/recorder.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "capture_test_util.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;
constexpr int64_t kMs = 1000000;

// Camera c's k-th frame at 40 ms · k plus a small per-camera offset.
std::vector<GrabResult> Steady(int camera, int count) {
  std::vector<GrabResult> script;
  for (int k = 0; k < count; ++k)
    script.push_back(test::ScriptedFrame(camera, k, k * 40 * kMs + camera * kMs));
  return script;
}

std::vector<std::unique_ptr<FrameSource>> Sources(std::vector<GrabResult> a,
                                                  std::vector<GrabResult> b) {
  std::vector<std::unique_ptr<FrameSource>> sources;
  sources.push_back(std::make_unique<test::ScriptedSource>("a", std::move(a)));
  sources.push_back(std::make_unique<test::ScriptedSource>("b", std::move(b)));
  return sources;
}

TEST(RecorderTest, RecordsTheRequestedNumberOfSynchronizedSets) {
  test::TempDir dir;
  RecorderOptions options;
  options.max_frame_sets = 6;
  Recorder recorder(Sources(Steady(0, 20), Steady(1, 20)), options);
  int progress_calls = 0;
  const RecordingSummary summary =
      recorder.Record(dir.File("seq"), [&](const RecordingStats&) { ++progress_calls; });
  ASSERT_TRUE(summary.status.ok()) << summary.status.message();
  EXPECT_EQ(summary.stop_reason, "max_frame_sets reached");
  EXPECT_EQ(summary.stats.frame_sets, 6);
  EXPECT_GE(progress_calls, 6);
  test::ExpectValidRecording(dir.File("seq"), {"a", "b"}, 6);
  const auto rows = test::ReadCsvRows(dir.File("seq/timestamps.csv"));
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(rows[i][1], std::to_string(i * 40 * kMs));
    EXPECT_EQ(rows[i][2], std::to_string(i * 40 * kMs + kMs));
  }
}

TEST(RecorderTest, ADroppedFrameCostsOneSetAndTheRestStaysInSync) {
  test::TempDir dir;
  std::vector<GrabResult> b = Steady(1, 8);
  b[3] = test::Missed();  // camera b misses the 4th trigger
  RecorderOptions options;
  options.max_frame_sets = 7;
  Recorder recorder(Sources(Steady(0, 8), b), options);
  const RecordingSummary summary = recorder.Record(dir.File("seq"));
  ASSERT_TRUE(summary.status.ok()) << summary.status.message();
  EXPECT_EQ(summary.stats.frame_sets, 7);  // 8 triggers, one set lost to the missed frame
  EXPECT_EQ(summary.stats.missed[1], 1);
  EXPECT_EQ(summary.stats.discarded[0], 1);
  test::ExpectValidRecording(dir.File("seq"), {"a", "b"}, 7);
  const auto rows = test::ReadCsvRows(dir.File("seq/timestamps.csv"));
  for (const auto& row : rows) {
    EXPECT_EQ(std::stoll(row[2]) - std::stoll(row[1]), kMs) << "frames of one set must pair";
  }
}

TEST(RecorderTest, ALostCameraStopsTheRecordingWithAValidDirectory) {
  test::TempDir dir;
  std::vector<GrabResult> b = Steady(1, 4);
  b.push_back({GrabStatus::kLost, Frame(), "unplugged"});
  Recorder recorder(Sources(Steady(0, 10), b), RecorderOptions());
  const RecordingSummary summary = recorder.Record(dir.File("seq"));
  ASSERT_FALSE(summary.status.ok());
  EXPECT_EQ(summary.status.code(), StatusCode::kIoError);
  EXPECT_THAT(summary.status.message(), HasSubstr("camera 'b'"));
  EXPECT_THAT(summary.status.message(), HasSubstr("unplugged"));
  EXPECT_EQ(summary.stats.frame_sets, 4);
  test::ExpectValidRecording(dir.File("seq"), {"a", "b"}, 4);
}

TEST(RecorderTest, TooManyMissesInARowCountAsALostCamera) {
  test::TempDir dir;
  std::vector<GrabResult> b = Steady(1, 2);
  for (int i = 0; i < 3; ++i) b.push_back(test::Missed());
  RecorderOptions options;
  options.max_consecutive_misses = 3;
  Recorder recorder(Sources(Steady(0, 10), b), options);
  const RecordingSummary summary = recorder.Record(dir.File("seq"));
  ASSERT_FALSE(summary.status.ok());
  EXPECT_THAT(summary.status.message(), HasSubstr("3 grabs in a row"));
  test::ExpectValidRecording(dir.File("seq"), {"a", "b"}, 2);
}

TEST(RecorderTest, CamerasWhoseFramesNeverPairStopTheRecording) {
  test::TempDir dir;
  std::vector<GrabResult> b;
  for (int k = 0; k < 20; ++k) b.push_back(test::ScriptedFrame(1, k, k * 40 * kMs + 20 * kMs));
  RecorderOptions options;
  options.max_rounds_without_set = 6;
  Recorder recorder(Sources(Steady(0, 20), b), options);
  const RecordingSummary summary = recorder.Record(dir.File("seq"));
  ASSERT_FALSE(summary.status.ok());
  EXPECT_EQ(summary.stop_reason, "cameras not synchronized");
  EXPECT_THAT(summary.status.message(), HasSubstr("no frame set in 6 rounds"));
  EXPECT_GT(summary.stats.discarded[0] + summary.stats.discarded[1], 0);
  test::ExpectValidRecording(dir.File("seq"), {"a", "b"}, 0);
}

TEST(RecorderTest, AStopRequestEndsTheRecordingCleanly) {
  test::TempDir dir;
  Recorder recorder(Sources(Steady(0, 100), Steady(1, 100)), RecorderOptions());
  const RecordingSummary summary = recorder.Record(dir.File("seq"), [&](const RecordingStats& s) {
    if (s.frame_sets == 5) recorder.RequestStop();
  });
  ASSERT_TRUE(summary.status.ok()) << summary.status.message();
  EXPECT_EQ(summary.stop_reason, "stop requested");
  EXPECT_EQ(summary.stats.frame_sets, 5);
  test::ExpectValidRecording(dir.File("seq"), {"a", "b"}, 5);
}

TEST(RecorderTest, InvalidOptionsAndOutputAreReportedBeforeRecording) {
  test::TempDir dir;
  RecorderOptions options;
  options.max_skew_ms = 0.0;
  options.png_compression = 12;
  Recorder recorder(Sources(Steady(0, 3), Steady(1, 3)), options);
  const RecordingSummary summary = recorder.Record(dir.File("seq"));
  test::ExpectErrorNaming(summary.status, StatusCode::kInvalidConfig,
                          {"recording.max_skew_ms = 0", "recording.png_compression = 12"});
  EXPECT_FALSE(std::filesystem::exists(dir.File("seq")));
}

}  // namespace
}  // namespace bcot
