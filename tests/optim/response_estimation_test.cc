#include "bcot/optim/response_estimation.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "test_util.h"

namespace bcot {
namespace {

const ImageResponse kLinear = ImageResponse::Gamma(1.0);

// Every candidate's score, for failure messages.
std::string Describe(const ResponseEstimate& estimate) {
  std::string text = "chosen " + estimate.response.Name() + ";";
  for (const ResponseScore& score : estimate.scores) {
    text += fmt::format(" {}: slope {:+.3f} ± {:.3f} px, spread {:.3f} ± {:.3f} px ({} lines);",
                        score.response.Name(), score.slope_px, score.slope_standard_error_px,
                        score.spread_px, score.spread_standard_error_px, score.lines);
  }
  return text;
}

// Frame 0 of a binocular `bcot synth` demo scene whose camera encodes with display gamma
// `sensor_gamma` (1 = a linear camera), its images and its true rig_from_objcentre.
class SynthFrame {
 public:
  explicit SynthFrame(double sensor_gamma) {
    StatusOr<SynthOptions> synth = ReadSynthOptions(
        test::SourcePath("configs/synth/demo.yaml"),
        {"motion.num_frames=1", "render.threads=2", fmt::format("sensor.gamma={}", sensor_gamma)});
    BCOT_CHECK(synth.ok());
    const std::string out = dir_.File("seq");
    BCOT_CHECK(Synthesize(*synth, out).ok());
    StatusOr<Sequence> sequence = LoadSequence(out);
    BCOT_CHECK(sequence.ok());
    sequence_ = std::move(sequence).value();
    StatusOr<Mesh> mesh = Mesh::Load(sequence_.object.mesh_path, sequence_.object.unit_to_mm);
    BCOT_CHECK(mesh.ok());
    caster_ = std::make_unique<RayCaster>(*mesh);
    StatusOr<std::vector<Eigen::Isometry3d>> truth = ReadPoseFile(out + "/gt/rig_from_object.txt");
    BCOT_CHECK(truth.ok());
    rig_from_objcentre_ = truth->front() * caster_->mesh().objcentre_from_template().inverse();
    for (int c = 0; c < sequence_.rig.size(); ++c) {
      images_.push_back(cv::imread(sequence_.image_paths[c][0]));
      views_.push_back({sequence_.rig[c].camera, sequence_.rig[c].cam_from_rig, 1.0});
    }
  }

  std::vector<FrameView> FrameViews() const {
    std::vector<FrameView> views;
    for (size_t c = 0; c < views_.size(); ++c) {
      FrameView view;
      view.camera = &views_[c].camera;
      view.cam_from_rig = views_[c].cam_from_rig;
      view.image = &images_[c];
      views.push_back(view);
    }
    return views;
  }

  const RayCaster& caster() const { return *caster_; }
  const std::vector<TrackedView>& views() const { return views_; }
  const std::vector<cv::Mat3b>& images() const { return images_; }
  const Eigen::Isometry3d& rig_from_objcentre() const { return rig_from_objcentre_; }

