// A Gaussian on one pose, for Ceres: the pose posterior of a frame's edge-alignment stage
// (frame_problem.h, EdgeRefineOptions) as the temporal window's data term for that frame
// (window_problem.h). With mean T̂ = (R̂, t̂) and information H (6×6, symmetric positive
// definite) in the tangent δ of T̂ ⊕ δ = T̂·Exp(δ) (Se3Manifold):
//
//   e = [ R̂ᵀ (t − t̂) ;  Log(R̂ᵀ R) ]        (centre displacement in O_o of T̂, mm; rotation, rad)
//   r = U e,   UᵀU = H (U upper triangular)   ½‖r‖² = ½ eᵀ H e
//
// e(T̂ ⊕ δ) = δ to first order, so H is the Gauss-Newton normal matrix JᵀJ of the whitened edge
// residuals at T̂ (their residuals are (n·(x − c) − μ)/σ_μ, so ½‖r‖² is the negative log
// likelihood of the same measurements to second order, in the same currency as the window's
// motion prior: both whitened Gaussians).
//
// Lie Jacobian (T ⊕ δ = T·Exp(δ), δ = (ρ, φ)), with θ = Log(R̂ᵀR):
//   ∂e/∂δ = [[R̂ᵀR, 0], [0, J_r⁻¹(θ)]],  J_r⁻¹(θ) = J_l⁻¹(−θ),   ∂r/∂δ = U·∂e/∂δ
// handed to Ceres through AmbientFromLieJacobian.
#pragma once

#include <ceres/sized_cost_function.h>

#include <Eigen/Geometry>

#include "bcot/core/se3.h"

namespace bcot {

// A pose posterior: its mean and the upper-triangular square root U of its information.
struct PoseGaussian {
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  Matrix6d sqrt_information = Matrix6d::Zero();
};

// The square root U (upper triangular, UᵀU = H) of an information matrix H; false when H is
// not symmetric positive definite (a direction the measurements do not observe).
bool SqrtInformation(const Matrix6d& information, Matrix6d* sqrt_information);

class PoseGaussianCost final : public ceres::SizedCostFunction<6, 7> {
 public:
  explicit PoseGaussianCost(const PoseGaussian& gaussian);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  PoseGaussian gaussian_;
};

}  // namespace bcot
