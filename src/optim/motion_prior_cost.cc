#include "bcot/optim/motion_prior_cost.h"

#include <cmath>

#include "bcot/core/status.h"

namespace bcot {
namespace {

// Rotation part shared by both forms: φ₁ − φ₂ with φ₁ = Log(R_A⁻¹R_B), φ₂ = Log(R_B⁻¹R_C).
Eigen::Vector3d RotationChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                               const Eigen::Isometry3d& c, Eigen::Vector3d* phi1,
                               Eigen::Vector3d* phi2) {
  *phi1 = LogSO3(Eigen::Matrix3d(a.linear().transpose() * b.linear()));
  *phi2 = LogSO3(Eigen::Matrix3d(b.linear().transpose() * c.linear()));
  return *phi1 - *phi2;
}

}  // namespace

ConstantVelocityCost::ConstantVelocityCost(const Vector6d& weights, MotionPriorForm form)
    : weights_(weights), form_(form) {
  for (int k = 0; k < 6; ++k) BCOT_CHECK(std::isfinite(weights_[k]) && weights_[k] >= 0.0);
}

Vector6d VelocityChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                        const Eigen::Isometry3d& c, MotionPriorForm form) {
  if (form == MotionPriorForm::kSe3) return LogSE3(a.inverse() * b) - LogSE3(b.inverse() * c);
  Eigen::Vector3d phi1, phi2;
  Vector6d change;
  change.head<3>() = 2.0 * b.translation() - a.translation() - c.translation();
  change.tail<3>() = RotationChange(a, b, c, &phi1, &phi2);
  return change;
}

bool ConstantVelocityCost::Evaluate(double const* const* parameters, double* residuals,
                                    double** jacobians) const {
  const Eigen::Isometry3d a = FromPoseParameters(parameters[0]);
  const Eigen::Isometry3d b = FromPoseParameters(parameters[1]);
  const Eigen::Isometry3d c = FromPoseParameters(parameters[2]);
  Eigen::Map<Vector6d> residual(residuals);
  const auto w = weights_.asDiagonal();
  Matrix6d lie[3];
  if (form_ == MotionPriorForm::kSe3) {
    const Vector6d xi1 = LogSE3(a.inverse() * b);
    const Vector6d xi2 = LogSE3(b.inverse() * c);
    residual = weights_.cwiseProduct(xi1 - xi2);
    if (jacobians == nullptr) return true;
    lie[0] = -(w * InverseLeftJacobianSE3(xi1));
    lie[1] = w * (InverseLeftJacobianSE3(-xi1) + InverseLeftJacobianSE3(xi2));
    lie[2] = -(w * InverseLeftJacobianSE3(-xi2));
  } else {
    Eigen::Vector3d phi1, phi2;
    Vector6d change;
    change.head<3>() = 2.0 * b.translation() - a.translation() - c.translation();
    change.tail<3>() = RotationChange(a, b, c, &phi1, &phi2);
    residual = weights_.cwiseProduct(change);
    if (jacobians == nullptr) return true;
    for (Matrix6d& j : lie) j.setZero();
    lie[0].topLeftCorner<3, 3>() = -a.linear();
    lie[1].topLeftCorner<3, 3>() = 2.0 * b.linear();
    lie[2].topLeftCorner<3, 3>() = -c.linear();
    lie[0].bottomRightCorner<3, 3>() = -InverseLeftJacobianSO3(phi1);
    lie[1].bottomRightCorner<3, 3>() = InverseLeftJacobianSO3(-phi1) + InverseLeftJacobianSO3(phi2);
    lie[2].bottomRightCorner<3, 3>() = -InverseLeftJacobianSO3(-phi2);
    for (Matrix6d& j : lie) j = w * j;
  }
  for (int i = 0; i < 3; ++i) {
    if (jacobians[i] != nullptr) AmbientFromLieJacobian(lie[i], parameters[i], jacobians[i]);
  }
  return true;
}

}  // namespace bcot
