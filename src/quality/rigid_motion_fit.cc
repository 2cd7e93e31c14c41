#include "bcot/quality/rigid_motion_fit.h"

#include <cmath>
#include <limits>
#include <random>

#include "bcot/quality/boundary_search.h"

namespace bcot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Standard deviation of the offset model itself (px): mesh facets, linearised projection.
constexpr double kModelSigmaPx = 0.1;

// Damps the directions of a 6×6 normal matrix that no point observes (depth, rotations that
// slide the contour along itself), so it can be solved; they move no contour point.
void DampUnobservedMotions(Eigen::Matrix<double, 6, 6>* normal) {
  normal->diagonal().array() += 1e-9 * normal->trace() + 1e-12;
}

}  // namespace

RigidMotionFitter::RigidMotionFitter(const std::vector<ContourPoint>& contour, const Camera& camera,
                                     const Eigen::Isometry3d& cam_from_object,
                                     const Eigen::Vector3d& object_centre)
    : rows_(contour.size(), 6) {
  // Row i: ∂(n_i · x_i)/∂δ for δ = (ω, v), the motion X ↦ X + ω × (X − c) + v of the
  // camera-frame points about the object centre c (rotation about c keeps ω and v apart).
  const Eigen::Vector3d centre = cam_from_object * object_centre;
  for (size_t i = 0; i < contour.size(); ++i) {
    const Eigen::Vector3d point = cam_from_object * contour[i].point_in_object;
    Eigen::Matrix<double, 2, 3> d_pixel_d_point;
    camera.Project(point, &d_pixel_d_point);
    const Eigen::RowVector3d n_d = contour[i].normal.transpose() * d_pixel_d_point;
    rows_.block<1, 3>(i, 0) = (point - centre).cross(n_d.transpose()).transpose();  // n_dᵀ(ω × r)
    rows_.block<1, 3>(i, 3) = n_d;
  }
}

std::vector<double> RigidMotionFitter::Fit(const std::vector<double>& offsets,
                                           const std::vector<double>& sigmas_px, double scale_px,
                                           const std::vector<int>& multiplicity,
                                           std::vector<double>* weights) const {
  const size_t n = static_cast<size_t>(rows_.rows());
  BCOT_CHECK(offsets.size() == n);
  BCOT_CHECK(sigmas_px.empty() || sigmas_px.size() == n);
  BCOT_CHECK(multiplicity.empty() || multiplicity.size() == n);
  BCOT_CHECK(scale_px > 0.0);
  auto prior_weight = [&](size_t i) {
    double weight = multiplicity.empty() ? 1.0 : multiplicity[i];
    if (!sigmas_px.empty()) {
      weight *= kModelSigmaPx * kModelSigmaPx /
                (sigmas_px[i] * sigmas_px[i] + kModelSigmaPx * kModelSigmaPx);
    }
    return weight;
  };
  // IRLS: Huber weights (convex, so the start does not matter), then Tukey's biweight, which
  // gives outliers (clutter edges, blur, highlights found instead of the boundary) no weight.
  Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
  int used = 0;
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    used = 0;
    if (weights != nullptr) weights->assign(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(offsets[i])) continue;
      const double prior = prior_weight(i);
      if (!(prior > 0.0)) continue;
      const double residual = std::abs(offsets[i] - rows_.row(i).dot(delta));
      double weight;
      if (iteration < 5) {
        weight = residual <= scale_px ? 1.0 : scale_px / residual;
      } else {
        const double u = residual / (3.0 * scale_px);
        weight = u < 1.0 ? (1 - u * u) * (1 - u * u) : 0.0;
      }
      if (weight <= 0) continue;
      weight *= prior;
      if (weights != nullptr) (*weights)[i] = weight;
      normal += weight * rows_.row(i).transpose() * rows_.row(i);
      rhs += weight * offsets[i] * rows_.row(i).transpose();
      ++used;
    }
    if (used < 6) break;
    // Unobserved directions are damped to zero, so the fitted offsets ignore them.
    DampUnobservedMotions(&normal);
    delta = normal.ldlt().solve(rhs);
  }
  std::vector<double> fitted(n, kNaN);
  if (used < 6) return fitted;
  for (size_t i = 0; i < n; ++i) fitted[i] = rows_.row(i).dot(delta);
  return fitted;
}

double RigidMotionFitter::BootstrapPercentileSigma(const std::vector<double>& offsets,
                                                   const std::vector<double>& sigmas_px,
                                                   double scale_px, double fraction, int resamples,
                                                   uint32_t seed) const {
  std::vector<size_t> finite;
  for (size_t i = 0; i < offsets.size(); ++i) {
    if (std::isfinite(offsets[i])) finite.push_back(i);
  }
  if (finite.size() < 6 || resamples < 2) return kNaN;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, finite.size() - 1);
  std::vector<int> multiplicity(offsets.size());
  double sum = 0.0, sum_squares = 0.0;
  int count = 0;
  for (int r = 0; r < resamples; ++r) {
    std::fill(multiplicity.begin(), multiplicity.end(), 0);
    for (size_t k = 0; k < finite.size(); ++k) ++multiplicity[finite[pick(rng)]];
    const double statistic =
        AbsPercentile(Fit(offsets, sigmas_px, scale_px, multiplicity), fraction);
    if (!std::isfinite(statistic)) continue;
    sum += statistic;
    sum_squares += statistic * statistic;
    ++count;
  }
  if (count < 2) return kNaN;
  const double mean = sum / count;
  return std::sqrt(std::max(0.0, (sum_squares - count * mean * mean) / (count - 1)));
}

double RigidMotionFitter::PredictionSigmaPercentile(const std::vector<double>& weights,
                                                    double fraction) const {
  const size_t n = static_cast<size_t>(rows_.rows());
  BCOT_CHECK(weights.size() == n);
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  int used = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!(weights[i] > 0.0)) continue;
    information +=
        weights[i] / (kModelSigmaPx * kModelSigmaPx) * rows_.row(i).transpose() * rows_.row(i);
    ++used;
  }
  if (used < 6) return kNaN;
  DampUnobservedMotions(&information);
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> covariance(information);
  std::vector<double> sigmas(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Matrix<double, 6, 1> row = rows_.row(i).transpose();
    sigmas[i] = std::sqrt(std::max(0.0, row.dot(covariance.solve(row))));
  }
  return AbsPercentile(sigmas, fraction);
}

std::vector<double> FitRigidMotionOffsets(const std::vector<ContourPoint>& contour,
                                          const std::vector<double>& offsets, const Camera& camera,
                                          const Eigen::Isometry3d& cam_from_object,
                                          const Eigen::Vector3d& object_centre, double scale_px) {
  BCOT_CHECK(contour.size() == offsets.size());
  return RigidMotionFitter(contour, camera, cam_from_object, object_centre)
      .Fit(offsets, {}, scale_px);
}

}  // namespace bcot
