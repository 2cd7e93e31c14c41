#include "bcot/quality/rigid_motion_fit.h"

#include <cmath>
#include <limits>

namespace bcot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

std::vector<double> FitRigidMotionOffsets(const std::vector<ContourPoint>& contour,
                                          const std::vector<double>& offsets, const Camera& camera,
                                          const Eigen::Isometry3d& cam_from_object,
                                          const Eigen::Vector3d& object_centre, double scale_px) {
  BCOT_CHECK(contour.size() == offsets.size());
  BCOT_CHECK(scale_px > 0.0);
  // Row i of A: ∂(n_i · x_i)/∂δ for δ = (ω, v), the motion X ↦ X + ω × (X − c) + v of the
  // camera-frame points about the object centre c (rotation about c keeps ω and v apart).
  const Eigen::Vector3d centre = cam_from_object * object_centre;
  Eigen::Matrix<double, Eigen::Dynamic, 6> rows(contour.size(), 6);
  for (size_t i = 0; i < contour.size(); ++i) {
    const Eigen::Vector3d point = cam_from_object * contour[i].point_in_object;
    Eigen::Matrix<double, 2, 3> d_pixel_d_point;
    camera.Project(point, &d_pixel_d_point);
    const Eigen::RowVector3d n_d = contour[i].normal.transpose() * d_pixel_d_point;
    rows.block<1, 3>(i, 0) = (point - centre).cross(n_d.transpose()).transpose();  // n_dᵀ(ω × r)
    rows.block<1, 3>(i, 3) = n_d;
  }
  // IRLS: Huber weights (convex, so the start does not matter), then Tukey's biweight, which
  // gives outliers (clutter edges, blur, highlights found instead of the boundary) no weight.
  Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
  int used = 0;
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    used = 0;
    for (size_t i = 0; i < contour.size(); ++i) {
      if (!std::isfinite(offsets[i])) continue;
      const double residual = std::abs(offsets[i] - rows.row(i).dot(delta));
      double weight;
      if (iteration < 5) {
        weight = residual <= scale_px ? 1.0 : scale_px / residual;
      } else {
        const double u = residual / (3.0 * scale_px);
        weight = u < 1.0 ? (1 - u * u) * (1 - u * u) : 0.0;
      }
      if (weight <= 0) continue;
      normal += weight * rows.row(i).transpose() * rows.row(i);
      rhs += weight * offsets[i] * rows.row(i).transpose();
      ++used;
    }
    if (used < 6) break;
    // Directions the contour does not observe (depth, rotations that slide the contour along
    // itself) are damped to zero; they move no contour point, so the fitted offsets ignore them.
    normal.diagonal().array() += 1e-9 * normal.trace() + 1e-12;
    delta = normal.ldlt().solve(rhs);
  }
  std::vector<double> fitted(contour.size(), kNaN);
  if (used < 6) return fitted;
  for (size_t i = 0; i < contour.size(); ++i) fitted[i] = rows.row(i).dot(delta);
  return fitted;
}

}  // namespace bcot