 private:
  test::TempDir dir_;
  Sequence sequence_;
  std::unique_ptr<RayCaster> caster_;
  std::vector<TrackedView> views_;
  std::vector<cv::Mat3b> images_;
  Eigen::Isometry3d rig_from_objcentre_ = Eigen::Isometry3d::Identity();
};

// The first-order model of docs/method.md against the edge fit itself: a Gaussian-blurred step
// between linear levels ρ (inside) and 1 (outside), its values raised to κ, is found moved
// towards its bright side by (κ − 1)·w·D(ρ), D from the half-level crossing. The fit weighs the
// whole profile and moves 10–20 % further; the estimate needs only the sign and the zero.
TEST(PowerShiftRateTest, PredictsHowFarTheEdgeFitMovesUnderAPowerError) {
  EXPECT_EQ(PowerShiftRate(1.0), 0.0);
  EXPECT_EQ(PowerShiftRate(0.5), 0.0);
  EXPECT_NEAR(PowerShiftRate(kMaxLevelRatio), std::sqrt(2.0 * M_PI) * std::log(2.0) / 2.0, 1e-4);
  const EdgeLineOptions options;
  const double width = 0.8;
  for (const double rho : {1.5, 3.0, 10.0}) {
    for (const double kappa : {0.95, 1.05}) {
      std::vector<double> profile;
      for (int k = 0; k <= 32; ++k) {
        const double s = -4.0 + k * options.step_px;
        const double outside_share = 0.5 * std::erfc(-s / (width * std::sqrt(2.0)));
        profile.push_back(std::pow(rho + (1.0 - rho) * outside_share, kappa) / rho);
      }
      EdgeFit fit;
      ASSERT_TRUE(FitEdgeProfile(profile, -4.0, options, &fit)) << rho << " " << kappa;
      const double predicted = -(kappa - 1.0) * width * PowerShiftRate(rho);  // inward
      EXPECT_GT(fit.mean_px / predicted, 1.0) << "rho " << rho << " kappa " << kappa;
      EXPECT_LT(fit.mean_px / predicted, 1.25) << "rho " << rho << " kappa " << kappa;
    }
  }
}

TEST(ResponseEstimationOptionsTest, DefaultsAreValidAndViolationsAreListed) {
  EXPECT_TRUE(ResponseEstimationOptions().Validate().ok());
  EXPECT_EQ(DefaultResponseCandidates().front(), ImageResponse());
  ResponseEstimationOptions bad;
  bad.candidates = {ImageResponse::Auto()};
  bad.min_slope_z = -1.0;
  bad.min_spread_z = std::nan("");
  bad.bootstrap_samples = 3;
  bad.edge_rounds = 0;
  test::ExpectErrorNaming(bad.Validate(), StatusCode::kInvalidConfig,
                          {"candidate auto", "min_slope_z = -1", "edge_rounds = 0",
                           "min_spread_z = nan", "bootstrap_samples = 3"});
}

// A linear camera is recognised from one frame. Its edges read as sRGB sit towards their bright
// sides (polarity slope > 3 standard errors), read as γ 1 they do not; with the demo's sharp
// 0.3 px blur that slope is small (+0.05 px) and the consistency test decides (spread 0.33 px
// as sRGB, 0.22 px as γ 1). A camera encoding with display gamma 2.2 (sRGB's curve but for its
// toe) keeps the default.
TEST(EstimateImageResponseTest, RecognisesALinearCameraAndKeepsSrgbForADisplayGamma) {
  const SynthFrame linear_camera(1.0);
  const FrameProblem problem(linear_camera.caster(), FrameProblemOptions());
  const StatusOr<ResponseEstimate> linear = EstimateImageResponse(
      problem, linear_camera.FrameViews(), linear_camera.rig_from_objcentre());
  ASSERT_TRUE(linear.ok()) << linear.status().message();
  EXPECT_EQ(linear->response, kLinear) << Describe(*linear);
  ASSERT_EQ(linear->scores.size(), DefaultResponseCandidates().size());
  // Read as sRGB (too heavy) the edges sit towards their bright sides; read as γ 1 they do not.
  EXPECT_GT(linear->scores[0].slope_px, 3.0 * linear->scores[0].slope_standard_error_px);
  EXPECT_LT(std::abs(linear->scores[1].slope_px), 2.0 * linear->scores[1].slope_standard_error_px);

  const SynthFrame display_camera(2.2);
  const FrameProblem display_problem(display_camera.caster(), FrameProblemOptions());
  const StatusOr<ResponseEstimate> display = EstimateImageResponse(
      display_problem, display_camera.FrameViews(), display_camera.rig_from_objcentre());
  ASSERT_TRUE(display.ok()) << display.status().message();
  EXPECT_EQ(display->response, ImageResponse()) << Describe(*display);
}

// The candidates are solved concurrently: one and two threads give the same scores bit for bit.
TEST(EstimateImageResponseTest, CandidatesSolvedConcurrentlyGiveTheOneThreadScores) {
  const SynthFrame frame(1.0);
  const FrameProblem problem(frame.caster(), FrameProblemOptions());
  auto estimate = [&](int threads) {
    StatusOr<ResponseEstimate> result = Status::InvalidInput("not run");
    tbb::task_arena arena(threads);
    arena.execute([&] {
      result = EstimateImageResponse(problem, frame.FrameViews(), frame.rig_from_objcentre());
    });
    return result;
  };
  const StatusOr<ResponseEstimate> one = estimate(1);
  const StatusOr<ResponseEstimate> two = estimate(2);
  ASSERT_TRUE(one.ok()) << one.status().message();
  ASSERT_TRUE(two.ok()) << two.status().message();
  EXPECT_EQ(one->response, two->response);
  ASSERT_EQ(one->scores.size(), two->scores.size());
  for (size_t c = 0; c < one->scores.size(); ++c) {
    SCOPED_TRACE(one->scores[c].response.Name());
    EXPECT_EQ(one->scores[c].response, two->scores[c].response);
    EXPECT_GT(one->scores[c].lines, 0);
    EXPECT_EQ(one->scores[c].lines, two->scores[c].lines);
    EXPECT_EQ(one->scores[c].slope_px, two->scores[c].slope_px);
    EXPECT_EQ(one->scores[c].spread_px, two->scores[c].spread_px);
  }
}

TEST(EstimateImageResponseTest, TooFewLinesIsAnError) {
  const SynthFrame frame(2.2);
  FrameProblemOptions options;
  options.edge.min_lines = 1000000;
  const FrameProblem problem(frame.caster(), options);
  const StatusOr<ResponseEstimate> estimate =
      EstimateImageResponse(problem, frame.FrameViews(), frame.rig_from_objcentre());
  EXPECT_EQ(estimate.status().code(), StatusCode::kInvalidInput);
}

// With edge.response auto the tracker's first Initialize estimates the response and decodes
// every later solve with it; with the edge stage off nothing is estimated (sRGB).
TEST(MultiViewTrackerResponseTest, InitializeResolvesAnAutomaticResponse) {
  const SynthFrame frame(1.0);
  MultiViewTrackerOptions options;
  options.frame.edge.lines.response.kind = ImageResponse::Kind::kAuto;
  StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
      MultiViewTracker::Create(frame.caster(), frame.views(), options);
  ASSERT_TRUE(tracker.ok());
  EXPECT_EQ((*tracker)->image_response(), ImageResponse());
  Eigen::Isometry3d pose = frame.rig_from_objcentre();
  ASSERT_TRUE((*tracker)->Initialize(frame.images(), &pose).ok());
  ASSERT_TRUE((*tracker)->response_estimate().has_value());
  EXPECT_TRUE((*tracker)->response_estimate()->ok());
  EXPECT_EQ((*tracker)->image_response(), kLinear);
  EXPECT_LT((pose.translation() - frame.rig_from_objcentre().translation()).norm(), 0.5);

  options.frame.edge.enabled = false;
  tracker = MultiViewTracker::Create(frame.caster(), frame.views(), options);
  ASSERT_TRUE(tracker.ok());
  pose = frame.rig_from_objcentre();
  ASSERT_TRUE((*tracker)->Initialize(frame.images(), &pose).ok());
  EXPECT_FALSE((*tracker)->response_estimate().has_value());
  EXPECT_EQ((*tracker)->image_response(), ImageResponse());
}

}  // namespace
}  // namespace bcot
