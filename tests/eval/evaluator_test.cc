#include "bcot/eval/evaluator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/eval/eval_report.h"
#include "benchmark_test_data.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// `pose` turned by `deg` about the object's x axis (object frame), translation unchanged.
Eigen::Isometry3d Turned(const Eigen::Isometry3d& pose, double deg) {
  Eigen::Isometry3d turned = pose;
  turned.linear() = pose.linear() * ExpSO3(Eigen::Vector3d(deg * kPi / 180.0, 0, 0));
  return turned;
}

// No frame lost and every column but the time at 100 %, as is the ADD AUC.
void ExpectPerfect(const MetricSummary& summary, int num_frames) {
  EXPECT_EQ(summary.num_frames, num_frames);
  EXPECT_EQ(summary.num_lost, 0);
  for (int i = 0; i + 1 < kNumMetricColumns; ++i) {
    EXPECT_EQ(summary.columns[i], 100.0) << kMetricColumnNames[i];
  }
  EXPECT_DOUBLE_EQ(summary.add_auc, 100.0);
}

class EvaluatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::WriteBcotSequence(dir_.File("data"), "scene A", "Cube Part", test::MakeTrajectory(10));
    test::WriteBcotSequence(dir_.File("data"), "scene B", "Cube Part", test::MakeTrajectory(6));
    const StatusOr<std::vector<BenchmarkSequence>> sequences =
        LoadBenchmark(dir_.File("data"), options_);
    ASSERT_TRUE(sequences.ok()) << sequences.status().message();
    sequences_ = *sequences;
    const StatusOr<Mesh> mesh = Mesh::Load(sequences_[0].mesh_path);
    ASSERT_TRUE(mesh.ok());
    mesh_ = std::make_unique<Mesh>(*mesh);
  }

  // Writes result files equal to the GT except `edit(scene, frame, pose)`.
  template <typename Edit>
  void WriteResults(const std::string& root, Edit edit) {
    for (const BenchmarkSequence& s : sequences_) {
      std::vector<Eigen::Isometry3d> poses = s.gt_cam_from_object;
      for (size_t f = 0; f < poses.size(); ++f)
        poses[f] = edit(s.scene, static_cast<int>(f), poses[f]);
      ASSERT_TRUE(WritePoseFile(root + "/" + s.RelativeDir() + "/pose.txt", poses).ok());
    }
  }

  test::TempDir dir_;
  EvalOptions options_;
  std::vector<BenchmarkSequence> sequences_;
  std::unique_ptr<Mesh> mesh_;
};

TEST_F(EvaluatorTest, GroundTruthScoredAgainstItselfIsPerfect) {
  WriteResults(dir_.File("results"),
               [](const std::string&, int, const Eigen::Isometry3d& p) { return p; });
  const StatusOr<std::vector<SequenceResult>> results =
      EvaluateOffline(sequences_, dir_.File("results"), options_);
  ASSERT_TRUE(results.ok()) << results.status().message();
  ASSERT_EQ(results->size(), 2u);
  EXPECT_EQ((*results)[0].frames.size(), 9u);  // frames 1..9
  EXPECT_EQ((*results)[1].frames.size(), 5u);
  const EvalReport report = BuildEvalReport(*results, "offline");
  ExpectPerfect(report.overall.summary, 14);
  EXPECT_TRUE(std::isnan(report.overall.summary.columns[kNumMetricColumns - 1]));  // no times
}

TEST_F(EvaluatorTest, OneFrameOffBySixDegreesIsLostExactlyOnce) {
  WriteResults(dir_.File("results"),
               [](const std::string& scene, int f, const Eigen::Isometry3d& p) {
                 return scene == "scene A" && f == 4 ? Turned(p, 6.0) : p;
               });
  const StatusOr<std::vector<SequenceResult>> results =
      EvaluateOffline(sequences_, dir_.File("results"), options_);
  ASSERT_TRUE(results.ok()) << results.status().message();
  const EvalReport report = BuildEvalReport(*results, "offline");
  const MetricSummary& s = report.overall.summary;
  EXPECT_EQ(s.num_lost, 1);
  EXPECT_NEAR(s.columns[3], 100.0 * 13 / 14, 1e-9);  // 5°5cm
  EXPECT_NEAR(s.columns[4], 100.0 * 13 / 14, 1e-9);  // 5°
  EXPECT_EQ(s.columns[5], 100.0);                    // 5cm
  ASSERT_EQ(report.per_scene.size(), 2u);
  EXPECT_EQ(report.per_scene[0].name, "scene A");
  EXPECT_EQ(report.per_scene[0].summary.num_lost, 1);
  EXPECT_NEAR(report.per_scene[0].summary.columns[3], 100.0 * 8 / 9, 1e-9);
  EXPECT_EQ(report.per_scene[1].summary.columns[3], 100.0);
  ASSERT_EQ(report.per_object.size(), 1u);
  EXPECT_EQ(report.per_object[0].name, "Cube Part");
  EXPECT_EQ(report.per_object[0].summary.num_frames, 14);
}

