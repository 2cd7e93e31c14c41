#include "bcot/optim/pose_gaussian_cost.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "bcot/optim/se3_manifold.h"

namespace bcot {

bool SqrtInformation(const Matrix6d& information, Matrix6d* sqrt_information) {
  if (!information.allFinite()) return false;
  const Matrix6d symmetric = 0.5 * (information + information.transpose());
  const Eigen::LLT<Matrix6d> llt(symmetric);
  if (llt.info() != Eigen::Success) return false;
  const Matrix6d upper = llt.matrixU();
  for (int k = 0; k < 6; ++k) {
    if (!(upper(k, k) > 0.0)) return false;
  }
  *sqrt_information = upper;
  return true;
}

PoseGaussianCost::PoseGaussianCost(const PoseGaussian& gaussian) : gaussian_(gaussian) {}

bool PoseGaussianCost::Evaluate(double const* const* parameters, double* residuals,
                                double** jacobians) const {
  const Eigen::Isometry3d pose = FromPoseParameters(parameters[0]);
  const Eigen::Matrix3d mean_rotation_transpose = gaussian_.mean.linear().transpose();
  // The log from quaternions stays exact near π, where the matrix route loses precision.
  const Eigen::Quaterniond relative_quaternion =
      Eigen::Quaterniond(gaussian_.mean.linear()).conjugate() * Eigen::Quaterniond(pose.linear());
  const Eigen::Vector3d theta = LogSO3(relative_quaternion);
  Vector6d error;
  error.head<3>() = mean_rotation_transpose * (pose.translation() - gaussian_.mean.translation());
  error.tail<3>() = theta;
  Eigen::Map<Vector6d> r(residuals);
  r = gaussian_.sqrt_information * error;
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    Matrix6d error_jacobian = Matrix6d::Zero();
    error_jacobian.block<3, 3>(0, 0) = mean_rotation_transpose * pose.linear();
    error_jacobian.block<3, 3>(3, 3) = InverseLeftJacobianSO3(-theta);
    const Eigen::Matrix<double, Eigen::Dynamic, 6> lie_jacobian =
        gaussian_.sqrt_information * error_jacobian;
    AmbientFromLieJacobian(lie_jacobian, parameters[0], jacobians[0]);
  }
  return true;
}

}  // namespace bcot
