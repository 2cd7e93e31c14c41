#include "bcot/core/rotational_symmetry.h"

#include <cmath>

namespace bcot {

Eigen::Isometry3d RotationalSymmetry::Rotation(double angle_rad) const {
  Eigen::Isometry3d rotation = Eigen::Isometry3d::Identity();
  rotation.linear() = ExpSO3(angle_rad * axis);
  rotation.translation() = point - rotation.linear() * point;
  return rotation;
}

Vector6d RotationalSymmetry::Twist() const {
  Vector6d twist;
  twist << point.cross(axis), axis;
  return twist;
}

RotationalSymmetry RotationalSymmetry::Transformed(const Eigen::Isometry3d& g_from_f) const {
  return {(g_from_f.linear() * axis).normalized(), g_from_f * point};
}

double RotationalSymmetry::NearestAngle(const Eigen::Isometry3d& x_from_f,
                                        const Eigen::Isometry3d& reference_x_from_f) const {
  const Eigen::Matrix3d m = reference_x_from_f.linear().transpose() * x_from_f.linear();
  const double along = axis.dot(m * axis);
  // trace(M·a^) = Σ_ij M_ij·(a^)_ji.
  const double sine = (m * Hat(axis)).trace();
  const double cosine = m.trace() - along;
  if (sine == 0.0 && cosine == 0.0) return 0.0;  // every angle is as near
  return std::atan2(sine, cosine);
}

Eigen::Isometry3d RotationalSymmetry::HoldAngle(const Eigen::Isometry3d& x_from_f,
                                                const Eigen::Isometry3d& reference_x_from_f) const {
  return x_from_f * Rotation(NearestAngle(x_from_f, reference_x_from_f));
}

}  // namespace bcot
