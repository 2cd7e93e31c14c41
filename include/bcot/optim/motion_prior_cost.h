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
// ConstantAccelerationCost — the same on four consecutive poses A, B, C, D (T_{t−1} … T_{t+2}):
// with the per-step velocities v₁ (A→B), v₂ (B→C), v₃ (C→D) of either form (ξ of kSe3, or the
// centre step in the rig and the body rotation vector φ of kDecoupled),
//   r = W · (v₁ − 2v₂ + v₃)          (the change of acceleration per frame, "jerk")
// zero on constant acceleration, e.g. kDecoupled: the centre on c_t = c₀ + v·t + ½a·t² and a
// spin whose body angular velocity changes by the same rotation vector every frame. Why: a hand
// accelerates smoothly; on the handheld bench the true change of the centre's velocity between
// frames is 0.15–0.5 mm/frame² (median; p90 up to 0.5), 2–7× the acceleration noise of the
// per-frame solves, so a constant-velocity prior tight enough to remove that noise bends the
// real motion; the true change of acceleration is 3–7× smaller (median 0.02–0.06 mm/frame³),
// while per-frame noise is amplified more by the third difference (variance 20σ² vs 6σ²).
// Jacobians: as above with ∂v_k/∂δ at the start of step k = −J_l⁻¹(v_k) (kSe3 / SO(3) part) or
// −R (centre), and at its end J_r⁻¹(v_k) or R:
//   ∂r/∂δa = W·(−J_l⁻¹(v₁)),              ∂r/∂δb = W·(J_r⁻¹(v₁) + 2J_l⁻¹(v₂)),
//   ∂r/∂δc = W·(−2J_r⁻¹(v₂) − J_l⁻¹(v₃)), ∂r/∂δd = W·J_r⁻¹(v₃),
// with the centre blocks −R_A, 3R_B, −3R_C, R_D in kDecoupled.
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

// The SizedCostFunction of a prior on kPoses consecutive poses (3 or 4).
template <int kPoses>
struct MotionPriorCostBase;
template <>
struct MotionPriorCostBase<3> {
  using type = ceres::SizedCostFunction<6, kPoseAmbientSize, kPoseAmbientSize, kPoseAmbientSize>;
};
template <>
struct MotionPriorCostBase<4> {
  using type = ceres::SizedCostFunction<6, kPoseAmbientSize, kPoseAmbientSize, kPoseAmbientSize,
                                        kPoseAmbientSize>;
};

// ConstantVelocityCost (kPoses = 3) and ConstantAccelerationCost (kPoses = 4).
template <int kPoses>
class MotionPriorCost final : public MotionPriorCostBase<kPoses>::type {
 public:
  // `weights` = diag(W) as above: (w_ρx, w_ρy, w_ρz) in 1/mm, then (w_φx, w_φy, w_φz) in 1/rad;
  // each finite and >= 0 (CHECKed).
  // Translation weights act on the rig axes in kDecoupled, on the object axes in kSe3.
  explicit MotionPriorCost(const Vector6d& weights, MotionPriorForm form = MotionPriorForm::kSe3);

  // parameters = the kPoses consecutive poses {A, B, C(, D)}.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const Vector6d& weights() const { return weights_; }

 private:
  Vector6d weights_;
  MotionPriorForm form_;
};

extern template class MotionPriorCost<3>;
extern template class MotionPriorCost<4>;
using ConstantVelocityCost = MotionPriorCost<3>;
using ConstantAccelerationCost = MotionPriorCost<4>;

// The unweighted residual of ConstantVelocityCost (r / W): the change of velocity between the
// two steps.
Vector6d VelocityChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                        const Eigen::Isometry3d& c, MotionPriorForm form = MotionPriorForm::kSe3);

// The unweighted residual of ConstantAccelerationCost: v₁ − 2v₂ + v₃.
Vector6d AccelerationChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                            const Eigen::Isometry3d& c, const Eigen::Isometry3d& d,
                            MotionPriorForm form = MotionPriorForm::kSe3);

}  // namespace bcot
