#include "bcot/optim/window_problem.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/core/trajectory_metrics.h"
#include "bcot/optim/motion_prior_cost.h"
#include "bcot/optim/multi_view_tracker.h"
#include "region_test_scene.h"
#include "test_util.h"

namespace bcot {
namespace {

TEST(WindowProblemOptionsTest, ValidateListsEveryViolation) {
  EXPECT_TRUE(WindowProblemOptions().Validate().ok());
  WindowProblemOptions options;
  options.size = 2;
  options.iterations = 0;
  options.rotation_sigma_deg[1] = 0.0;
  options.translation_sigma_mm[2] = -1.0;
  options.robust_rotation_deg = -0.5;
  options.num_threads = 0;
  test::ExpectErrorNaming(
      options.Validate(), StatusCode::kInvalidConfig,
      {"size = 2", "overlap = 10", "iterations = 0", "rotation_sigma_deg = 0 (y)",
       "translation_sigma_mm = -1 (z)", "robust_rotation_deg = -0.5", "num_threads = 0"});
}

// The prior reaches 2 frames beyond a window with constant-velocity models, 3 as soon as one
// part holds a constant acceleration; the Cauchy scales are the thresholds in σ units.
TEST(WindowProblemOptionsTest, ContextFramesAndCauchyScales) {
  WindowProblemOptions options;
  options.translation_model = MotionModel::kConstantVelocity;
  options.rotation_model = MotionModel::kConstantVelocity;
  EXPECT_EQ(options.ContextFrames(), 2);
  options.rotation_model = MotionModel::kConstantAcceleration;
  EXPECT_EQ(options.ContextFrames(), 3);
  options.translation_sigma_mm = {0.1, 0.2, 0.4};  // geometric mean 0.2
  options.robust_translation_mm = 0.5;
  EXPECT_NEAR(options.TranslationCauchyScale(), 2.5, 1e-12);
  options.rotation_sigma_deg = {0.1, 0.1, 0.1};
  options.robust_rotation_deg = 0.0;
  EXPECT_EQ(options.RotationCauchyScale(), 0.0);
}

// The sliding scheme: windows of W frames stepping by W − overlap cover every frame, and the
// smoother never holds more than W + C frames of templates while streaming (C the context of
// the priors: 2 for constant velocity, 3 for constant acceleration).
// A trajectory whose centre's acceleration changes per frame by Gaussian steps of sd `jerk_mm`
// per axis and whose body angular velocity changes by steps of sd `spin_change_deg`, observed
// with white noise of sd `noise_mm` / `noise_deg` per axis.
std::vector<Eigen::Isometry3d> RandomMotion(int frames, double jerk_mm, double spin_change_deg,
                                            const Eigen::Vector3d& noise_mm, double noise_deg,
                                            unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  auto draw = [&](double sd) {
    return Eigen::Vector3d(sd * gaussian(rng), sd * gaussian(rng), sd * gaussian(rng));
  };
  constexpr double kRad = kPi / 180.0;
  Eigen::Vector3d centre(0.0, 0.0, 600.0), velocity(2.0, -1.0, 0.5), acceleration(0.1, 0.0, 0.0);
  Eigen::Vector3d spin(0.02, 0.01, -0.015);  // rad/frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  std::vector<Eigen::Isometry3d> observed;
  for (int t = 0; t < frames; ++t) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rotation * ExpSO3(draw(noise_deg * kRad));
    pose.translation() = centre + draw(1.0).cwiseProduct(noise_mm);
    observed.push_back(pose);
    acceleration += draw(jerk_mm);
    velocity += acceleration;
    centre += velocity;
    spin += draw(spin_change_deg * kRad);
    rotation = rotation * ExpSO3(spin);
  }
  return observed;
}
std::vector<Eigen::Isometry3d> RandomMotion(int frames, double jerk_mm, double spin_change_deg,
                                            double noise_mm, double noise_deg, unsigned seed) {
  return RandomMotion(frames, jerk_mm, spin_change_deg, Eigen::Vector3d::Constant(noise_mm),
                      noise_deg, seed);
}

// Empirical Bayes: the motion's own change per frame, the noise's share removed, raises the
// prior σ; a smooth motion keeps the configured floor, and one lost frame does not move it.
TEST(AdaptedPriorOptionsTest, RaisesSigmaToTheMotionAndKeepsTheFloorOnSmoothMotion) {
  const WindowProblemOptions options;  // σ 0.1 mm/frame³ and 0.1°/frame²
  const PerFrameNoise noise{0.03 * 0.03 * Eigen::Matrix3d::Identity(),
                            std::pow(0.05 * kPi / 180.0, 2) * Eigen::Matrix3d::Identity()};
  // Smooth (the true changes 0.01, well below the floor), noisy as predicted: the floor stays.
  const WindowProblemOptions smooth =
      AdaptedPriorOptions(options, RandomMotion(40, 0.01, 0.01, 0.03, 0.05, 1), noise);
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(smooth.translation_sigma_mm[k], 0.1);
    EXPECT_DOUBLE_EQ(smooth.rotation_sigma_deg[k], 0.1);
  }
  // Fast: jerk 0.5 mm/frame³ and spin change 0.3°/frame², as in the Cycles scenes.
  std::vector<Eigen::Isometry3d> fast = RandomMotion(40, 0.5, 0.3, 0.03, 0.05, 2);
  WindowProblemOptions adapted = AdaptedPriorOptions(options, fast, noise);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(adapted.translation_sigma_mm[k], 0.5, 0.15) << k;
    EXPECT_NEAR(adapted.rotation_sigma_deg[k], 0.3, 0.09) << k;
  }
  // A lost frame 30 mm and 10° off: the median keeps the estimate.
  fast[20].translation() += Eigen::Vector3d(30.0, 0.0, 0.0);
  fast[20].linear() = fast[20].linear() * ExpSO3(Eigen::Vector3d(0.0, 10.0 * kPi / 180.0, 0.0));
  const WindowProblemOptions with_outlier = AdaptedPriorOptions(options, fast, noise);
  EXPECT_NEAR(with_outlier.translation_sigma_mm[0], adapted.translation_sigma_mm[0],
              0.3 * adapted.translation_sigma_mm[0]);
  EXPECT_NEAR(with_outlier.rotation_sigma_deg[0], adapted.rotation_sigma_deg[0],
              0.3 * adapted.rotation_sigma_deg[0]);
  // Too few frames for five spans: unchanged.
  const std::vector<Eigen::Isometry3d> short_span(fast.begin(), fast.begin() + 6);
  EXPECT_DOUBLE_EQ(AdaptedPriorOptions(options, short_span, noise).translation_sigma_mm[0], 0.1);
}

