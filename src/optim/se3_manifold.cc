#include "bcot/optim/se3_manifold.h"

#include <Eigen/QR>

namespace bcot {
namespace {

using Matrix76 = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;
using Matrix67 = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;

Eigen::Quaterniond QuaternionOf(const double* x) {
  return Eigen::Quaterniond(x[3], x[0], x[1], x[2]);  // (w, x, y, z) constructor
}

// Q(q) with q ⊗ p = Q(q)·p, both quaternions in Eigen's coefficient order (x, y, z, w).
Eigen::Matrix4d LeftProductMatrix(const Eigen::Quaterniond& q) {
  Eigen::Matrix4d m;
  m << q.w(), -q.z(), q.y(), q.x(),  //
      q.z(), q.w(), -q.x(), q.y(),   //
      -q.y(), q.x(), q.w(), q.z(),   //
      -q.x(), -q.y(), -q.z(), q.w();
  return m;
}

}  // namespace

PoseParameters ToPoseParameters(const Eigen::Isometry3d& transform) {
  const Eigen::Quaterniond q(transform.linear());
  PoseParameters parameters;
  parameters << q.coeffs(), transform.translation();
  return parameters;
}

Eigen::Isometry3d FromPoseParameters(const double* parameters) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = QuaternionOf(parameters).normalized().toRotationMatrix();
  transform.translation() = Eigen::Vector3d(parameters[4], parameters[5], parameters[6]);
  return transform;
}

bool Se3Manifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Eigen::Quaterniond q = QuaternionOf(x).normalized();
  const Eigen::Map<const Eigen::Vector3d> t(x + 4);
  const Eigen::Map<const Eigen::Vector3d> rho(delta);
  const Eigen::Map<const Eigen::Vector3d> phi(delta + 3);
  // T·Exp(δ) = (R·Exp(φ), t + R·J_l(φ)·ρ).
  const Eigen::Quaterniond q_new = (q * Eigen::Quaterniond(ExpSO3(phi))).normalized();
  const Eigen::Vector3d t_new = t + q * (LeftJacobianSO3(phi) * rho);
  Eigen::Map<Eigen::Vector4d> q_out(x_plus_delta);
  Eigen::Map<Eigen::Vector3d> t_out(x_plus_delta + 4);
  q_out = q_new.coeffs();
  t_out = t_new;
  return true;
}

bool Se3Manifold::PlusJacobian(const double* x, double* jacobian) const {
  const Eigen::Quaterniond q = QuaternionOf(x);
  Eigen::Map<Matrix76> j(jacobian);
  j.setZero();
  // ∂q/∂φ = ½·Q(q)·[I₃; 0] since Exp(φ) ≈ (φ/2, 1); ∂t/∂ρ = R (J_l(0) = I).
  j.block<4, 3>(0, 3) = 0.5 * LeftProductMatrix(q).leftCols<3>();
  j.block<3, 3>(4, 0) = q.normalized().toRotationMatrix();
  return true;
}

bool Se3Manifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  const Eigen::Isometry3d x_from_y = FromPoseParameters(x).inverse() * FromPoseParameters(y);
  // Take the rotation log from the quaternions directly (exact near π, no matrix round trip).
  const Eigen::Quaterniond q_rel =
      QuaternionOf(x).normalized().conjugate() * QuaternionOf(y).normalized();
  const Eigen::Vector3d phi = LogSO3(q_rel);
  Eigen::Map<Eigen::Vector3d> rho_out(y_minus_x);
  Eigen::Map<Eigen::Vector3d> phi_out(y_minus_x + 3);
  rho_out = InverseLeftJacobianSO3(phi) * x_from_y.translation();
  phi_out = phi;
  return true;
}

