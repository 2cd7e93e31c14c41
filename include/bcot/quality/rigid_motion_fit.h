// Step 5 of the quality measurement (bcot/quality/quality_report.h): the part of the raw
// boundary offsets that one small rigid motion of the object explains, and how well the
// contour points pin that motion down.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

// Fits a small motion δ = (ω, v) of the object about `object_centre` (object frame) to boundary
// offsets along the contour normals, with the first-order model offset_i = n_iᵀ · ∂x_i/∂δ · δ
// (step 5 of bcot/quality/quality_report.h). The model rows depend only on the contour and
// the pose, so one fitter serves the fit and its bootstrap.
class RigidMotionFitter {
 public:
  RigidMotionFitter(const std::vector<ContourPoint>& contour, const Camera& camera,
                    const Eigen::Isometry3d& cam_from_object, const Eigen::Vector3d& object_centre);

  // Robust (Huber, then Tukey; scale `scale_px` > 0) weighted least squares on the finite
  // `offsets` (one per contour point, NaN = none). `sigmas_px` (empty = all equal) are the
  // offsets' standard deviations: point i weighs 1 / (σ_i² + σ_model²), σ_model = 0.1 px (mesh
  // facets, the linearisation). `multiplicity` (empty = all 1) counts each point that many
  // times (a bootstrap resample). Returns the model's offset at every contour point, all NaN
  // when fewer than 6 points carry weight. `weights` (optional) receives each point's weight in
  // the final solve, relative to 1 / σ_model²: multiplicity × σ_model² / (σ_i² + σ_model²) ×
  // the robust weight, 0 for points without an offset or rejected as outliers.
  std::vector<double> Fit(const std::vector<double>& offsets, const std::vector<double>& sigmas_px,
                          double scale_px, const std::vector<int>& multiplicity = {},
                          std::vector<double>* weights = nullptr) const;

  // Standard deviation of the `fraction` percentile of |fitted offset| over `resamples`
  // bootstrap resamples of the contour points with a finite offset (seeded by `seed`, so the
  // result is reproducible); NaN when fewer than 6 points have an offset or resamples < 2.
  double BootstrapPercentileSigma(const std::vector<double>& offsets,
                                  const std::vector<double>& sigmas_px, double scale_px,
                                  double fraction, int resamples, uint32_t seed) const;

  // The `fraction` percentile, over every contour point, of the standard deviation of the
  // fitted offset there: s_i = √(r_iᵀ I⁻¹ r_i), I = Σ w_j r_j r_jᵀ / σ_model² with w_j the
  // final weights of a Fit (`weights`; w_j / σ_model² = 1 / (σ_j² + σ_model²) for a point the
  // robust loss keeps whole; Cramér-Rao, DESIGN.md "Quality"). Small when the weighted points
  // observe every motion that moves the contour; large when they leave one unobserved (a side
  // of the object with no usable boundary, or whose boundaries the fit rejected) which moves
  // the rest of the contour, whose fitted offsets then say nothing. Motions that move no
  // contour point add nothing. NaN when fewer than 6 points carry weight.
  double PredictionSigmaPercentile(const std::vector<double>& weights, double fraction) const;

 private:
  Eigen::Matrix<double, Eigen::Dynamic, 6> rows_;
};

// RigidMotionFitter(contour, ...).Fit(offsets, {}, scale_px).
std::vector<double> FitRigidMotionOffsets(const std::vector<ContourPoint>& contour,
                                          const std::vector<double>& offsets, const Camera& camera,
                                          const Eigen::Isometry3d& cam_from_object,
                                          const Eigen::Vector3d& object_centre, double scale_px);

}  // namespace bcot
