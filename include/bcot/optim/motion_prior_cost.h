// Constant-velocity motion prior on three consecutive poses for Ceres (DESIGN.md "Temporal
// smoothing window"): three parameter blocks of size 7, A = T_{t−1}, B = T_t, C = T_{t+1}, each
// rig_from_objcentre ([qx, qy, qz, qw, tx, ty, tz], manifold Se3Manifold). Two forms:
//
// MotionPriorForm::kSe3 — constant body twist on SE(3):
//   ξ₁ = Log(A⁻¹·B),   ξ₂ = Log(B⁻¹·C)          (SE(3) twists (ρ, φ): ρ in mm, φ in rad)
//   r  = W · (ξ₁ − ξ₂),   W = diag(w_ρx, w_ρy, w_ρz, w_φx, w_φy, w_φz)
//
// ξ₁ is the motion from frame t−1 to t expressed in the object-centred frame O_o of frame t−1
// (the body twist per frame), ξ₂ the one from t to t+1; r = 0 exactly when the object moves with
// constant body velocity (a screw motion at constant speed, e.g. a constant spin about the
// object centre with constant straight translation along the spin axis). Its axes are the object
// axes: ρ = J_l(φ)⁻¹·(translation of A⁻¹B), mm along O_o's x, y, z; φ the rotation vector, rad.
// Units of W: w_ρ in 1/mm and w_φ in 1/rad, so r is dimensionless; ½‖r‖² is the negative log
// of a Gaussian on the per-frame change of velocity with standard deviations 1/w (σ_ρ mm,
// σ_φ rad per frame²) — the same currency as the region energy (a sum of −log likelihoods).
//
// Jacobians (analytic, in the tangents δ of X ⊕ δ = X·Exp(δ) of each block):
//   A·Exp(δa):  A⁻¹B → Exp(−δa)·A⁻¹B                     ∂ξ₁/∂δa = −J_l⁻¹(ξ₁)
//   B·Exp(δb):  A⁻¹B → A⁻¹B·Exp(δb),  B⁻¹C → Exp(−δb)·B⁻¹C
//                                        ∂ξ₁/∂δb = J_r⁻¹(ξ₁),  ∂ξ₂/∂δb = −J_l⁻¹(ξ₂)
//   C·Exp(δc):  B⁻¹C → B⁻¹C·Exp(δc)                       ∂ξ₂/∂δc = J_r⁻¹(ξ₂)
// so ∂r/∂δa = −W·J_l⁻¹(ξ₁), ∂r/∂δb = W·(J_r⁻¹(ξ₁) + J_l⁻¹(ξ₂)), ∂r/∂δc = −W·J_r⁻¹(ξ₂), with
// the SE(3) Jacobians of core/se3.h (J_r(ξ) = J_l(−ξ)), handed to Ceres through
// AmbientFromLieJacobian. Valid while each relative rotation is below π (consecutive frames).
//
// MotionPriorForm::kDecoupled — constant angular velocity (body frame) and constant velocity of
// the object centre (rig frame), independently (SO(3) × R³):
//   φ₁ = Log(R_A⁻¹·R_B),  φ₂ = Log(R_B⁻¹·R_C),   c_X = translation of X = centre in the rig, mm
//   r  = W · (c_B − c_A − (c_C − c_B),  φ₁ − φ₂)
// Why both: under kSe3 an object spinning at ω while its centre moves straight at speed v has
// r_ρ ≈ |ω|·|v| per frame (the straight path bends in the rotating body frame), e.g. 0.065 mm at
// 1.5°/frame and 2.5 mm/frame, more than the σ a jitter-removing prior needs; kDecoupled
// penalises only real changes of the centre's velocity, along rig axes (cam0: z = depth), which
// is also where per-axis weights mean most. Jacobians: with X·Exp(δ), ∂c_X/∂ρ = R_X, ∂c_X/∂φ = 0,
// and the SO(3) parts as above with J_l⁻¹(φ), J_r⁻¹(φ) of SO(3):
//   ∂r/∂δa = −W·[[R_A, 0], [0, J_l⁻¹(φ₁)]],  ∂r/∂δb = W·[[2R_B, 0], [0, J_r⁻¹(φ₁) + J_l⁻¹(φ₂)]],
//   ∂r/∂δc = −W·[[R_C, 0], [0, J_r⁻¹(φ₂)]].
//
// Thread safety: Evaluate is const; one instance may be evaluated concurrently.
#pragma once

#include <ceres/sized_cost_function.h>

#include "bcot/core/se3.h"
#include "bcot/optim/se3_manifold.h"

namespace bcot {

enum class MotionPriorForm {
  kSe3,        // W·(Log(A⁻¹B) − Log(B⁻¹C)) on SE(3)
  kDecoupled,  // W·(centre acceleration in the rig frame, body angular-velocity change)
};

class ConstantVelocityCost final
    : public ceres::SizedCostFunction<6, kPoseAmbientSize, kPoseAmbientSize, kPoseAmbientSize> {
 public:
  // `weights` = diag(W) as above: (w_ρx, w_ρy, w_ρz) in 1/mm, then (w_φx, w_φy, w_φz) in 1/rad;
  // each finite and >= 0 (CHECKed).
  // Translation weights act on the rig axes in kDecoupled, on the object axes in kSe3.
  explicit ConstantVelocityCost(const Vector6d& weights,
                                MotionPriorForm form = MotionPriorForm::kSe3);

  // parameters = {A, B, C}.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const Vector6d& weights() const { return weights_; }

 private:
  Vector6d weights_;
  MotionPriorForm form_;
};

// The unweighted residual of `form` (r / W): the change of velocity between the two steps.
Vector6d VelocityChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                        const Eigen::Isometry3d& c, MotionPriorForm form = MotionPriorForm::kSe3);

}  // namespace bcot
