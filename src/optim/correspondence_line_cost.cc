#include "bcot/optim/correspondence_line_cost.h"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/optim/se3_manifold.h"

namespace bcot {
namespace {

// Model points closer to the camera plane than this (mm) make the evaluation fail.
constexpr double kMinDepthMm = 1e-6;

}  // namespace

CorrespondenceLineCostFunction::CorrespondenceLineCostFunction(
    const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
    std::shared_ptr<const CorrespondenceLines> lines, double weight, int first_line, int num_lines)
    : camera_(camera),
      cam_from_rig_(cam_from_rig),
      lines_(std::move(lines)),
      first_line_(first_line) {
  BCOT_CHECK(lines_ != nullptr);
  const int available = static_cast<int>(lines_->lines.size());
  if (num_lines < 0) num_lines = available - first_line;
  BCOT_CHECK(first_line >= 0 && num_lines >= 1 && first_line + num_lines <= available);
  BCOT_CHECK(weight >= 0.0 && std::isfinite(weight));
  sqrt_weight_ = std::sqrt(weight);
  set_num_residuals(num_lines);
  mutable_parameter_block_sizes()->push_back(kPoseAmbientSize);
}

bool CorrespondenceLineCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                              double** jacobians) const {
  const Eigen::Isometry3d cam_from_objcentre = cam_from_rig_ * FromPoseParameters(parameters[0]);
  const Eigen::Matrix3d rotation = cam_from_objcentre.linear();
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  const int n = num_residuals();
  Eigen::Matrix<double, Eigen::Dynamic, 6> lie_jacobian;
  if (want_jacobian) lie_jacobian.resize(n, 6);
  Eigen::Matrix<double, 2, 3> d_pixel_d_point;
  for (int i = 0; i < n; ++i) {
    const CorrespondenceLine& line = lines_->lines[first_line_ + i];
    const Eigen::Vector3d point_in_cam = cam_from_objcentre * line.point_in_objcentre;
    if (!(point_in_cam.z() > kMinDepthMm)) return false;
    const Eigen::Vector2d projection =
        camera_.Project(point_in_cam, want_jacobian ? &d_pixel_d_point : nullptr);
    const double scale = sqrt_weight_ / line.sigma_px;
    residuals[i] = scale * (line.normal.dot(projection - line.projection0) - line.mean_px);
    if (want_jacobian) {
      // ∂r/∂δ = (√w/σ)·nᵀ·∂π/∂X_c·R_c·[I | −X^]  (S.19).
      lie_jacobian.row(i) = scale * ProjectionLieJacobian(line.normal.transpose(), d_pixel_d_point,
                                                          rotation, line.point_in_objcentre);
    }
  }
  if (want_jacobian) AmbientFromLieJacobian(lie_jacobian, parameters[0], jacobians[0]);
  return true;
}

double CorrespondenceLineCostFunction::Energy(const double* rig_from_objcentre) const {
  std::vector<double> residuals;
  if (!EvaluatePoseResiduals(*this, rig_from_objcentre, &residuals)) {
    return std::numeric_limits<double>::infinity();
  }
  return 0.5 * Eigen::Map<const Eigen::VectorXd>(residuals.data(), residuals.size()).squaredNorm();
}

}  // namespace bcot
