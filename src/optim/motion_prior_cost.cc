#include "bcot/optim/motion_prior_cost.h"

#include <array>
#include <cmath>

#include "bcot/core/status.h"

namespace bcot {
namespace {

// Both priors are r = W · Σ_k c_k·v_k over the K − 1 steps between K consecutive poses X_k,
// with c = (1, −1) (constant velocity) or (1, −2, 1) (constant acceleration) and the per-step
// velocity v_k of `form`:
//   kSe3:        v_k = Log(X_k⁻¹·X_{k+1})                    (body twist, SE(3))
//   kDecoupled:  v_k = (centre_{k+1} − centre_k, Log(R_k⁻¹·R_{k+1}))  (rig-frame centre, body spin)
// Jacobians in the tangent δ_j of X_j ⊕ δ_j = X_j·Exp(δ_j): ∂v_k/∂δ_k = −J_l⁻¹(v_k) and
// ∂v_k/∂δ_{k+1} = J_r⁻¹(v_k) = J_l⁻¹(−v_k) (SE(3), or SO(3) for the spin); for the centre,
// ∂centre_j/∂ρ_j = R_j. So ∂r/∂δ_j = W·(c_{j−1}·∂v_{j−1}/∂δ_j + c_j·∂v_j/∂δ_j).
template <int K>
struct StepVelocities {
  std::array<Vector6d, K - 1> v;
};

template <int K>
StepVelocities<K> Velocities(const std::array<Eigen::Isometry3d, K>& poses, MotionPriorForm form) {
  StepVelocities<K> steps;
  for (int k = 0; k + 1 < K; ++k) {
    if (form == MotionPriorForm::kSe3) {
      steps.v[k] = LogSE3(poses[k].inverse() * poses[k + 1]);
    } else {
      steps.v[k].template head<3>() = poses[k + 1].translation() - poses[k].translation();
      steps.v[k].template tail<3>() =
          LogSO3(Eigen::Matrix3d(poses[k].linear().transpose() * poses[k + 1].linear()));
    }
  }
  return steps;
}

template <int K>
Vector6d Combine(const StepVelocities<K>& steps, const std::array<double, K - 1>& coefficients) {
  Vector6d sum = Vector6d::Zero();
  for (int k = 0; k + 1 < K; ++k) sum += coefficients[k] * steps.v[k];
  return sum;
}

// ∂v_k/∂δ_j for j = k (start of the step) or j = k + 1 (end of the step).
template <int K>
Matrix6d StepJacobian(const std::array<Eigen::Isometry3d, K>& poses, const StepVelocities<K>& steps,
                      MotionPriorForm form, int k, bool end) {
  const Vector6d& v = steps.v[k];
  if (form == MotionPriorForm::kSe3) {
    return end ? InverseLeftJacobianSE3(-v) : Matrix6d(-InverseLeftJacobianSE3(v));
  }
  Matrix6d jacobian = Matrix6d::Zero();
  const Eigen::Vector3d phi = v.tail<3>();
  if (end) {
    jacobian.topLeftCorner<3, 3>() = poses[k + 1].linear();
    jacobian.bottomRightCorner<3, 3>() = InverseLeftJacobianSO3(-phi);
  } else {
    jacobian.topLeftCorner<3, 3>() = -poses[k].linear();
    jacobian.bottomRightCorner<3, 3>() = -InverseLeftJacobianSO3(phi);
  }
  return jacobian;
}

// c of the prior on K poses: (1, −1) constant velocity, (1, −2, 1) constant acceleration.
template <int K>
std::array<double, K - 1> Coefficients() {
  if constexpr (K == 3) {
    return {1.0, -1.0};
  } else {
    return {1.0, -2.0, 1.0};
  }
}

}  // namespace

template <int kPoses>
MotionPriorCost<kPoses>::MotionPriorCost(const Vector6d& weights, MotionPriorForm form)
    : weights_(weights), form_(form) {
  for (int k = 0; k < 6; ++k) BCOT_CHECK(std::isfinite(weights_[k]) && weights_[k] >= 0.0);
}

template <int kPoses>
bool MotionPriorCost<kPoses>::Evaluate(double const* const* parameters, double* residuals,
                                       double** jacobians) const {
  const std::array<double, kPoses - 1> coefficients = Coefficients<kPoses>();
  std::array<Eigen::Isometry3d, kPoses> poses;
  for (int k = 0; k < kPoses; ++k) poses[k] = FromPoseParameters(parameters[k]);
  const StepVelocities<kPoses> steps = Velocities<kPoses>(poses, form_);
  Eigen::Map<Vector6d> residual(residuals);
  residual = weights_.cwiseProduct(Combine<kPoses>(steps, coefficients));
  if (jacobians == nullptr) return true;
  for (int j = 0; j < kPoses; ++j) {
    if (jacobians[j] == nullptr) continue;
    Matrix6d lie = Matrix6d::Zero();
    if (j > 0) lie += coefficients[j - 1] * StepJacobian<kPoses>(poses, steps, form_, j - 1, true);
    if (j + 1 < kPoses)
      lie += coefficients[j] * StepJacobian<kPoses>(poses, steps, form_, j, false);
    AmbientFromLieJacobian(weights_.asDiagonal() * lie, parameters[j], jacobians[j]);
  }
  return true;
}

template class MotionPriorCost<3>;
template class MotionPriorCost<4>;

Vector6d VelocityChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                        const Eigen::Isometry3d& c, MotionPriorForm form) {
  return Combine<3>(Velocities<3>({a, b, c}, form), Coefficients<3>());
}

Vector6d AccelerationChange(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                            const Eigen::Isometry3d& c, const Eigen::Isometry3d& d,
                            MotionPriorForm form) {
  return Combine<4>(Velocities<4>({a, b, c, d}, form), Coefficients<4>());
}

}  // namespace bcot
