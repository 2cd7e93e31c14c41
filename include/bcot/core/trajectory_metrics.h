// Accuracy and smoothness of an estimated pose trajectory against ground truth (used by the
// temporal-window tests and scripts/bench_window.sh).
//
// For poses rig_from_object T_t = (R_t, t_t) and truth G_t over frames [first, end), with
// p_t = T_t·point (a fixed point of the object, e.g. its bounding-box centre, in the rig frame):
//   rotation error      mean_t angle(R_t·R_gtᵀ), deg
//   translation error   mean_t |p_t − p_gt,t| per rig axis (x, y, z), mm
//   acceleration        a_t = (Log(R_{t+1}·R_tᵀ) − Log(R_t·R_{t−1}ᵀ),  p_{t+1} − 2·p_t + p_{t−1}):
//                       the change of rig-frame angular velocity (rad/frame²) and of the point's
//                       velocity (mm/frame²) between consecutive frame steps
//   jitter              mean over t with t−1, t+1 in the range of ‖a_t − a_gt,t‖, split into
//                       rotation (deg/frame²) and translation (mm/frame²)
// Jitter is 0 for any trajectory whose frame-to-frame motion changes exactly as the truth's
// (a constant offset is not jitter), and grows with frame-to-frame noise.
#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace bcot {

struct TrajectoryErrors {
  int frames = 0;
  double rotation_deg = 0.0;
  Eigen::Vector3d translation_mm = Eigen::Vector3d::Zero();  // per rig axis
  double jitter_rotation_deg = 0.0;
  double jitter_translation_mm = 0.0;
};

// CHECKs equal sizes and 0 <= first < end <= size.
TrajectoryErrors CompareTrajectories(const std::vector<Eigen::Isometry3d>& rig_from_object,
                                     const std::vector<Eigen::Isometry3d>& truth,
                                     const Eigen::Vector3d& point_in_object, int first, int end);

}  // namespace bcot
