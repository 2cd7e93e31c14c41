#include "bcot/core/se3.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace bcot {
namespace {

// Below this angle the closed forms lose digits to cancellation (1 − cos θ, θ − sin θ) and
// three-term Taylor series are used; their truncation error is O(θ⁶) < 1e-18.
constexpr double kSmallAngle = 1e-3;

// The coefficients of exp(φ^) = I + a·φ^ + b·φ^² and of the left Jacobian J = I + b·φ^ + c·φ^²
// with θ = |φ|: a = sin θ / θ, b = (1 − cos θ) / θ², c = (θ − sin θ) / θ³.
struct RodriguesCoefficients {
  double a, b, c;
};

RodriguesCoefficients RodriguesCoefficientsOf(const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  if (theta < kSmallAngle) {
    return {1.0 - theta2 / 6.0 * (1.0 - theta2 / 20.0),           // a
            0.5 - theta2 / 24.0 * (1.0 - theta2 / 30.0),          // b
            1.0 / 6.0 - theta2 / 120.0 * (1.0 - theta2 / 42.0)};  // c
  }
  const double sin_theta = std::sin(theta);
  return {sin_theta / theta,                        // a
          (1.0 - std::cos(theta)) / theta2,         // b
          (theta - sin_theta) / (theta2 * theta)};  // c
}

}  // namespace

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

Eigen::Vector3d Vee(const Eigen::Matrix3d& m) { return {m(2, 1), m(0, 2), m(1, 0)}; }

Eigen::Matrix4d HatSE3(const Vector6d& twist) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m.topLeftCorner<3, 3>() = Hat(twist.tail<3>());
  m.topRightCorner<3, 1>() = twist.head<3>();
  return m;
}

Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi) {
  const Eigen::Matrix3d phi_hat = Hat(phi);
  const RodriguesCoefficients k = RodriguesCoefficientsOf(phi);
  return Eigen::Matrix3d::Identity() + k.a * phi_hat + k.b * phi_hat * phi_hat;
}

Eigen::Vector3d LogSO3(const Eigen::Quaterniond& rotation) {
  Eigen::Quaterniond q = rotation.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // pick the angle in [0, π]
  const Eigen::Vector3d v = q.vec();
  const double sin_half = v.norm();
  if (sin_half < 1e-6) {
    // θ / sin(θ/2) = 2·atan(s/w)/s ≈ (2/w)·(1 − s²/(3w²)) with s = sin(θ/2).
    const double w = q.w();
    return (2.0 / w) * (1.0 - sin_half * sin_half / (3.0 * w * w)) * v;
  }
  const double theta = 2.0 * std::atan2(sin_half, q.w());
  return (theta / sin_half) * v;
}

Eigen::Vector3d LogSO3(const Eigen::Matrix3d& rotation) {
  return LogSO3(Eigen::Quaterniond(rotation));
}

Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& phi) {
  const Eigen::Matrix3d phi_hat = Hat(phi);
  const RodriguesCoefficients k = RodriguesCoefficientsOf(phi);
  return Eigen::Matrix3d::Identity() + k.b * phi_hat + k.c * phi_hat * phi_hat;
}

Eigen::Matrix3d InverseLeftJacobianSO3(const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  const Eigen::Matrix3d phi_hat = Hat(phi);
  double b;  // J⁻¹ = I − ½·φ^ + b·φ^²
  if (theta < kSmallAngle) {
    b = 1.0 / 12.0 + theta2 / 720.0 * (1.0 + theta2 / 42.0);
  } else {
    const double half = 0.5 * theta;
    b = (1.0 - half * std::cos(half) / std::sin(half)) / theta2;
  }
  return Eigen::Matrix3d::Identity() - 0.5 * phi_hat + b * phi_hat * phi_hat;
}

