#include "bcot/optim/motion_prior_cost.h"

#include <cmath>

#include "bcot/core/status.h"

namespace bcot {

ConstantVelocityCost::ConstantVelocityCost(const Vector6d& weights) : weights_(weights) {
  for (int k = 0; k < 6; ++k) BCOT_CHECK(std::isfinite(weights_[k]) && weights_[k] >= 0.0);
}

Vector6d VelocityChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                        const Eigen::Isometry3d& c) {
  return LogSE3(a.inverse() * b) - LogSE3(b.inverse() * c);
}

bool ConstantVelocityCost::Evaluate(double const* const* parameters, double* residuals,
                                    double** jacobians) const {
  const Eigen::Isometry3d a = FromPoseParameters(parameters[0]);
  const Eigen::Isometry3d b = FromPoseParameters(parameters[1]);
  const Eigen::Isometry3d c = FromPoseParameters(parameters[2]);
  const Vector6d xi1 = LogSE3(a.inverse() * b);
  const Vector6d xi2 = LogSE3(b.inverse() * c);
  Eigen::Map<Vector6d> residual(residuals);
  residual = weights_.cwiseProduct(xi1 - xi2);
  if (jacobians == nullptr) return true;
  const auto w = weights_.asDiagonal();
  Eigen::Matrix<double, 6, 6> lie[3];
  lie[0] = -(w * InverseLeftJacobianSE3(xi1));
  lie[1] = w * (InverseLeftJacobianSE3(-xi1) + InverseLeftJacobianSE3(xi2));
  lie[2] = -(w * InverseLeftJacobianSE3(-xi2));
  for (int i = 0; i < 3; ++i) {
    if (jacobians[i] != nullptr) AmbientFromLieJacobian(lie[i], parameters[i], jacobians[i]);
  }
  return true;
}

}  // namespace bcot