// One camera: its depth noise (rig z here, 1.5 mm) is 50 times its lateral noise, and its edge
// posteriors predict three times the noise the poses show from frame to frame (the slow part of
// their error does not change between frames). The motion is read where the noise is small,
// with the noise's fast share fitted where it is large: over 20 random motions σ follows a jerk
// of 0.5 mm/frame³ on average (single draws spread by about ±20 %), and smooth motions keep
// about the floor.
TEST(AdaptedPriorOptionsTest, ReadsTheMotionBesideOneCamerasDepthNoise) {
  const WindowProblemOptions options;  // σ 0.1 mm/frame³
  const Eigen::Vector3d noise_mm(0.03, 0.03, 1.5);
  PerFrameNoise predicted;
  predicted.translation_mm2 = 3.0 * Eigen::Matrix3d(noise_mm.cwiseAbs2().asDiagonal());
  predicted.rotation_rad2 = std::pow(0.05 * kPi / 180.0, 2) * Eigen::Matrix3d::Identity();
  constexpr int kMotions = 20;
  double fast = 0.0, smooth = 0.0;
  for (unsigned seed = 1; seed <= kMotions; ++seed) {
    const std::vector<Eigen::Isometry3d> moving = RandomMotion(40, 0.5, 0.3, noise_mm, 0.05, seed);
    fast += AdaptedPriorOptions(options, moving, predicted).translation_sigma_mm[0] / kMotions;
    smooth +=
        AdaptedPriorOptions(options, RandomMotion(40, 0.01, 0.01, noise_mm, 0.05, seed), predicted)
            .translation_sigma_mm[0] /
        kMotions;
  }
  EXPECT_NEAR(fast, 0.5, 0.1);
  EXPECT_LT(smooth, 0.15);
}