bool Se3Manifold::MinusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<Matrix67> j(jacobian);
  j = TangentFromAmbientJacobian(x);
  return true;
}

Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize> TangentFromAmbientJacobian(
    const double* parameters) {
  const Eigen::Quaterniond q = QuaternionOf(parameters);
  const double norm2 = q.squaredNorm();
  Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize> j;
  j.setZero();
  // ∂φ/∂q = 2·[Q(q)ᵀ]₀:₃ / |q|², the left inverse of ½·Q(q)·[I; 0] (Q(q)ᵀQ(q) = |q|²·I);
  // ∂ρ/∂t = Rᵀ.
  j.block<3, 4>(3, 0) = (2.0 / norm2) * LeftProductMatrix(q).transpose().topRows<3>();
  j.block<3, 3>(0, 4) = q.normalized().toRotationMatrix().transpose();
  return j;
}

void AmbientFromLieJacobian(const Eigen::Matrix<double, Eigen::Dynamic, 6>& lie_jacobian,
                            const double* parameters, double* ambient_jacobian_row_major) {
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, kPoseAmbientSize, Eigen::RowMajor>> ambient(
      ambient_jacobian_row_major, lie_jacobian.rows(), kPoseAmbientSize);
  ambient = lie_jacobian * TangentFromAmbientJacobian(parameters);
}

Eigen::Matrix<double, 1, 6> ProjectionLieJacobian(
    const Eigen::RowVector2d& direction, const Eigen::Matrix<double, 2, 3>& d_pixel_d_point,
    const Eigen::Matrix3d& rotation, const Eigen::Vector3d& point_in_objcentre) {
  Eigen::Matrix<double, 1, 6> jacobian;
  const Eigen::RowVector3d d_rho = direction * d_pixel_d_point * rotation;
  jacobian << d_rho, -d_rho * Hat(point_in_objcentre);
  return jacobian;
}

bool EvaluatePoseResiduals(const ceres::CostFunction& cost, const double* pose_parameters,
                           std::vector<double>* residuals) {
  residuals->assign(cost.num_residuals(), 0.0);
  const double* parameters[] = {pose_parameters};
  return cost.Evaluate(parameters, residuals->data(), nullptr);
}

AxisLockedSe3Manifold::AxisLockedSe3Manifold(const RotationalSymmetry& symmetry) {
  // U: the last two columns of a Householder QR of a (orthonormal, orthogonal to a).
  const Eigen::HouseholderQR<Eigen::Vector3d> qr(symmetry.axis.normalized());
  const Eigen::Matrix3d q = qr.householderQ();
  basis_.setZero();
  basis_.topLeftCorner<3, 3>().setIdentity();
  basis_.bottomRightCorner<3, 2>() = q.rightCols<2>();
}

bool AxisLockedSe3Manifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Vector6d full_delta =
      basis_ * Eigen::Map<const Eigen::Matrix<double, kPoseTangentSize - 1, 1>>(delta);
  return full_.Plus(x, full_delta.data(), x_plus_delta);
}

bool AxisLockedSe3Manifold::PlusJacobian(const double* x, double* jacobian) const {
  Matrix76 full;
  full_.PlusJacobian(x, full.data());
  Eigen::Map<Eigen::Matrix<double, kPoseAmbientSize, kPoseTangentSize - 1, Eigen::RowMajor>> j(
      jacobian);
  j = full * basis_;
  return true;
}

bool AxisLockedSe3Manifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  Vector6d full_difference;
  full_.Minus(y, x, full_difference.data());
  Eigen::Map<Eigen::Matrix<double, kPoseTangentSize - 1, 1>> difference(y_minus_x);
  difference = basis_.transpose() * full_difference;
  return true;
}

bool AxisLockedSe3Manifold::MinusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, kPoseTangentSize - 1, kPoseAmbientSize, Eigen::RowMajor>> j(
      jacobian);
  j = basis_.transpose() * TangentFromAmbientJacobian(x);
  return true;
}

std::unique_ptr<ceres::Manifold> NewPoseManifold(
    const std::optional<RotationalSymmetry>& symmetry_in_objcentre) {
  if (symmetry_in_objcentre.has_value()) {
    return std::make_unique<AxisLockedSe3Manifold>(*symmetry_in_objcentre);
  }
  return std::make_unique<Se3Manifold>();
}

}  // namespace bcot
