// Region cost of ONE view for Ceres (DESIGN.md "Region energy", paper eq. 5–6, supplement
// S.19): one residual per band pixel of a RegionTemplate, one parameter block of size 7,
// T = rig_from_objcentre ([qx, qy, qz, qw, tx, ty, tz], manifold Se3Manifold).
//
// For template pixel x with Φ0, n = ∇Φ0, model point X (O_o) and x_X(T0), at parameter T:
//
//   x_X(T) = π(cam_from_rig · T · X)                       (Camera::Project, with distortion)
//   Φ(x;T) = Φ0(x) − n · (x_X(T) − x_X(T0))                 (the template moves with the object)
//   He(Φ)  = ½ − atan(s·Φ)/π                                (s = heaviside_slope, per px)
//   m      = ε + (1 − 2ε)·(He·P_f + (1 − He)·P_b)            (ε = probability_floor)
//   F      = −log(m)
//
// The floor ε keeps m in [ε, 1 − ε] (P_f + P_b = 1, see color_model.h), so F lies in
// [−log(1 − ε), −log ε]: strictly positive, which both residual forms need, and bounded, so a
// colour the models never saw cannot produce an infinite cost. It is smooth in T.
//
// Residual forms (both make Ceres minimise w·Σ F, w = view_weight):
//   kSqrtEnergy:  r = √(2wF), ½r² = wF; Gauss-Newton weight w(∂F)²/(2F). One residual block
//                 per view with all its pixels (the fast layout of LIBRARIES.md).
//   kIrls:        r = F with the loss SqrtLoss ρ(s) = 2w√s, ½ρ(r²) = wF; Ceres' IRLS
//                 correction (ρ'' < 0 → weight only) gives the weight ρ'(F²) = w/F, RBOT's
//                 1/F weights, i.e. the same gradient as kSqrtEnergy with twice its
//                 Gauss-Newton Hessian. A ceres::LossFunction acts on the squared norm of a
//                 whole residual block, so this form needs ONE PIXEL PER BLOCK (a block of n
//                 pixels would minimise 2√(Σ F²), not Σ F): AddRegionResidualBlocks adds n
//                 one-pixel blocks sharing the template, at the per-block overhead
//                 LIBRARIES.md measured (~2.5× slower).
//
// Jacobian (analytic, in the Lie tangent δ of T ⊕ δ = T·Exp(δ), δ = (ρ, φ) in O_o):
//   ∂r/∂δ = ∂r/∂F · ∂F/∂Φ · (−nᵀ · ∂π/∂X_c · R_c · [I | −X^])      (S.19)
//   ∂F/∂Φ = −(1 − 2ε)(P_f − P_b)·He'(Φ) / m,   He'(Φ) = −s / (π (1 + s²Φ²))
// with R_c the rotation of cam_from_objcentre = cam_from_rig · T, handed to Ceres through
// AmbientFromLieJacobian. Evaluate fails (returns false, Ceres rejects the step) when a model
// point is at or behind the camera plane.
//
// Thread safety: Evaluate is const and allocation-local; one instance may be evaluated
// concurrently.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/optim/region_template.h"

namespace bcot {

enum class RegionResidualForm {
  kSqrtEnergy,  // r = √(2wF)
  kIrls,        // r = F with SqrtLoss(w)
};

struct RegionCostOptions {
  RegionResidualForm form = RegionResidualForm::kSqrtEnergy;
  // Heaviside slope s (1/px) of He(Φ) = ½ − atan(s·Φ)/π; > 0. RBOT: 1.2.
  double heaviside_slope = 1.2;
  // Per-view weight w >= 0 multiplying the view's energy (0 switches the view off).
  double view_weight = 1.0;
  // ε of the probability mix m = ε + (1 − 2ε)·(He·P_f + (1 − He)·P_b); in (0, 0.5).
  double probability_floor = 1e-3;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// ρ(s) = 2w√s: with residual r = F >= 0, ½ρ(r²) = wF. ρ'(s) = w/√s, ρ''(s) = −w/(2 s^{3/2}).
// Defined for s > 0; at s = 0 returns ρ' = ρ'' = 0 (never reached: F >= −log(1 − ε) > 0).
class SqrtLoss final : public ceres::LossFunction {
 public:
  explicit SqrtLoss(double weight = 1.0) : weight_(weight) {}
  void Evaluate(double s, double rho[3]) const override;

 private:
  double weight_;
};

class RegionCostFunction final : public ceres::CostFunction {
 public:
  // One residual per template pixel. `region_template` must not be empty and `options` must
  // be valid (both CHECKed: the caller skips empty views).
  RegionCostFunction(const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
                     RegionTemplate region_template, const RegionCostOptions& options);
  // One residual per pixel of region_template->pixels[first, first + count), the template
  // shared (kIrls uses count = 1 per block). CHECKs count >= 1 and the range.
  RegionCostFunction(const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
                     std::shared_ptr<const RegionTemplate> region_template, int first, int count,
                     const RegionCostOptions& options);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  // The loss to pass to Problem::AddResidualBlock: SqrtLoss(w) for kIrls (meaningful only on
  // a one-pixel block, see above), nullptr for kSqrtEnergy. The caller (or Ceres, with
  // TAKE_OWNERSHIP) owns it.
  std::unique_ptr<ceres::LossFunction> MakeLossFunction() const;

  // w·Σ F at rig_from_objcentre (7 ambient parameters): the energy both forms minimise.
  // +∞ when a model point is behind the camera.
  double Energy(const double* rig_from_objcentre) const;

  const RegionTemplate& region_template() const { return *template_; }
  const RegionCostOptions& options() const { return options_; }

 private:
  void Initialize(int count);

  Camera camera_;
  Eigen::Isometry3d cam_from_rig_;
  std::shared_ptr<const RegionTemplate> template_;
  int first_ = 0;
  RegionCostOptions options_;
};

// Adds the view's region energy to `problem` in the layout its form needs: kSqrtEnergy one
// block with every pixel; kIrls one block per pixel, each with its SqrtLoss. The problem must
// own cost and loss functions (Ceres' default TAKE_OWNERSHIP). Nothing is added for an empty
// template. The caller sets the Se3Manifold on `rig_from_objcentre`. Returns the blocks.
std::vector<ceres::ResidualBlockId> AddRegionResidualBlocks(
    const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
    std::shared_ptr<const RegionTemplate> region_template, const RegionCostOptions& options,
    double* rig_from_objcentre, ceres::Problem* problem);

}  // namespace bcot