// Two cameras: their edge posteriors predict more noise than changes from frame to frame (the
// slow part of the error, which the window cannot remove, is in the prediction too; here three
// times the white noise's standard deviation). The white share is read from how the variance
// grows with one more difference, so the motion is not hidden under the prediction: over 20
// random motions σ follows a jerk of 0.5 mm/frame³ and a change of spin of 0.3°/frame² on
// average, and smooth motions keep about the floor. Subtracting the whole prediction (c·σ²,
// 20 · 0.09 mm² here, more than the differences' own variance) would keep the floor.
TEST(AdaptedPriorOptionsTest, ReadsTheNoisesWhiteShareFromItsGrowthWithTheDifferenceOrder) {
  const WindowProblemOptions options;  // σ 0.1 mm/frame³ and 0.1°/frame²
  const PerFrameNoise predicted{0.3 * 0.3 * Eigen::Matrix3d::Identity(),
                                std::pow(0.15 * kPi / 180.0, 2) * Eigen::Matrix3d::Identity()};
  constexpr int kMotions = 20;
  double translation = 0.0, rotation = 0.0, smooth_translation = 0.0, smooth_rotation = 0.0;
  for (unsigned seed = 1; seed <= kMotions; ++seed) {
    const WindowProblemOptions fast =
        AdaptedPriorOptions(options, RandomMotion(40, 0.5, 0.3, 0.1, 0.05, seed), predicted);
    const WindowProblemOptions smooth =
        AdaptedPriorOptions(options, RandomMotion(40, 0.01, 0.01, 0.1, 0.05, seed), predicted);
    translation += fast.translation_sigma_mm[0] / kMotions;
    rotation += fast.rotation_sigma_deg[0] / kMotions;
    smooth_translation += smooth.translation_sigma_mm[0] / kMotions;
    smooth_rotation += smooth.rotation_sigma_deg[0] / kMotions;
  }
  EXPECT_NEAR(translation, 0.5, 0.1);
  EXPECT_NEAR(rotation, 0.3, 0.06);
  EXPECT_LT(smooth_translation, 0.15);
  EXPECT_LT(smooth_rotation, 0.15);
}

class WindowSmootherTest : public ::testing::TestWithParam<MotionModel> {};

TEST_P(WindowSmootherTest, WindowsCoverTheSequenceWithBoundedMemory) {
  WindowProblemOptions options;
  options.size = 8;
  options.overlap = 3;
  options.translation_model = GetParam();
  options.rotation_model = MotionModel::kConstantVelocity;
  WindowSmoother smoother(options);
  int most_buffered = 0;
  for (int frame = 0; frame < 41; ++frame) {
    smoother.Push(Eigen::Isometry3d::Identity(), {});
    most_buffered = std::max(most_buffered, smoother.buffered_frames());
  }
  smoother.Finish();
  EXPECT_LE(most_buffered, options.size + options.ContextFrames());
  EXPECT_EQ(smoother.buffered_frames(), 0);
  const std::vector<WindowSummary>& windows = smoother.windows();
  ASSERT_FALSE(windows.empty());
  EXPECT_EQ(windows.front().first, 0);
  EXPECT_EQ(windows.back().end, 41);
  for (size_t k = 0; k < windows.size(); ++k) {
    EXPECT_LE(windows[k].end - windows[k].first, options.size);
    if (k > 0) {
      EXPECT_EQ(windows[k].first, windows[k - 1].first + 5) << k;
    }
  }
  EXPECT_EQ(smoother.rig_from_objcentre().size(), 41u);
}

