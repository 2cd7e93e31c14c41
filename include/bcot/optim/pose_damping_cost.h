// Per-round damping of the pose update (a Tikhonov term, as region trackers regularise their
// Newton steps): keeps one Ceres solve on a fixed template close to the pose T0 the template
// was rendered at, where its linearisation (DESIGN.md "Rounds") is valid.
//
// Parameter block: T = rig_from_objcentre (7 ambient, Se3Manifold). With T0 = (R0, t0) fixed:
//
//   r = [ a_t · R0ᵀ (t − t0) ;  a_r · Log(R0ᵀ R) ]            (6 residuals)
//
// the object-centre displacement in O_o of T0 (mm) and the rotation about the object centre
// (rad), each scaled by a_t = √N/σ_t, a_r = √N/σ_r. ½|r|² = ½N(|Δt|²/σ_t² + |Δφ|²/σ_r²), so with
// N the number of region residuals the term keeps the same weight relative to the data energy
// at any resolution or stride. It is zero at T = T0, so it never moves the solution of a round
// that has converged (T0 = T): it only bounds the steps in directions the views observe poorly
// (depth in a monocular view), which otherwise run away on a wrong linearisation.
//
// Lie Jacobian (T ⊕ δ = T·Exp(δ), δ = (ρ, φ)): ∂r_t/∂ρ = a_t R0ᵀR, ∂r_t/∂φ = 0,
// ∂r_r/∂ρ = 0, ∂r_r/∂φ = a_r J_r⁻¹(θ) with θ = Log(R0ᵀR) and J_r⁻¹(θ) = J_l⁻¹(−θ).
#pragma once

#include <ceres/sized_cost_function.h>

#include <Eigen/Geometry>

namespace bcot {

class PoseDampingCost final : public ceres::SizedCostFunction<6, 7> {
 public:
  // `translation_scale` a_t (1/mm) and `rotation_scale` a_r (1/rad), both >= 0 (CHECKed).
  PoseDampingCost(const Eigen::Isometry3d& rig_from_objcentre_0, double translation_scale,
                  double rotation_scale);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Isometry3d rig_from_objcentre_0_;
  double translation_scale_;
  double rotation_scale_;
};

}  // namespace bcot
