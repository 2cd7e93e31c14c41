#include "bcot/optim/pose_damping_cost.h"

#include "bcot/core/se3.h"
#include "bcot/core/status.h"
#include "bcot/optim/se3_manifold.h"

namespace bcot {

PoseDampingCost::PoseDampingCost(const Eigen::Isometry3d& rig_from_objcentre_0,
                                 double translation_scale, double rotation_scale)
    : rig_from_objcentre_0_(rig_from_objcentre_0),
      translation_scale_(translation_scale),
      rotation_scale_(rotation_scale) {
  BCOT_CHECK(translation_scale >= 0.0 && rotation_scale >= 0.0);
}

bool PoseDampingCost::Evaluate(double const* const* parameters, double* residuals,
                               double** jacobians) const {
  const Eigen::Isometry3d rig_from_objcentre = FromPoseParameters(parameters[0]);
  const Eigen::Matrix3d rotation_0_transpose = rig_from_objcentre_0_.linear().transpose();
  const Eigen::Matrix3d relative_rotation = rotation_0_transpose * rig_from_objcentre.linear();
  // The log from quaternions stays exact near π, where the matrix route loses precision.
  const Eigen::Quaterniond relative_quaternion =
      Eigen::Quaterniond(rig_from_objcentre_0_.linear()).conjugate() *
      Eigen::Quaterniond(rig_from_objcentre.linear());
  const Eigen::Vector3d theta = LogSO3(relative_quaternion);
  Eigen::Map<Eigen::Matrix<double, 6, 1>> r(residuals);
  r.head<3>() = translation_scale_ * rotation_0_transpose *
                (rig_from_objcentre.translation() - rig_from_objcentre_0_.translation());
  r.tail<3>() = rotation_scale_ * theta;
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    Eigen::Matrix<double, Eigen::Dynamic, 6> lie_jacobian =
        Eigen::Matrix<double, Eigen::Dynamic, 6>::Zero(6, 6);
    lie_jacobian.block<3, 3>(0, 0) = translation_scale_ * relative_rotation;
    lie_jacobian.block<3, 3>(3, 3) = rotation_scale_ * InverseLeftJacobianSO3(-theta);
    AmbientFromLieJacobian(lie_jacobian, parameters[0], jacobians[0]);
  }
  return true;
}

}  // namespace bcot