INSTANTIATE_TEST_SUITE_P(Models, WindowSmootherTest,
                         ::testing::Values(MotionModel::kConstantVelocity,
                                           MotionModel::kConstantAcceleration));

// A binocular sequence rendered once for the suite: the object centre moves on a straight line
// at v1 and the object spins at constant body angular velocity ω1 for frames 0..kStep−1, then
// at v2, ω2 (a step in velocity: the spin triples, the centre's path turns by ~80° and its
// speed doubles), image noise seeded per frame.
// The per-frame poses come from MultiViewTracker (annotation setting) started at the truth,
// with 200 edge lines per view (one per ~3.5 px of this scene's contours), the input the
// window's defaults and this suite's expectations were measured on. With the default of one
// line per contour pixel the per-frame jitter is 2.5× lower (0.0755 → 0.0305°, 0.0611 → 0.0270
// mm on frames 0..8) and the window lowers it 1.6–1.9× further (to 0.0189°, 0.0157 mm; with 200
// lines to 0.0300°, 0.0295 mm): what is left is less of the frame-to-frame noise a motion
// prior removes. WindowSequenceDefaultLinesTest runs on the default lines.
class WindowSequenceTest : public test::BunnyCasterTest {
 protected:
  static constexpr int kFrames = 18;
  static constexpr int kStep = 9;

  static void SetUpTestSuite() {
    EdgeLineOptions lines;
    lines.num_lines = 200;
    lines.line_spacing_px = 0.01;  // num_lines decides
    // The silhouette's lines alone: the test image shades the coarse bunny flat, facet by facet,
    // so next to the few facet edges sharp enough to pass as creases lie other facets' steps,
    // and this suite's least-squares edge stage (below) gives those lines their full weight.
    lines.crease_contours = false;
    SetUpSequence(lines);
  }

  static void SetUpSequence(const EdgeLineOptions& edge_lines) {
    test::BunnyCasterTest::SetUpTestSuite();
    const test::BinocularScene scene;
    // Centre velocity (rig frame, mm/frame) and body angular velocity (rad/frame).
    const Eigen::Vector3d v1(1.5, 0.5, 0.0), v2(-0.5, 3.0, 1.0);
    const Eigen::Vector3d omega1(0.010, 0.006, -0.004), omega2(0.030, 0.018, -0.012);
    truth_ = new std::vector<Eigen::Isometry3d>();
    Eigen::Isometry3d pose = scene.rig_from_objcentre;
    for (int t = 0; t < kFrames; ++t) {
      truth_->push_back(pose);
      const bool before_step = t + 1 < kStep;
      pose.linear() = pose.linear() * ExpSO3(before_step ? omega1 : omega2);
      pose.translation() += before_step ? v1 : v2;
    }
    std::vector<TrackedView> views = {{scene.camera0, scene.cam0_from_rig, 1.0},
                                      {scene.camera1, scene.cam1_from_rig, 1.0}};
    // Per-frame solves with a least-squares edge stage (no robust line loss), the input the
    // window's defaults and this suite's expectations were measured on. With the default
    // Cauchy line loss the per-frame poses switch between which lines they discount and the
    // window reduces their jitter by 1.8–2.1× instead of ≥ 2× (0.0767 → 0.0370°, 0.0517 →
    // 0.0279 mm; 0.0700 → 0.0351°, 0.0405 → 0.0227 mm), the mean error not raised.
    MultiViewTrackerOptions tracker_options;
    tracker_options.frame.edge.rounds = 2;
    tracker_options.frame.edge.redescending_rounds = 0;
    tracker_options.frame.edge.robust_loss = EdgeRobustLoss::kHuber;
    tracker_options.frame.edge.robust_scale = 1e6;
    tracker_options.frame.edge.lines = edge_lines;
    StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
        MultiViewTracker::Create(*caster_, views, tracker_options);
    BCOT_CHECK(tracker.ok());
    per_frame_ = new std::vector<Eigen::Isometry3d>();
    templates_ = new std::vector<std::vector<ViewLinearisation>>(kFrames);
    Eigen::Isometry3d estimate = truth_->front();
    for (int t = 0; t < kFrames; ++t) {
      const std::vector<cv::Mat3b> images = {
          test::RenderTestImage(*caster_, scene.camera0, scene.cam0_from_rig * (*truth_)[t],
                                100 + 2 * t, 8.0),
          test::RenderTestImage(*caster_, scene.camera1, scene.cam1_from_rig * (*truth_)[t],
                                101 + 2 * t, 8.0)};
      const StatusOr<FrameSummary> summary =
          t == 0 ? (*tracker)->Initialize(images, &estimate, &(*templates_)[t])
                 : (*tracker)->Track(images, &estimate, &(*templates_)[t]);
      BCOT_CHECK(summary.ok() && summary->usable());
      per_frame_->push_back(estimate);
    }
  }
  static void TearDownTestSuite() {
    delete truth_;
    delete per_frame_;
    delete templates_;
    test::BunnyCasterTest::TearDownTestSuite();
  }