namespace {

// Q(ρ, φ), the top-right block of the SE(3) left Jacobian, summed from its series:
// J_l(ξ) = Σ_k ad_ξ^k / (k+1)! with ad_ξ = [[φ^, ρ^], [0, φ^]]. The top-right block of ad_ξ^k
// is Σ_{i+j=k−1} φ^^i·ρ^·φ^^j, built recursively as B_k = φ^·B_{k−1} + ρ^·φ^^{k−1}.
Eigen::Matrix3d SE3JacobianQ(const Vector6d& twist) {
  const Eigen::Matrix3d rho_hat = Hat(twist.head<3>());
  const Eigen::Matrix3d phi_hat = Hat(twist.tail<3>());
  Eigen::Matrix3d block = rho_hat;                          // B_1
  Eigen::Matrix3d phi_power = Eigen::Matrix3d::Identity();  // φ^^{k−1}
  Eigen::Matrix3d q = 0.5 * block;                          // B_1 / 2!
  double factorial = 2.0;
  for (int k = 2; k < 60; ++k) {
    phi_power = phi_power * phi_hat;
    block = phi_hat * block + rho_hat * phi_power;
    factorial *= (k + 1);
    const Eigen::Matrix3d term = block / factorial;
    q += term;
    if (term.cwiseAbs().maxCoeff() <= 1e-18 * (1.0 + q.cwiseAbs().maxCoeff())) break;
  }
  return q;
}

}  // namespace

Matrix6d LeftJacobianSE3(const Vector6d& twist) {
  const Eigen::Matrix3d j = LeftJacobianSO3(twist.tail<3>());
  Matrix6d result = Matrix6d::Zero();
  result.topLeftCorner<3, 3>() = j;
  result.bottomRightCorner<3, 3>() = j;
  result.topRightCorner<3, 3>() = SE3JacobianQ(twist);
  return result;
}

Matrix6d InverseLeftJacobianSE3(const Vector6d& twist) {
  const Eigen::Matrix3d j_inverse = InverseLeftJacobianSO3(twist.tail<3>());
  Matrix6d result = Matrix6d::Zero();
  result.topLeftCorner<3, 3>() = j_inverse;
  result.bottomRightCorner<3, 3>() = j_inverse;
  result.topRightCorner<3, 3>() = -j_inverse * SE3JacobianQ(twist) * j_inverse;
  return result;
}

Eigen::Isometry3d ExpSE3(const Vector6d& twist) {
  const Eigen::Vector3d rho = twist.head<3>();
  const Eigen::Vector3d phi = twist.tail<3>();
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = ExpSO3(phi);
  transform.translation() = LeftJacobianSO3(phi) * rho;
  return transform;
}

Vector6d LogSE3(const Eigen::Isometry3d& transform) {
  const Eigen::Vector3d phi = LogSO3(Eigen::Matrix3d(transform.linear()));
  Vector6d twist;
  twist.head<3>() = InverseLeftJacobianSO3(phi) * transform.translation();
  twist.tail<3>() = phi;
  return twist;
}

Matrix6d AdjointSE3(const Eigen::Isometry3d& transform) {
  const Eigen::Matrix3d r = transform.linear();
  Matrix6d adjoint = Matrix6d::Zero();
  adjoint.topLeftCorner<3, 3>() = r;
  adjoint.topRightCorner<3, 3>() = Hat(transform.translation()) * r;
  adjoint.bottomRightCorner<3, 3>() = r;
  return adjoint;
}

Eigen::Isometry3d InterpolateSE3(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s) {
  return a * ExpSE3(s * LogSE3(a.inverse() * b));
}

Eigen::Matrix3d InterpolateSO3(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double s) {
  return a * ExpSO3(s * LogSO3(Eigen::Matrix3d(a.transpose() * b)));
}

double RotationDistanceDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return LogSO3(Eigen::Matrix3d(a.transpose() * b)).norm() * 180.0 / kPi;
}

bool IsRotationMatrix(const Eigen::Matrix3d& rotation, double tolerance, std::string* why) {
  if (!rotation.allFinite()) {
    if (why) *why = "rotation has non-finite entries";
    return false;
  }
  const double deviation =
      (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (deviation > tolerance) {
    if (why)
      *why = fmt::format("rotation is not orthonormal: RᵀR deviates from I by {:.3g}", deviation);
    return false;
  }
  const double det = rotation.determinant();
  if (det < 0.0) {
    if (why) *why = fmt::format("rotation has determinant {:.3g} (a reflection)", det);
    return false;
  }
  return true;
}

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& matrix) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(matrix, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

Eigen::Isometry3d LookAtOrigin(const Eigen::Vector3d& position) {
  const Eigen::Vector3d forward = (-position).normalized();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (forward.cross(up).norm() < 1e-6) up = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d right = forward.cross(up).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Isometry3d world_from_cam = Eigen::Isometry3d::Identity();
  world_from_cam.linear().col(0) = right;
  world_from_cam.linear().col(1) = down;
  world_from_cam.linear().col(2) = forward;
  world_from_cam.translation() = position;
  return world_from_cam;
}

}  // namespace bcot
