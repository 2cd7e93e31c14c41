#include "bcot/eval/metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "bcot/core/se3.h"

namespace bcot {
namespace {

constexpr double kRadToDeg = 180.0 / kPi;

bool Passes(double error, double threshold) { return !(error > threshold); }

}  // namespace

double RotationErrorDeg(const Eigen::Matrix3d& estimated, const Eigen::Matrix3d& truth) {
  const double cosine = ((estimated.transpose() * truth).trace() - 1.0) / 2.0;
  return std::acos(std::clamp(cosine, -1.0, 1.0)) * kRadToDeg;
}

double TranslationErrorMm(const Eigen::Vector3d& estimated, const Eigen::Vector3d& truth) {
  return (estimated - truth).norm();
}

double AddErrorMm(const std::vector<Eigen::Vector3f>& points_in_object,
                  const Eigen::Isometry3d& estimated_cam_from_object,
                  const Eigen::Isometry3d& truth_cam_from_object) {
  BCOT_CHECK(!points_in_object.empty());
  // (R̂X + t̂) − (RX + t) = (R̂ − R)X + (t̂ − t).
  const Eigen::Matrix3d delta_rotation =
      estimated_cam_from_object.linear() - truth_cam_from_object.linear();
  const Eigen::Vector3d delta_translation =
      estimated_cam_from_object.translation() - truth_cam_from_object.translation();
  double sum = 0.0;
  for (const Eigen::Vector3f& point : points_in_object) {
    sum += (delta_rotation * point.cast<double>() + delta_translation).norm();
  }
  return sum / static_cast<double>(points_in_object.size());
}

FrameErrors ComputeFrameErrors(const std::vector<Eigen::Vector3f>& points_in_object,
                               const Eigen::Isometry3d& estimated_cam_from_object,
                               const Eigen::Isometry3d& truth_cam_from_object) {
  FrameErrors errors;
  errors.rotation_deg =
      RotationErrorDeg(estimated_cam_from_object.linear(), truth_cam_from_object.linear());
  errors.translation_mm = TranslationErrorMm(estimated_cam_from_object.translation(),
                                             truth_cam_from_object.translation());
  errors.add_mm = AddErrorMm(points_in_object, estimated_cam_from_object, truth_cam_from_object);
  return errors;
}

bool IsTrackingFailure(const FrameErrors& errors, double max_rotation_deg,
                       double max_translation_mm) {
  return !Passes(errors.rotation_deg, max_rotation_deg) ||
         !Passes(errors.translation_mm, max_translation_mm);
}

const OptionSchema<CurveOptions>& CurveOptionSchema() {
  static const OptionSchema<CurveOptions>* const schema = [] {
    auto* s = new OptionSchema<CurveOptions>();
    s->Add(
         "curve.max_fraction_of_d", [](auto& o) -> auto& { return o.max_fraction_of_d; }, "d",
         "ADD success curve from 0 to this fraction of the diameter d")
        .Range(LeftOpen(0, 10));
    s->Add(
         "curve.steps", [](auto& o) -> auto& { return o.steps; }, "",
         "intervals on the threshold axis")
        .Range(Closed(1, 100000));
    return s;
  }();
  return *schema;
}

Status CurveOptions::Validate() const { return CurveOptionSchema().Validate(*this, nullptr); }

MetricSummary Summarize(const std::vector<ScoredFrame>& frames, const CurveOptions& curve) {
  BCOT_CHECK(curve.Validate().ok());
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  MetricSummary summary;
  summary.num_frames = static_cast<int>(frames.size());
  summary.columns.fill(kNaN);
  for (int k = 0; k <= curve.steps; ++k) {
    summary.curve_thresholds_d.push_back(curve.max_fraction_of_d * k / curve.steps);
  }
  summary.curve_success_percent.assign(summary.curve_thresholds_d.size(), kNaN);
  summary.add_auc = kNaN;
  if (frames.empty()) return summary;

  std::array<int, kNumMetricColumns - 1> passed{};
  std::vector<int> curve_passed(summary.curve_thresholds_d.size(), 0);
  double time_sum = 0.0;
  int timed = 0;
  for (const ScoredFrame& frame : frames) {
    BCOT_CHECK(frame.diameter_mm > 0.0);
    const FrameErrors& e = frame.errors;
    const double d = frame.diameter_mm;
    const bool r5 = Passes(e.rotation_deg, 5.0), t5 = Passes(e.translation_mm, 50.0);
    const bool r2 = Passes(e.rotation_deg, 2.0), t2 = Passes(e.translation_mm, 20.0);
    const std::array<bool, kNumMetricColumns - 1> pass = {Passes(e.add_mm, 0.02 * d),
                                                          Passes(e.add_mm, 0.05 * d),
                                                          Passes(e.add_mm, 0.1 * d),
                                                          r5 && t5,
                                                          r5,
                                                          t5,
                                                          r2 && t2,
                                                          r2,
                                                          t2};
    for (size_t i = 0; i < pass.size(); ++i) passed[i] += pass[i] ? 1 : 0;
    for (size_t k = 0; k < curve_passed.size(); ++k) {
      curve_passed[k] += Passes(e.add_mm, summary.curve_thresholds_d[k] * d) ? 1 : 0;
    }
    if (frame.lost) ++summary.num_lost;
    if (std::isfinite(frame.time_ms)) {
      time_sum += frame.time_ms;
      ++timed;
    }
  }
  const double n = static_cast<double>(frames.size());
  for (size_t i = 0; i < passed.size(); ++i) summary.columns[i] = 100.0 * passed[i] / n;
  summary.columns[kNumMetricColumns - 1] = timed > 0 ? time_sum / timed : kNaN;
  // Trapezoidal rule on the uniform grid, divided by the axis length: the weights are ½ at
  // both ends and 1 inside, over `steps` intervals.
  double weighted = 0.0;
  for (size_t k = 0; k < curve_passed.size(); ++k) {
    summary.curve_success_percent[k] = 100.0 * curve_passed[k] / n;
    const bool end = k == 0 || k + 1 == curve_passed.size();
    weighted += (end ? 0.5 : 1.0) * summary.curve_success_percent[k];
  }
  summary.add_auc = weighted / curve.steps;
  return summary;
}

}  // namespace bcot
