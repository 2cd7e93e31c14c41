// The blurred-step model of one edge profile, the least-squares problem behind FitEdgeProfile
// (edge_lines.h, "fit"): samples p_i at offsets s_i along a line, parameters
// x = (a, g, b, μ, w, k), residuals
//
//   r_i(x) = a + g·u_i + b·Φ(z_i) + k·w·R(z_i) − p_i,   u_i = s_i − μ0,  z_i = (s_i − μ)/w,
//   R(z) = z·Φ(z) + φ(z)   (the Gaussian-blurred kink max(0, s − μ)/w),
//
// and their Jacobian, column by column (R' = Φ, φ' = −zφ):
//   ∂r/∂a = 1, ∂r/∂g = u, ∂r/∂b = Φ(z),
//   ∂r/∂μ = −b·φ(z)/w − k·Φ(z),   ∂r/∂w = −b·φ(z)·z/w + k·φ(z),   ∂r/∂k = w·R(z).
//
// Φ(z) and φ(z) come from one exponential: Φ(z) = ½·erfc(|z|/√2) for z <= 0, else 1 − that,
// with erfc(x) = t·(a1 + t·(a2 + t·(a3 + t·(a4 + t·a5))))·e^{−x²}, t = 1/(1 + p·x), x >= 0
// (Abramowitz & Stegun 7.1.26, |error| <= 1.5e-7, so |ΔΦ| <= 7.5e-8: far below a profile's
// noise), and e^{−x²} = e^{−z²/2} = √(2π)·φ(z).
//
// Evaluate returns the Gauss-Newton normal equations JᵀJ and Jᵀr with the residuals: the fit
// needs them at every Levenberg-Marquardt step (of some 4,000 lines per binocular frame), and
// they share Φ and φ with the residuals.
//
// Thread safety: an instance holds work arrays; one per thread.
#pragma once

#include <Eigen/Core>

namespace bcot {

constexpr int kEdgeStepParams = 6;
using EdgeStepParams = Eigen::Matrix<double, kEdgeStepParams, 1>;
using EdgeStepMatrix = Eigen::Matrix<double, kEdgeStepParams, kEdgeStepParams>;

class EdgeStepModel {
 public:
  // Samples `values` at `offsets` (same size, >= 1); `mu0` is the origin of the linear trend.
  EdgeStepModel(const Eigen::ArrayXd& offsets, double mu0, const Eigen::ArrayXd& values);

  int size() const { return static_cast<int>(s_.size()); }

  // The residual sum of squares Σ r_i² at x (x[4] = w > 0); when `jtj` and `jtr` are not null
  // (both or neither), also JᵀJ and Jᵀr at x.
  double Evaluate(const EdgeStepParams& x, EdgeStepMatrix* jtj, EdgeStepParams* jtr);

  // The residuals and their size()×6 Jacobian at x (tests).
  void ResidualsAndJacobian(const EdgeStepParams& x, Eigen::VectorXd* residuals,
                            Eigen::MatrixXd* jacobian);

 private:
  // z, gauss = e^{−z²/2}, cdf = Φ(z), pdf = φ(z) at (μ, w).
  void Basis(double mu, double w);

  Eigen::ArrayXd s_, u_, p_;
  // Work arrays of one evaluation, sized once, so that the fit's iterations allocate nothing.
  Eigen::ArrayXd z_, gauss_, t_, tail_, cdf_, pdf_, ramp_, residual_, step_slope_;
  Eigen::Matrix<double, Eigen::Dynamic, kEdgeStepParams> j_;  // the size()×6 Jacobian
};

}  // namespace bcot
