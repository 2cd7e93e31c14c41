#include "bcot/optim/correspondence_line_cost.h"

#include <cmath>
#include <utility>

#include "bcot/core/se3.h"
#include "bcot/optim/projected_point_cost.h"
#include "bcot/optim/se3_manifold.h"

namespace bcot {

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
  const CorrespondenceLine* lines = lines_->lines.data() + first_line_;
  // r = (√w/σ)·(nᵀ(π − π₀) − μ), ∂r/∂π = (√w/σ)·nᵀ  (S.19).
  return EvaluateProjectedPointResiduals(
      camera_, cam_from_rig_, parameters, num_residuals(),
      [&](int i) -> const Eigen::Vector3d& { return lines[i].point_in_objcentre; },
      [&](int i, const Eigen::Vector2d& projection, Eigen::RowVector2d* d_residual_d_pixel) {
        const CorrespondenceLine& line = lines[i];
        const double scale = sqrt_weight_ / line.sigma_px;
        if (d_residual_d_pixel != nullptr) *d_residual_d_pixel = scale * line.normal.transpose();
        return scale * (line.normal.dot(projection - line.projection0) - line.mean_px);
      },
      residuals, jacobians);
}

double CorrespondenceLineCostFunction::Energy(const double* rig_from_objcentre) const {
  return SumOverPoseResiduals(*this, rig_from_objcentre, [](double r) { return 0.5 * r * r; });
}

}  // namespace bcot