TEST_F(EvaluatorTest, ResultFilesWithoutFrameZeroAreAccepted) {
  const BenchmarkSequence& s = sequences_[1];
  std::vector<Eigen::Isometry3d> frames_1_to_5(s.gt_cam_from_object.begin() + 1,
                                               s.gt_cam_from_object.end());
  frames_1_to_5[0] = Turned(frames_1_to_5[0], 10.0);
  const StatusOr<SequenceResult> result = ScoreSequence(s, *mesh_, frames_1_to_5, "r", options_);
  ASSERT_TRUE(result.ok()) << result.status().message();
  ASSERT_EQ(result->frames.size(), 5u);
  EXPECT_NEAR(result->frames[0].errors.rotation_deg, 10.0, 1e-6);
  EXPECT_TRUE(result->frames[0].lost);
  EXPECT_FALSE(result->frames[1].lost);
  const std::vector<Eigen::Isometry3d> too_few(3, Eigen::Isometry3d::Identity());
  const Status status = ScoreSequence(s, *mesh_, too_few, "r.txt", options_).status();
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_THAT(status.message(), HasSubstr("r.txt: 3 poses, expected 6"));
}

TEST_F(EvaluatorTest, BadResultFilesAreErrorsNamingFileAndLine) {
  WriteResults(dir_.File("results"),
               [](const std::string&, int, const Eigen::Isometry3d& p) { return p; });
  const std::string path = dir_.File("results/scene B/Cube Part/pose.txt");
  std::string text = *ReadTextFile(path);
  text.replace(text.find('\n') + 1, 1, "x");
  test::WriteText(path, text);
  Status status = EvaluateOffline(sequences_, dir_.File("results"), options_).status();
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_THAT(status.message(), HasSubstr(path + ":2"));
  std::filesystem::remove(path);
  status = EvaluateOffline(sequences_, dir_.File("results"), options_).status();
  EXPECT_EQ(status.code(), StatusCode::kNotFound);
  EXPECT_THAT(status.message(), HasSubstr(path));
}

// Returns the GT of the frame it is shown (read from the image's pixel value), turned by
// `error_deg(frame, frames since the last reset)`.
class FakeTracker : public MonocularTracker {
 public:
  using ErrorFn = std::function<double(int frame, int since_reset)>;
  FakeTracker(std::vector<Eigen::Isometry3d> gt, ErrorFn error_deg, std::vector<int>* resets)
      : gt_(std::move(gt)), error_deg_(std::move(error_deg)), resets_(resets) {}

  Status Reset(const cv::Mat3b& image, const Eigen::Isometry3d& cam_from_object) override {
    const int frame = image(0, 0)[0];
    EXPECT_THAT(cam_from_object, test::PoseNear(gt_[frame], 1e-12, 1e-12));
    resets_->push_back(frame);
    since_reset_ = 0;
    return Status::Ok();
  }
  StatusOr<Eigen::Isometry3d> Track(const cv::Mat3b& image) override {
    const int frame = image(0, 0)[0];
    ++since_reset_;
    const double deg = error_deg_(frame, since_reset_);
    if (deg < 0) return Status::Internal("tracker gave up");
    return Turned(gt_[frame], deg);
  }

 private:
  std::vector<Eigen::Isometry3d> gt_;
  ErrorFn error_deg_;
  std::vector<int>* resets_;
  int since_reset_ = 0;
};

TEST_F(EvaluatorTest, OnlineProtocolResetsOnlyAfterALostFrame) {
  const BenchmarkSequence& s = sequences_[0];  // 10 frames
  std::vector<int> resets;
  FakeTracker six_degrees_once(
      s.gt_cam_from_object, [](int frame, int) { return frame == 4 ? 6.0 : 0.5; }, &resets);
  std::vector<Eigen::Isometry3d> estimates;
  StatusOr<SequenceResult> result =
      RunTrackingProtocol(s, *mesh_, &six_degrees_once, options_, &estimates);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_THAT(resets, ElementsAre(0, 4));
  EXPECT_EQ(result->num_resets, 1);
  ASSERT_EQ(result->frames.size(), 9u);
  int lost = 0;
  for (const ScoredFrame& frame : result->frames) lost += frame.lost ? 1 : 0;
  EXPECT_EQ(lost, 1);
  EXPECT_TRUE(result->frames[3].lost);  // frame 4
  ASSERT_EQ(estimates.size(), 10u);
  EXPECT_NEAR(RotationDistanceDeg(estimates[4].linear(), s.gt_cam_from_object[4].linear()), 6.0,
              1e-6);

  // Drift of 1.9° per frame since the last reset: lost on the 3rd frame after each reset
  // (5.7° > 5°), i.e. frames 3, 6 and 9.
  resets.clear();
  FakeTracker drifting(
      s.gt_cam_from_object, [](int, int since) { return 1.9 * since; }, &resets);
  result = RunTrackingProtocol(s, *mesh_, &drifting, options_);
  ASSERT_TRUE(result.ok());
  EXPECT_THAT(resets, ElementsAre(0, 3, 6, 9));
  EXPECT_EQ(result->num_resets, 3);
  const MetricSummary summary = Summarize(result->frames);
  EXPECT_EQ(summary.num_lost, 3);
  EXPECT_NEAR(summary.columns[3], 100.0 * 6 / 9, 1e-9);                // 5°5cm
  EXPECT_NEAR(summary.columns[7], 100.0 * 3 / 9, 1e-9);                // 2°: only the 1.9° frames
  EXPECT_TRUE(std::isfinite(summary.columns[kNumMetricColumns - 1]));  // timed

  // A tracker error is a lost frame, not an aborted evaluation.
  resets.clear();
  FakeTracker failing(
      s.gt_cam_from_object, [](int frame, int) { return frame == 2 ? -1.0 : 0.0; }, &resets);
  result = RunTrackingProtocol(s, *mesh_, &failing, options_);
  ASSERT_TRUE(result.ok());
  EXPECT_THAT(resets, ElementsAre(0, 2));
  EXPECT_TRUE(result->frames[1].lost);
  EXPECT_FALSE(result->frames[2].lost);
}

