#include "bcot/optim/edge_step_model.h"

#include <cassert>
#include <cmath>

namespace bcot {

namespace {

constexpr double kInvSqrt2 = 0.70710678118654752440;
constexpr double kInvSqrt2Pi = 0.39894228040143267794;

}  // namespace

EdgeStepModel::EdgeStepModel(const Eigen::ArrayXd& offsets, double mu0,
                             const Eigen::ArrayXd& values)
    : s_(offsets), u_(offsets - mu0), p_(values) {
  assert(offsets.size() == values.size() && offsets.size() >= 1);
  const Eigen::Index m = s_.size();
  z_.resize(m);
  gauss_.resize(m);
  t_.resize(m);
  tail_.resize(m);
  cdf_.resize(m);
  pdf_.resize(m);
  ramp_.resize(m);
  residual_.resize(m);
  step_slope_.resize(m);
  j_.resize(m, kEdgeStepParams);
  j_.col(0).setOnes();
  j_.col(1) = u_.matrix();
}

void EdgeStepModel::Basis(double mu, double w) {
  // Abramowitz & Stegun 7.1.26 (header).
  constexpr double kP = 0.3275911;
  constexpr double kA1 = 0.254829592, kA2 = -0.284496736, kA3 = 1.421413741;
  constexpr double kA4 = -1.453152027, kA5 = 1.061405429;
  // Array expressions over all samples, so that the exponentials are vectorised.
  z_ = (s_ - mu) * (1.0 / w);
  gauss_ = (-0.5 * z_.square()).exp();
  t_ = (1.0 + (kP * kInvSqrt2) * z_.abs()).inverse();
  tail_ = 0.5 * t_ * (kA1 + t_ * (kA2 + t_ * (kA3 + t_ * (kA4 + t_ * kA5)))) *
          gauss_;  // ½·erfc(|z|/√2)
  cdf_ = (z_ <= 0.0).select(tail_, 1.0 - tail_);
  pdf_ = kInvSqrt2Pi * gauss_;
}

double EdgeStepModel::Evaluate(const EdgeStepParams& x, EdgeStepMatrix* jtj, EdgeStepParams* jtr) {
  assert((jtj == nullptr) == (jtr == nullptr));
  const double w = x[4];
  const double inv_w = 1.0 / w;
  Basis(x[3], w);
  ramp_ = z_ * cdf_ + pdf_;
  residual_ = x[0] + x[1] * u_ + x[2] * cdf_ + (x[5] * w) * ramp_ - p_;
  if (jtj != nullptr) {
    // J's columns of a (ones) and g (u) are constant, set in the constructor.
    step_slope_ = (x[2] * inv_w) * pdf_;  // b·φ(z)/w
    j_.col(2) = cdf_.matrix();
    j_.col(3) = (-step_slope_ - x[5] * cdf_).matrix();
    j_.col(4) = (-step_slope_ * z_ + x[5] * pdf_).matrix();
    j_.col(5) = (w * ramp_).matrix();
    jtj->noalias() = j_.transpose().lazyProduct(j_);
    jtr->noalias() = j_.transpose().lazyProduct(residual_.matrix());
  }
  return residual_.square().sum();
}

void EdgeStepModel::ResidualsAndJacobian(const EdgeStepParams& x, Eigen::VectorXd* residuals,
                                         Eigen::MatrixXd* jacobian) {
  EdgeStepMatrix unused_jtj;
  EdgeStepParams unused_jtr;
  Evaluate(x, &unused_jtj, &unused_jtr);
  *residuals = residual_.matrix();
  *jacobian = j_;
}

}  // namespace bcot