  static std::vector<Eigen::Isometry3d> Smooth(const WindowProblemOptions& options) {
    WindowSmoother smoother(options);
    for (int t = 0; t < kFrames; ++t) smoother.Push((*per_frame_)[t], (*templates_)[t]);
    smoother.Finish();
    for (const WindowSummary& w : smoother.windows()) {
      EXPECT_TRUE(w.usable) << w.message;
      EXPECT_LE(w.final_cost, w.initial_cost);
    }
    return smoother.rig_from_objcentre();
  }

  // Windows of 8 frames, 3 shared: three windows over the sequence, one across the step; the
  // prior as configured by default.
  static WindowProblemOptions SlidingOptions() {
    WindowProblemOptions options;
    options.enabled = true;
    options.size = 8;
    options.overlap = 3;
    return options;
  }

  static inline std::vector<Eigen::Isometry3d>* truth_ = nullptr;
  static inline std::vector<Eigen::Isometry3d>* per_frame_ = nullptr;
  static inline std::vector<std::vector<ViewLinearisation>>* templates_ = nullptr;
};

// On the two constant-velocity stretches (frames 0..kStep−1 and kStep..kFrames−1, each with
// its own velocity) the window at least halves the jitter of the per-frame solves and does not
// raise their mean error. The mean error leaves out the kink frame kStep−1, which
// VelocityStepDoesNotLag judges: the robust prior still pulls it by a few hundredths of a mm
// (the Cauchy loss's pull on a large change fades as c²/r, never to 0, and the
// constant-acceleration translation prior sees the kink in three spans of four frames).
TEST_F(WindowSequenceTest, SlidingWindowHalvesJitterWithoutRaisingTheError) {
  const std::vector<Eigen::Isometry3d> smoothed = Smooth(SlidingOptions());
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // poses are rig_from_objcentre
  for (const auto& [first, end] : {std::pair{0, kStep}, std::pair{kStep, kFrames}}) {
    TrajectoryErrors before = CompareTrajectories(*per_frame_, *truth_, centre, first, end);
    TrajectoryErrors after = CompareTrajectories(smoothed, *truth_, centre, first, end);
    const int error_end = end == kStep ? kStep - 1 : end;
    const TrajectoryErrors before_error =
        CompareTrajectories(*per_frame_, *truth_, centre, first, error_end);
    const TrajectoryErrors after_error =
        CompareTrajectories(smoothed, *truth_, centre, first, error_end);
    before.rotation_deg = before_error.rotation_deg;
    before.translation_mm = before_error.translation_mm;
    after.rotation_deg = after_error.rotation_deg;
    after.translation_mm = after_error.translation_mm;
    std::printf(
        "frames [%d, %d): jitter per-frame %.4f deg %.4f mm -> window %.4f deg %.4f mm; "
        "mean error %.4f deg %.4f mm -> %.4f deg %.4f mm\n",
        first, end, before.jitter_rotation_deg, before.jitter_translation_mm,
        after.jitter_rotation_deg, after.jitter_translation_mm, before.rotation_deg,
        before.translation_mm.norm(), after.rotation_deg, after.translation_mm.norm());
    EXPECT_LT(after.jitter_rotation_deg, 0.5 * before.jitter_rotation_deg) << first;
    EXPECT_LT(after.jitter_translation_mm, 0.5 * before.jitter_translation_mm) << first;
    EXPECT_LE(after.rotation_deg, before.rotation_deg) << first;
    EXPECT_LE(after.translation_mm.norm(), before.translation_mm.norm()) << first;
  }
}

