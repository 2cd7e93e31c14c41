// Pose-error metrics of the BCOT benchmark (paper §4.7, DESIGN.md "Release export and
// evaluation"): rotation / translation errors, ADD, the n°/n cm success rates, ADD success
// curves and their AUC, pooled over frames.
//
// All poses are cam_from_object (object = mesh template frame O_t), translations in mm.
//   rotation error    e(R) = acos(clamp((tr(R̂ᵀR) − 1) / 2, −1, 1)) in degrees (eq. 11);
//   translation error e(t) = ‖t̂ − t‖ in mm (eq. 10);
//   ADD               mean over all mesh vertices X of ‖(R̂X + t̂) − (RX + t)‖ in mm (eq. 12).
// A frame FAILS a threshold when its error is strictly greater than it, i.e. it passes with
// error <= threshold. Success rates are percentages of the pooled frames, in [0, 100].
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "bcot/core/option_schema.h"
#include "bcot/core/status.h"

namespace bcot {

// Rotation error in degrees, in [0, 180]. The acos argument is clamped, so rotations equal up
// to rounding (argument slightly above 1) give 0, never NaN.
double RotationErrorDeg(const Eigen::Matrix3d& estimated, const Eigen::Matrix3d& truth);
// ‖t̂ − t‖ in mm.
double TranslationErrorMm(const Eigen::Vector3d& estimated, const Eigen::Vector3d& truth);
// ADD (mm) over `points_in_object` (the mesh vertices, O_t, mm); CHECKs a non-empty list.
double AddErrorMm(const std::vector<Eigen::Vector3f>& points_in_object,
                  const Eigen::Isometry3d& estimated_cam_from_object,
                  const Eigen::Isometry3d& truth_cam_from_object);

// Errors of one scored frame.
struct FrameErrors {
  double rotation_deg = 0.0;
  double translation_mm = 0.0;
  double add_mm = 0.0;
};
FrameErrors ComputeFrameErrors(const std::vector<Eigen::Vector3f>& points_in_object,
                               const Eigen::Isometry3d& estimated_cam_from_object,
                               const Eigen::Isometry3d& truth_cam_from_object);

// The tracking-failure test of the protocol: rotation_deg > max_rotation_deg or
// translation_mm > max_translation_mm (5° / 50 mm in BCOT and RBOT).
bool IsTrackingFailure(const FrameErrors& errors, double max_rotation_deg,
                       double max_translation_mm);

// One scored frame as the aggregation sees it.
struct ScoredFrame {
  FrameErrors errors;
  double diameter_mm = 0.0;  // d of the frame's object: longest bounding-box side (mm), > 0
  double time_ms = 0.0;      // tracker time for the frame; NaN when unknown (offline mode)
  bool lost = false;         // failed the reset test (5°/5 cm)
};

// ADD success curve: success rate at thresholds τ_k = k/steps · max_fraction_of_d · d,
// k = 0..steps; AUC = trapezoidal ∫ success dτ / max_fraction_of_d, in [0, 100].
struct CurveOptions {
  double max_fraction_of_d = 0.1;  // upper end of the threshold axis, in units of d; (0, 10]
  int steps = 100;                 // intervals on the axis; [1, 100000]
  Status Validate() const;         // kInvalidConfig listing every violation
};

// The declaration of the options above: the `curve:` section of configs/eval.yaml.
const OptionSchema<CurveOptions>& CurveOptionSchema();

// The columns of the paper's Table 6, in order, with their headings.
inline constexpr int kNumMetricColumns = 10;
inline constexpr std::array<const char*, kNumMetricColumns> kMetricColumnNames = {
    "ADD-0.02d", "ADD-0.05d", "ADD-0.1d", "5°5cm", "5°", "5cm", "2°2cm", "2°", "2cm", "Time(ms)"};

struct MetricSummary {
  int num_frames = 0;  // pooled scored frames
  int num_lost = 0;    // frames that failed the reset test
  // Table 6 columns (kMetricColumnNames order): nine success rates in percent, then the mean
  // time per frame (ms; NaN when no frame has a time). All NaN when num_frames = 0.
  std::array<double, kNumMetricColumns> columns{};
  std::vector<double> curve_thresholds_d;     // τ_k / d
  std::vector<double> curve_success_percent;  // success rate at τ_k
  double add_auc = 0.0;                       // percent
};

// Pools `frames` (any mix of objects: ADD thresholds use each frame's own d).
MetricSummary Summarize(const std::vector<ScoredFrame>& frames, const CurveOptions& curve = {});

}  // namespace bcot
