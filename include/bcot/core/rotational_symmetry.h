// A continuous rotational symmetry of a rigid object (a body of revolution: spool, cylinder,
// bottle), and the choice among the poses it makes equivalent.
//
// The object looks the same after any rotation S(θ) about its axis, the line {point + s·axis}
// in the object's frame F:
//   S(θ) = [Exp(θ·axis), point − Exp(θ·axis)·point]   (F_from_F),
// so the images constrain a pose x_from_F only up to x_from_F·S(θ). The angle θ about the axis
// is a direction no energy observes; a solver left to itself drifts along it, and constant-
// velocity prediction turns that drift into a spin. HoldAngle picks, among the equivalent
// poses, the one whose rotation is nearest to a reference (the previous frame's pose): θ* =
// argmin_θ angle(R·Exp(θ·a), R_ref). With M = R_refᵀ·R and a the unit axis,
//   trace(M·Exp(θ·a)) = aᵀMa + cos θ·(trace M − aᵀMa) + sin θ·trace(M·a^),
// and the rotation angle φ of R_refᵀ·R·Exp(θ·a) has trace = 1 + 2 cos φ, so the nearest pose is at
//   θ* = atan2(trace(M·a^), trace M − aᵀMa).
// docs/method.md, "Symmetric objects".
#pragma once

#include <Eigen/Geometry>

#include "bcot/core/se3.h"

namespace bcot {

struct RotationalSymmetry {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, in the object's frame F
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the axis, in F (mm)

  // S(θ) of the header (F_from_F).
  Eigen::Isometry3d Rotation(double angle_rad) const;
  // Its generator as a twist (ρ, φ) = (point × axis, axis): S(θ) = Exp(θ·Twist()) (se3.h), the
  // one direction of F's tangent that no image observes.
  Vector6d Twist() const;
  // The same symmetry in frame G: axis and point mapped by g_from_f.
  RotationalSymmetry Transformed(const Eigen::Isometry3d& g_from_f) const;
  // θ* of the header: the angle about the axis that brings x_from_f's rotation nearest to
  // reference_x_from_f's.
  double NearestAngle(const Eigen::Isometry3d& x_from_f,
                      const Eigen::Isometry3d& reference_x_from_f) const;
  // x_from_f·S(θ*): the pose equivalent to x_from_f whose rotation is nearest to the reference.
  Eigen::Isometry3d HoldAngle(const Eigen::Isometry3d& x_from_f,
                              const Eigen::Isometry3d& reference_x_from_f) const;
};

}  // namespace bcot