// No lag: over the frames around the velocity step (kStep−2 .. kStep+1; the kink is at
// kStep−1) the window's mean error is not worse than the per-frame mean error by more than
// 0.02° / 0.02 mm, and no single frame is worse by more than 0.05° / 0.05 mm (about half the
// per-frame mean error of this scene: single frames carry per-frame noise of that size).
TEST_F(WindowSequenceTest, VelocityStepDoesNotLag) {
  const std::vector<Eigen::Isometry3d> smoothed = Smooth(SlidingOptions());
  double before_deg = 0.0, before_mm = 0.0, after_deg = 0.0, after_mm = 0.0;
  for (int t = kStep - 2; t <= kStep + 1; ++t) {
    const double frame_before_deg = test::RotationErrorDeg((*per_frame_)[t], (*truth_)[t]);
    const double frame_before_mm = test::TranslationErrorMm((*per_frame_)[t], (*truth_)[t]);
    const double frame_after_deg = test::RotationErrorDeg(smoothed[t], (*truth_)[t]);
    const double frame_after_mm = test::TranslationErrorMm(smoothed[t], (*truth_)[t]);
    std::printf("frame %d: per-frame %.4f deg %.4f mm, window %.4f deg %.4f mm\n", t,
                frame_before_deg, frame_before_mm, frame_after_deg, frame_after_mm);
    EXPECT_LE(frame_after_deg, frame_before_deg + 0.05) << t;
    EXPECT_LE(frame_after_mm, frame_before_mm + 0.05) << t;
    before_deg += frame_before_deg / 4.0;
    before_mm += frame_before_mm / 4.0;
    after_deg += frame_after_deg / 4.0;
    after_mm += frame_after_mm / 4.0;
  }
  EXPECT_LE(after_deg, before_deg + 0.02);
  EXPECT_LE(after_mm, before_mm + 0.02);
}

class WindowSequenceDefaultLinesTest : public WindowSequenceTest {
 protected:
  static void SetUpTestSuite() { SetUpSequence(EdgeLineOptions()); }
};

