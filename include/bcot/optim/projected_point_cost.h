// The evaluation loop shared by the image cost functions: residual i depends on the pose only
// through the projection of one model point X_i (in O_o),
//
//   r_i = f_i(π_i),   π_i = π(cam_from_rig · T · X_i),
//
// so its Lie Jacobian is ∂r_i/∂δ = (∂f_i/∂π)·∂π/∂X_c·R_c·[I | −X^] (DESIGN.md S.19). Each cost
// function supplies X_i and f_i with its derivative; the projection, the depth check and the
// chain rule to the ambient parameters are done here once.
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/optim/se3_manifold.h"

namespace bcot {

// Model points closer to the camera plane than this (mm) make an evaluation fail.
constexpr double kMinProjectedDepthMm = 1e-6;

// Evaluates `count` residuals at parameters[0] (Ceres's CostFunction::Evaluate contract).
//   point_of(i) -> const Eigen::Vector3d&: X_i in O_o;
//   residual_at(i, π_i, Eigen::RowVector2d* d_residual_d_pixel) -> double: r_i, and ∂r_i/∂π
//     when the pointer is not null.
// False when a point lies behind the camera.
template <typename PointOf, typename ResidualAt>
bool EvaluateProjectedPointResiduals(const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
                                     double const* const* parameters, int count,
                                     const PointOf& point_of, const ResidualAt& residual_at,
                                     double* residuals, double** jacobians) {
  const Eigen::Isometry3d cam_from_objcentre = cam_from_rig * FromPoseParameters(parameters[0]);
  const Eigen::Matrix3d rotation = cam_from_objcentre.linear();
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  Eigen::Matrix<double, Eigen::Dynamic, 6> lie_jacobian;
  if (want_jacobian) lie_jacobian.resize(count, 6);
  Eigen::Matrix<double, 2, 3> d_pixel_d_point;
  Eigen::RowVector2d d_residual_d_pixel;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d& point_in_objcentre = point_of(i);
    const Eigen::Vector3d point_in_cam = cam_from_objcentre * point_in_objcentre;
    if (!(point_in_cam.z() > kMinProjectedDepthMm)) return false;
    const Eigen::Vector2d projection =
        camera.Project(point_in_cam, want_jacobian ? &d_pixel_d_point : nullptr);
    residuals[i] = residual_at(i, projection, want_jacobian ? &d_residual_d_pixel : nullptr);
    if (want_jacobian) {
      lie_jacobian.row(i) =
          ProjectionLieJacobian(d_residual_d_pixel, d_pixel_d_point, rotation, point_in_objcentre);
    }
  }
  if (want_jacobian) AmbientFromLieJacobian(lie_jacobian, parameters[0], jacobians[0]);
  return true;
}

// Σ_i term(r_i) over the residuals of `cost` at the pose `pose_parameters`; +∞ when the
// evaluation fails (a point behind the camera).
template <typename Term>
double SumOverPoseResiduals(const ceres::CostFunction& cost, const double* pose_parameters,
                            const Term& term) {
  std::vector<double> residuals;
  if (!EvaluatePoseResiduals(cost, pose_parameters, &residuals)) {
    return std::numeric_limits<double>::infinity();
  }
  double sum = 0.0;
  for (const double r : residuals) sum += term(r);
  return sum;
}

}  // namespace bcot
