// Sparse region cost of ONE view for Ceres (DESIGN.md "Sparse variant", SRT3D/ICG style): one
// residual per correspondence line (correspondence_lines.h), one parameter block of size 7,
// T = rig_from_objcentre ([qx, qy, qz, qw, tx, ty, tz], manifold Se3Manifold).
//
// For line i with outward normal n, model point X (O_o), its projection x0 = x_X(T0), and the
// contour-position distribution (μ, σ) measured along the line at T0:
//
//   x_X(T) = π(cam_from_rig · T · X)                 (Camera::Project, with distortion)
//   r_i    = √w · (n · (x_X(T) − x0) − μ) / σ        (w = view weight)
//
// n·(x_X(T) − x0) is where the model's contour sits on the line at T (the contour moves with
// its model point), μ where the image says it is; ½Σ r² is the negative log of the Gaussian
// approximation of the lines' distributions, so Ceres' Gauss-Newton is exact in form.
//
// Jacobian (analytic, in the Lie tangent δ of T ⊕ δ = T·Exp(δ), δ = (ρ, φ) in O_o):
//   ∂r/∂δ = (√w/σ) · nᵀ · ∂π/∂X_c · R_c · [I | −X^]   (S.19)
// with R_c the rotation of cam_from_objcentre = cam_from_rig · T, handed to Ceres through
// AmbientFromLieJacobian. Evaluate fails (Ceres rejects the step) when a model point is at or
// behind the camera plane.
//
// Thread safety: Evaluate is const and allocation-local.
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Geometry>
#include <memory>

#include "bcot/core/camera.h"
#include "bcot/optim/correspondence_lines.h"

namespace bcot {

class CorrespondenceLineCostFunction final : public ceres::CostFunction {
 public:
  // One residual per line of lines[first_line, first_line + num_lines) (num_lines < 0: to the
  // last line). A block per line lets each line have its own robust loss (the edge stage);
  // one block for all lines is cheaper. The range must be non-empty and within the lines, and
  // `weight` finite and >= 0 (CHECKed: the caller skips views without lines).
  CorrespondenceLineCostFunction(const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
                                 std::shared_ptr<const CorrespondenceLines> lines, double weight,
                                 int first_line = 0, int num_lines = -1);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  // ½Σ r² at rig_from_objcentre (7 ambient parameters); +∞ when a model point is behind the
  // camera.
  double Energy(const double* rig_from_objcentre) const;

  const CorrespondenceLines& lines() const { return *lines_; }

 private:
  Camera camera_;
  Eigen::Isometry3d cam_from_rig_;
  std::shared_ptr<const CorrespondenceLines> lines_;
  int first_line_;
  double sqrt_weight_;
};

}  // namespace bcot