// The edge posterior (the window's data term) is calibrated: its predicted standard deviation
// of translation and rotation (per axis, rms over the frames) is within a factor 4/3 of the
// per-frame errors' rms. Measured with 200 lines: 0.0229 mm vs 0.0220 mm, 0.0361° vs 0.0388°
// (with the default Cauchy line loss in the solve: 0.0230 mm vs 0.0238 mm, 0.0362° vs 0.0428°;
// counting the lines as independent instead of the per-view discount predicts about half).
// With the default one line per contour pixel: 0.0230 mm vs 0.0197 mm, 0.0363° vs 0.0421°
// (without the posterior's line-spacing weight 0.0168 mm and 0.0265°: overconfident).
void ExpectEdgePosteriorPredictsThePerFrameErrors(
    const std::vector<std::vector<ViewLinearisation>>& templates,
    const std::vector<Eigen::Isometry3d>& per_frame, const std::vector<Eigen::Isometry3d>& truth) {
  double predicted_t = 0.0, predicted_r = 0.0, actual_t = 0.0, actual_r = 0.0;
  int frames = 0;
  for (size_t t = 0; t < templates.size(); ++t) {
    const std::shared_ptr<const PoseGaussian>& posterior = templates[t][0].edge_posterior;
    ASSERT_NE(posterior, nullptr) << t;
    const Matrix6d covariance =
        (posterior->sqrt_information.transpose() * posterior->sqrt_information).inverse();
    predicted_t += covariance.topLeftCorner<3, 3>().trace() / 3.0;
    predicted_r += covariance.bottomRightCorner<3, 3>().trace() / 3.0;
    const Eigen::Isometry3d error = truth[t].inverse() * per_frame[t];
    const double angle = Eigen::AngleAxisd(error.linear()).angle();
    actual_t += error.translation().squaredNorm() / 3.0;
    actual_r += angle * angle / 3.0;
    ++frames;
  }
  const double ratio_t = std::sqrt(predicted_t / actual_t);
  const double ratio_r = std::sqrt(predicted_r / actual_r);
  std::printf("predicted / actual sd: translation %.4f / %.4f mm, rotation %.4f / %.4f deg\n",
              std::sqrt(predicted_t / frames), std::sqrt(actual_t / frames),
              std::sqrt(predicted_r / frames) * 180.0 / kPi,
              std::sqrt(actual_r / frames) * 180.0 / kPi);
  EXPECT_GT(ratio_t, 0.75);
  EXPECT_LT(ratio_t, 4.0 / 3.0);
  EXPECT_GT(ratio_r, 0.75);
  EXPECT_LT(ratio_r, 4.0 / 3.0);
}

TEST_F(WindowSequenceTest, EdgePosteriorPredictsThePerFrameErrors) {
  ExpectEdgePosteriorPredictsThePerFrameErrors(*templates_, *per_frame_, *truth_);
}

TEST_F(WindowSequenceDefaultLinesTest, EdgePosteriorPredictsThePerFrameErrors) {
  ExpectEdgePosteriorPredictsThePerFrameErrors(*templates_, *per_frame_, *truth_);
}

// With the default lines the window still lowers the per-frame jitter without raising the mean
// error (by 1.6–1.9×, see the fixture's comment; its ≥ 2× is judged on the 200-line input).
TEST_F(WindowSequenceDefaultLinesTest, WindowLowersJitterWithoutRaisingTheError) {
  const std::vector<Eigen::Isometry3d> smoothed = Smooth(SlidingOptions());
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& [first, end] : {std::pair{0, kStep - 1}, std::pair{kStep, kFrames}}) {
    const TrajectoryErrors before = CompareTrajectories(*per_frame_, *truth_, centre, first, end);
    const TrajectoryErrors after = CompareTrajectories(smoothed, *truth_, centre, first, end);
    std::printf("frames [%d, %d): jitter %.4f deg %.4f mm -> %.4f deg %.4f mm\n", first, end,
                before.jitter_rotation_deg, before.jitter_translation_mm, after.jitter_rotation_deg,
                after.jitter_translation_mm);
    EXPECT_LT(after.jitter_rotation_deg, before.jitter_rotation_deg) << first;
    EXPECT_LT(after.jitter_translation_mm, before.jitter_translation_mm) << first;
    EXPECT_LE(after.rotation_deg, before.rotation_deg) << first;
    EXPECT_LE(after.translation_mm.norm(), before.translation_mm.norm()) << first;
  }
}

}  // namespace
}  // namespace bcot
