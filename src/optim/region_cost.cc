#include "bcot/optim/region_cost.h"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>

#include "bcot/core/se3.h"
#include "bcot/optim/projected_point_cost.h"
#include "bcot/optim/se3_manifold.h"
#include "bcot/core/violations.h"

namespace bcot {

Status RegionCostOptions::Validate() const {
  std::vector<std::string> violations;
  if (form != RegionResidualForm::kSqrtEnergy && form != RegionResidualForm::kIrls) {
    violations.push_back(
        fmt::format("form = {}, must be sqrt_energy or irls", static_cast<int>(form)));
  }
  if (!(heaviside_slope > 0.0) || !std::isfinite(heaviside_slope)) {
    violations.push_back(
        fmt::format("heaviside_slope = {}, must be finite and > 0", heaviside_slope));
  }
  if (!(view_weight >= 0.0) || !std::isfinite(view_weight)) {
    violations.push_back(fmt::format("view_weight = {}, must be finite and >= 0", view_weight));
  }
  if (!(probability_floor > 0.0 && probability_floor < 0.5)) {
    violations.push_back(
        fmt::format("probability_floor = {}, must be in (0, 0.5)", probability_floor));
  }
  return internal::JoinViolations("region_cost", violations);
}

void SqrtLoss::Evaluate(double s, double rho[3]) const {
  if (!(s > 0.0)) {
    rho[0] = 0.0;
    rho[1] = 0.0;
    rho[2] = 0.0;
    return;
  }
  const double root = std::sqrt(s);
  rho[0] = 2.0 * weight_ * root;
  rho[1] = weight_ / root;
  rho[2] = -0.5 * weight_ / (s * root);
}

RegionCostFunction::RegionCostFunction(const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
                                       RegionTemplate region_template,
                                       const RegionCostOptions& options)
    : camera_(camera),
      cam_from_rig_(cam_from_rig),
      template_(std::make_shared<const RegionTemplate>(std::move(region_template))),
      options_(options) {
  Initialize(static_cast<int>(template_->pixels.size()));
}

RegionCostFunction::RegionCostFunction(const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
                                       std::shared_ptr<const RegionTemplate> region_template,
                                       int first, int count, const RegionCostOptions& options)
    : camera_(camera),
      cam_from_rig_(cam_from_rig),
      template_(std::move(region_template)),
      first_(first),
      options_(options) {
  Initialize(count);
}

void RegionCostFunction::Initialize(int count) {
  BCOT_CHECK(template_ != nullptr);
  BCOT_CHECK(count >= 1 && first_ >= 0 &&
             first_ + count <= static_cast<int>(template_->pixels.size()));
  BCOT_CHECK(options_.Validate().ok());
  set_num_residuals(count);
  mutable_parameter_block_sizes()->push_back(kPoseAmbientSize);
}

std::unique_ptr<ceres::LossFunction> RegionCostFunction::MakeLossFunction() const {
  if (options_.form == RegionResidualForm::kIrls) {
    return std::make_unique<SqrtLoss>(options_.view_weight);
  }
  return nullptr;
}

bool RegionCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                  double** jacobians) const {
  const RegionPixel* pixels = template_->pixels.data() + first_;
  const double s = options_.heaviside_slope;
  const double eps = options_.probability_floor;
  const double w = options_.view_weight;
  const bool sqrt_form = options_.form == RegionResidualForm::kSqrtEnergy;
  return EvaluateProjectedPointResiduals(
      camera_, cam_from_rig_, parameters, num_residuals(),
      [&](int i) -> const Eigen::Vector3d& { return pixels[i].point_in_objcentre; },
      [&](int i, const Eigen::Vector2d& projection, Eigen::RowVector2d* d_residual_d_pixel) {
        const RegionPixel& p = pixels[i];
        const double phi = p.phi0 - p.grad_phi0.dot(projection - p.projection0);
        const double heaviside = 0.5 - std::atan(s * phi) / kPi;
        const double mix = eps + (1.0 - 2.0 * eps) * (heaviside * p.p_foreground +
                                                      (1.0 - heaviside) * p.p_background);
        const double energy = -std::log(mix);
        const double residual = sqrt_form ? std::sqrt(2.0 * w * energy) : energy;
        if (d_residual_d_pixel != nullptr) {
          // 0 only when w = 0.
          const double d_residual_d_energy =
              !sqrt_form ? 1.0 : (residual > 0.0 ? w / residual : 0.0);
          const double d_heaviside = -s / (kPi * (1.0 + s * s * phi * phi));
          const double d_energy_d_phi =
              -(1.0 - 2.0 * eps) * (p.p_foreground - p.p_background) * d_heaviside / mix;
          // ∂Φ/∂π = −nᵀ with n = ∇Φ₀  (S.19).
          *d_residual_d_pixel = (-d_residual_d_energy * d_energy_d_phi) * p.grad_phi0.transpose();
        }
        return residual;
      },
      residuals, jacobians);
}

double RegionCostFunction::Energy(const double* rig_from_objcentre) const {
  const bool sqrt_form = options_.form == RegionResidualForm::kSqrtEnergy;
  const double w = options_.view_weight;
  return SumOverPoseResiduals(*this, rig_from_objcentre,
                              [&](double r) { return sqrt_form ? 0.5 * r * r : w * r; });
}

std::vector<ceres::ResidualBlockId> AddRegionResidualBlocks(
    const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
    std::shared_ptr<const RegionTemplate> region_template, const RegionCostOptions& options,
    double* rig_from_objcentre, ceres::Problem* problem) {
  std::vector<ceres::ResidualBlockId> blocks;
  const int size = static_cast<int>(region_template->pixels.size());
  if (size == 0) return blocks;
  if (options.form == RegionResidualForm::kSqrtEnergy) {
    blocks.push_back(problem->AddResidualBlock(
        new RegionCostFunction(camera, cam_from_rig, std::move(region_template), 0, size, options),
        nullptr, rig_from_objcentre));
    return blocks;
  }
  blocks.reserve(size);
  for (int i = 0; i < size; ++i) {
    blocks.push_back(problem->AddResidualBlock(
        new RegionCostFunction(camera, cam_from_rig, region_template, i, 1, options),
        new SqrtLoss(options.view_weight), rig_from_objcentre));
  }
  return blocks;
}

}  // namespace bcot
