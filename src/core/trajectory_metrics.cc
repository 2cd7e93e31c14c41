#include "bcot/core/trajectory_metrics.h"

#include "bcot/core/se3.h"
#include "bcot/core/status.h"

namespace bcot {
namespace {

constexpr double kDegPerRad = 180.0 / kPi;

using Vector6d = Eigen::Matrix<double, 6, 1>;

// (rotation, translation) acceleration at frame t, see the header.
Vector6d Acceleration(const std::vector<Eigen::Isometry3d>& poses, const Eigen::Vector3d& point,
                      int t) {
  Vector6d a;
  a.head<3>() = LogSO3(Eigen::Matrix3d(poses[t + 1].linear() * poses[t].linear().transpose())) -
                LogSO3(Eigen::Matrix3d(poses[t].linear() * poses[t - 1].linear().transpose()));
  a.tail<3>() = poses[t + 1] * point - 2.0 * (poses[t] * point) + poses[t - 1] * point;
  return a;
}

}  // namespace

TrajectoryErrors CompareTrajectories(const std::vector<Eigen::Isometry3d>& rig_from_object,
                                     const std::vector<Eigen::Isometry3d>& truth,
                                     const Eigen::Vector3d& point_in_object, int first, int end) {
  BCOT_CHECK(rig_from_object.size() == truth.size());
  BCOT_CHECK(0 <= first && first < end && end <= static_cast<int>(truth.size()));
  TrajectoryErrors errors;
  errors.frames = end - first;
  for (int t = first; t < end; ++t) {
    errors.rotation_deg += RotationDistanceDeg(rig_from_object[t].linear(), truth[t].linear());
    errors.translation_mm +=
        (rig_from_object[t] * point_in_object - truth[t] * point_in_object).cwiseAbs();
  }
  errors.rotation_deg /= errors.frames;
  errors.translation_mm /= errors.frames;
  int count = 0;
  for (int t = first + 1; t + 1 < end; ++t) {
    const Vector6d e =
        Acceleration(rig_from_object, point_in_object, t) - Acceleration(truth, point_in_object, t);
    errors.jitter_rotation_deg += e.head<3>().norm() * kDegPerRad;
    errors.jitter_translation_mm += e.tail<3>().norm();
    ++count;
  }
  if (count > 0) {
    errors.jitter_rotation_deg /= count;
    errors.jitter_translation_mm /= count;
  }
  return errors;
}

}  // namespace bcot
