// The pose parameter block of every bcot problem and its Lie-group manifold.
//
// Ambient parameters (7): [qx, qy, qz, qw, tx, ty, tz] = rig_from_objcentre, the rotation as a
// unit quaternion (Eigen's coefficient order) and the translation in mm. The tangent (6) is a
// twist δ = (ρ, φ) in the object-centred frame O_o (DESIGN.md, "Update in O_o"; paper eq. 4,
// S.12–19):
//
//   Plus:  T ⊕ δ = T · Exp(δ)          Minus: y ⊖ x = Log(T_x⁻¹ · T_y)
//
// so one increment is shared by every view and rotation acts about the object centre.
// PlusJacobian is ∂(T ⊕ δ)/∂δ at δ = 0 (7×6) and MinusJacobian its left inverse (6×7).
// A cost function that knows ∂r/∂δ (its "Lie Jacobian") hands Ceres the ambient Jacobian
// ∂r/∂δ · MinusJacobian(x); Ceres multiplies by PlusJacobian(x) and recovers exactly ∂r/∂δ
// (see AmbientFromLieJacobian).
#pragma once

#include <ceres/cost_function.h>
#include <ceres/manifold.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "bcot/core/rotational_symmetry.h"
#include "bcot/core/se3.h"

namespace bcot {

constexpr int kPoseAmbientSize = 7;
constexpr int kPoseTangentSize = 6;

using PoseParameters = Eigen::Matrix<double, kPoseAmbientSize, 1>;

// Conversions between an isometry and the 7 ambient parameters.
PoseParameters ToPoseParameters(const Eigen::Isometry3d& transform);
Eigen::Isometry3d FromPoseParameters(const double* parameters);

// MinusJacobian of the manifold at `parameters`: the 6×7 left inverse of PlusJacobian.
Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize> TangentFromAmbientJacobian(
    const double* parameters);

// Ambient Jacobian (rows × 7, row-major as Ceres stores it) of a residual whose derivative
// with respect to the tangent δ is `lie_jacobian` (rows × 6).
void AmbientFromLieJacobian(const Eigen::Matrix<double, Eigen::Dynamic, 6>& lie_jacobian,
                            const double* parameters, double* ambient_jacobian_row_major);

// Lie Jacobian (1×6) of aᵀ·π(X_c), the projection π of a model point X (in O_o) read along the
// image direction a, X_c = cam_from_objcentre·Exp(δ)·X (DESIGN.md S.19):
//   ∂(aᵀπ)/∂δ = aᵀ·∂π/∂X_c·R_c·[I | −X^]
// `d_pixel_d_point` = ∂π/∂X_c (Camera::Project), `rotation` = R_c of cam_from_objcentre.
Eigen::Matrix<double, 1, 6> ProjectionLieJacobian(
    const Eigen::RowVector2d& direction, const Eigen::Matrix<double, 2, 3>& d_pixel_d_point,
    const Eigen::Matrix3d& rotation, const Eigen::Vector3d& point_in_objcentre);

// The residuals of a cost function on one pose block at `pose_parameters` (no Jacobians); false
// when the evaluation fails.
bool EvaluatePoseResiduals(const ceres::CostFunction& cost, const double* pose_parameters,
                           std::vector<double>* residuals);

class Se3Manifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseAmbientSize; }
  int TangentSize() const override { return kPoseTangentSize; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

// Se3Manifold without turns about the axis of a body of revolution (core/rotational_symmetry.h).
// Its twist ξ = (p × a, a) is the direction no image observes; the tangent here is the
// complement of ξ that keeps the rotation part perpendicular to the axis a (in O_o):
//
//   Plus:  T ⊕ δ = T · Exp(B·δ),  B = [[I₃, 0], [0, U]]   Minus: y ⊖ x = Bᵀ·Log(T_x⁻¹ · T_y)
//
// with U (3×2) an orthonormal basis of a's orthogonal plane. Every twist splits uniquely as
// (φ·a)·ξ + B·δ, so each observable change of pose is still one step, and no step turns the
// object about its axis: the angle about it stays where tracking started (the gauge of a
// symmetric object; docs/method.md, "Symmetric objects"). (The complement orthogonal to ξ
// itself would not do: with ξ's translation part p × a in mm, translating the object along it
// costs a turn about the axis of up to 1/(2|p × a|) rad per mm, and a moving object spins.)
// Cost functions keep handing Ceres ∂r/∂δ₆·MinusJacobian₆ (AmbientFromLieJacobian); with
// PlusJacobian = PlusJacobian₆·B Ceres recovers ∂r/∂δ₆·B.
class AxisLockedSe3Manifold final : public ceres::Manifold {
 public:
  // `symmetry` in O_o (the frame of the pose's tangent); only its axis direction is used.
  explicit AxisLockedSe3Manifold(const RotationalSymmetry& symmetry);
  int AmbientSize() const override { return kPoseAmbientSize; }
  int TangentSize() const override { return kPoseTangentSize - 1; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;

 private:
  Se3Manifold full_;
  Eigen::Matrix<double, kPoseTangentSize, kPoseTangentSize - 1> basis_;  // B
};

// The pose manifold of a problem: AxisLockedSe3Manifold for an object with a rotational
// symmetry (in O_o), else Se3Manifold.
std::unique_ptr<ceres::Manifold> NewPoseManifold(
    const std::optional<RotationalSymmetry>& symmetry_in_objcentre);

}  // namespace bcot