TEST_F(EvaluatorTest, EvaluateOnlineBuildsOneTrackerPerSequenceAndWritesRescorablePoses) {
  std::vector<int> resets;
  std::vector<Camera> cameras;
  std::map<std::string, std::vector<Eigen::Isometry3d>> gt_by_scene;
  for (const BenchmarkSequence& s : sequences_) gt_by_scene[s.scene] = s.gt_cam_from_object;
  int built = 0;
  const MonocularTrackerFactory factory =
      [&](const Camera& camera, const Mesh& mesh) -> StatusOr<std::unique_ptr<MonocularTracker>> {
    EXPECT_EQ(mesh.diameter(), 100.0);
    cameras.push_back(camera);
    const auto& gt = built++ == 0 ? gt_by_scene["scene A"] : gt_by_scene["scene B"];
    return std::unique_ptr<MonocularTracker>(std::make_unique<FakeTracker>(
        gt, [](int frame, int) { return frame == 4 ? 6.0 : 0.0; }, &resets));
  };
  const StatusOr<std::vector<SequenceResult>> results =
      EvaluateOnline(sequences_, factory, options_, dir_.File("poses"));
  ASSERT_TRUE(results.ok()) << results.status().message();
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[0].width, 8);  // from the first image
  EXPECT_EQ(cameras[0].height, 6);
  EXPECT_EQ(cameras[0].fx, 500.5);
  EXPECT_EQ((*results)[0].num_resets + (*results)[1].num_resets, 2);
  // The written estimates score the same offline.
  const StatusOr<std::vector<SequenceResult>> rescored =
      EvaluateOffline(sequences_, dir_.File("poses"), options_);
  ASSERT_TRUE(rescored.ok()) << rescored.status().message();
  EXPECT_EQ(BuildEvalReport(*rescored, "offline").overall.summary.num_lost, 2);
}

TEST(EvalOptionsTest, ValidateAndYaml) {
  EvalOptions options;
  options.layout = "ycb";
  options.reset_rotation_deg = 0;
  options.curve.steps = 0;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"layout = 'ycb'", "reset_rotation_deg = 0", "curve.steps = 0"});
  test::TempDir dir;
  test::WriteText(dir.File("eval.yaml"), "layout: rbot\ncurve:\n  steps: 50\n");
  StatusOr<EvalOptions> read = ReadEvalOptions(dir.File("eval.yaml"), {"rbot_variant=c_noisy"});
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->layout, "rbot");
  EXPECT_EQ(read->rbot_variant, "c_noisy");
  EXPECT_EQ(read->curve.steps, 50);
  test::WriteText(dir.File("resolved.yaml"), FormatEvalOptions(*read));
  const StatusOr<EvalOptions> again = ReadEvalOptions(dir.File("resolved.yaml"));
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(FormatEvalOptions(*again), FormatEvalOptions(*read));
  test::WriteText(dir.File("bad.yaml"), "layout: bcot\ncurve:\n  step: 50\n");
  const Status status = ReadEvalOptions(dir.File("bad.yaml")).status();
  EXPECT_EQ(status.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(status.message(), HasSubstr("bad.yaml:3"));
}

TEST(EvaluatorRealDataTest, RealCatGroundTruthAgainstItselfIsPerfect) {
  const std::string root = test::SharedDataPath("bcot_real_cat");
  if (root.empty() || !std::filesystem::exists(root)) GTEST_SKIP() << "no shared data";
  const EvalOptions options;
  const StatusOr<std::vector<BenchmarkSequence>> sequences = LoadBenchmark(root, options);
  ASSERT_TRUE(sequences.ok()) << sequences.status().message();
  // The release itself is laid out like a results folder.
  const StatusOr<std::vector<SequenceResult>> results = EvaluateOffline(*sequences, root, options);
  ASSERT_TRUE(results.ok()) << results.status().message();
  ExpectPerfect(BuildEvalReport(*results, "offline").overall.summary, 30);
}

}  // namespace
}  // namespace bcot
