#include "bcot/eval/metrics.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "bcot/core/se3.h"
#include "benchmark_test_data.h"

namespace bcot {
namespace {

using test::MakeScoredFrame;

Eigen::Matrix3d RotZ(double deg) { return ExpSO3(Eigen::Vector3d(0, 0, deg * kPi / 180.0)); }

TEST(MetricsTest, RotationErrorIsTheRelativeAngleInDegrees) {
  EXPECT_EQ(RotationErrorDeg(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()), 0.0);
  EXPECT_NEAR(RotationErrorDeg(RotZ(30), Eigen::Matrix3d::Identity()), 30.0, 1e-9);
  EXPECT_NEAR(RotationErrorDeg(RotZ(10), RotZ(-15)), 25.0, 1e-9);
  // Symmetric, and 180° exactly: tr = −1.
  EXPECT_NEAR(RotationErrorDeg(Eigen::Matrix3d::Identity(), RotZ(180)), 180.0, 1e-6);
  const Eigen::Matrix3d a = ExpSO3(Eigen::Vector3d(0.1, -0.4, 0.3));
  const Eigen::Matrix3d b = ExpSO3(Eigen::Vector3d(-0.2, 0.1, 0.05));
  EXPECT_NEAR(RotationErrorDeg(a, b), RotationErrorDeg(b, a), 1e-12);
  EXPECT_NEAR(RotationErrorDeg(a, b), RotationDistanceDeg(a, b), 1e-7);
}

TEST(MetricsTest, AcosArgumentJustOutsideItsDomainIsClampedNotNaN) {
  Eigen::Matrix3d truth = Eigen::Matrix3d::Identity();
  truth(0, 0) = 1.0 + 4e-15;  // tr(R̂ᵀR) = 3 + 4e-15 → argument 1 + 2e-15
  const double zero = RotationErrorDeg(Eigen::Matrix3d::Identity(), truth);
  EXPECT_FALSE(std::isnan(zero));
  EXPECT_EQ(zero, 0.0);
  Eigen::Matrix3d flipped = Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  flipped(0, 0) = -1.0 - 4e-15;  // tr = −1 − 4e-15 → argument −1 − 2e-15
  const double half_turn = RotationErrorDeg(Eigen::Matrix3d::Identity(), flipped);
  EXPECT_FALSE(std::isnan(half_turn));
  EXPECT_DOUBLE_EQ(half_turn, 180.0);
}

TEST(MetricsTest, TranslationAndAddErrors) {
  EXPECT_EQ(TranslationErrorMm({3, 4, 0}, {0, 0, 0}), 5.0);
  EXPECT_EQ(TranslationErrorMm({1, 2, 3}, {1, 2, 3}), 0.0);
  const std::vector<Eigen::Vector3f> points = {{10, 0, 0}, {-10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translation() = Eigen::Vector3d(5, 5, 500);
  // Pure translation: every point moves by the same 2 mm.
  Eigen::Isometry3d shifted = truth;
  shifted.translation() += Eigen::Vector3d(0, 2, 0);
  EXPECT_NEAR(AddErrorMm(points, shifted, truth), 2.0, 1e-12);
  // 90° about the object z axis: the three points at 10 mm from the axis move by 10√2, the one
  // on the axis stays → ADD = 3·10√2 / 4.
  Eigen::Isometry3d turned = truth;
  turned.linear() = RotZ(90);
  EXPECT_NEAR(AddErrorMm(points, turned, truth), 3.0 * 10.0 * std::sqrt(2.0) / 4.0, 1e-9);
  const FrameErrors errors = ComputeFrameErrors(points, turned, truth);
  EXPECT_NEAR(errors.rotation_deg, 90.0, 1e-9);
  EXPECT_EQ(errors.translation_mm, 0.0);
}

TEST(MetricsTest, AFrameFailsOnlyWhenStrictlyGreater) {
  FrameErrors errors;
  errors.rotation_deg = 5.0;
  errors.translation_mm = 50.0;
  EXPECT_FALSE(IsTrackingFailure(errors, 5.0, 50.0));
  errors.translation_mm = std::nextafter(50.0, 100.0);
  EXPECT_TRUE(IsTrackingFailure(errors, 5.0, 50.0));
  errors.translation_mm = 0.0;
  errors.rotation_deg = 6.0;
  EXPECT_TRUE(IsTrackingFailure(errors, 5.0, 50.0));
}

TEST(MetricsTest, SummaryColumnsOnAHandComputedSet) {
  // d = 100 mm: ADD thresholds 2, 5, 10 mm.
  const std::vector<ScoredFrame> frames = {
      MakeScoredFrame(1.0, 10.0, 2.0, 4.0),   // passes everything (ADD = 0.02d exactly)
      MakeScoredFrame(3.0, 30.0, 5.0, 6.0),   // ADD-0.05d, 0.1d, 5°5cm, 5°, 5cm
      MakeScoredFrame(6.0, 15.0, 10.5),       // 5cm, 2cm (fails 5° → lost), ADD none; no time
      MakeScoredFrame(1.5, 60.0, 50.0, 8.0),  // 2°, 5°; lost (translation)
  };
  const MetricSummary s = Summarize(frames);
  EXPECT_EQ(s.num_frames, 4);
  EXPECT_EQ(s.num_lost, 2);
  const std::array<double, kNumMetricColumns> expected = {
      25.0,  // ADD-0.02d: frame 0
      50.0,  // ADD-0.05d: frames 0, 1
      50.0,  // ADD-0.1d: frames 0, 1 (10.5 > 10)
      50.0,  // 5°5cm: 0, 1
      75.0,  // 5°: 0, 1, 3
      75.0,  // 5cm: 0, 1, 2
      25.0,  // 2°2cm: 0
      50.0,  // 2°: 0, 3
      50.0,  // 2cm: 0, 2
      6.0};  // mean time over the 3 timed frames
  for (int i = 0; i < kNumMetricColumns; ++i) {
    EXPECT_DOUBLE_EQ(s.columns[i], expected[i]) << kMetricColumnNames[i];
  }
}

TEST(MetricsTest, SuccessCurveAndAuc) {
  CurveOptions curve;  // 0..0.1d in 100 steps
  // ADD = 0: success 100 at every threshold, AUC 100.
  MetricSummary s = Summarize({MakeScoredFrame(0, 0, 0.0)}, curve);
  ASSERT_EQ(s.curve_thresholds_d.size(), 101u);
  EXPECT_DOUBLE_EQ(s.curve_success_percent.front(), 100.0);
  EXPECT_DOUBLE_EQ(s.add_auc, 100.0);
  // ADD = 0.05d: 0 below τ = 0.05d, 100 from there; the trapezoid over the step [0.049, 0.05]
  // adds half a bin: AUC = (0.5·0.001 + 0.05)/0.1 · 100 = 50.5.
  s = Summarize({MakeScoredFrame(0, 0, 5.0)}, curve);
  EXPECT_DOUBLE_EQ(s.curve_success_percent[49], 0.0);
  EXPECT_DOUBLE_EQ(s.curve_success_percent[50], 100.0);
  EXPECT_NEAR(s.add_auc, 50.5, 1e-9);
  // Two frames, one never within 0.1d: half of that.
  s = Summarize({MakeScoredFrame(0, 0, 5.0), MakeScoredFrame(0, 0, 20.0)}, curve);
  EXPECT_NEAR(s.add_auc, 25.25, 1e-9);
  EXPECT_TRUE(std::isnan(s.columns[kNumMetricColumns - 1]));  // no times
}

TEST(MetricsTest, EmptySummaryIsAllUnknown) {
  const MetricSummary s = Summarize({});
  EXPECT_EQ(s.num_frames, 0);
  for (double value : s.columns) EXPECT_TRUE(std::isnan(value));
  EXPECT_TRUE(std::isnan(s.add_auc));
}

TEST(MetricsTest, CurveOptionsValidateListsEveryViolation) {
  CurveOptions curve;
  curve.max_fraction_of_d = 0.0;
  curve.steps = 0;
  test::ExpectErrorNaming(curve.Validate(), StatusCode::kInvalidConfig,
                          {"max_fraction_of_d = 0", "steps = 0"});
}

}  // namespace
}  // namespace bcot
