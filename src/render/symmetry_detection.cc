#include "bcot/render/symmetry_detection.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "bcot/core/se3.h"
#include "bcot/core/violations.h"

namespace bcot {

Status SymmetryDetectionOptions::Validate() const {
  std::vector<std::string> violations;
  if (!(moment_tolerance > 0.0 && moment_tolerance < 0.5)) {
    violations.push_back(
        fmt::format("moment_tolerance = {}, must be in (0, 0.5)", moment_tolerance));
  }
  if (!(tolerance > 0.0 && tolerance < 0.1)) {
    violations.push_back(fmt::format("tolerance = {}, must be in (0, 0.1)", tolerance));
  }
  if (image_px < 64 || image_px > 2048) {
    violations.push_back(fmt::format("image_px = {}, must be in [64, 2048]", image_px));
  }
  return internal::JoinViolations("symmetry detection", violations);
}

namespace {

constexpr int kSamplesPerAxis = 2;

// The surface's area-weighted centroid and second central moments (3×3): per triangle
// ∫ x·xᵀ dA = A/12·(Σ vᵢvᵢᵀ + s·sᵀ), s = v₀ + v₁ + v₂, and ∫ x dA = A·s/3.
void SurfaceMoments(const Mesh& mesh, Eigen::Vector3d* centroid, Eigen::Matrix3d* moments) {
  double area = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3i& triangle : mesh.triangles()) {
    const Eigen::Vector3d v0 = mesh.vertices()[triangle[0]].cast<double>();
    const Eigen::Vector3d v1 = mesh.vertices()[triangle[1]].cast<double>();
    const Eigen::Vector3d v2 = mesh.vertices()[triangle[2]].cast<double>();
    const double a = 0.5 * (v1 - v0).cross(v2 - v0).norm();
    const Eigen::Vector3d s = v0 + v1 + v2;
    area += a;
    first += a * s / 3.0;
    second += a / 12.0 *
              (v0 * v0.transpose() + v1 * v1.transpose() + v2 * v2.transpose() + s * s.transpose());
  }
  *centroid = first / std::max(area, 1e-300);
  *moments = second / std::max(area, 1e-300) - *centroid * centroid->transpose();
}

// The pixels of `mask` that differ from `other`, and its boundary pixels (inside, with a
// 4-neighbour outside; the object never reaches the image's border here).
void CompareMasks(const cv::Mat1b& mask, const cv::Mat1b& other, double* differing,
                  double* boundary) {
  *differing = cv::countNonZero(mask != other);
  cv::Mat1b interior;
  cv::erode(mask, interior, cv::getStructuringElement(cv::MORPH_CROSS, cv::Size(3, 3)));
  *boundary = cv::countNonZero(mask) - cv::countNonZero(interior);
}

// Step 2 of the header: the worst mean silhouette displacement over views and turns, as a
// fraction of the object's diameter in the image.
double SilhouetteDisplacement(const RayCaster& caster, const RotationalSymmetry& symmetry,
                              int image_px) {
  const Mesh& mesh = caster.mesh();
  const Eigen::Vector3d centre = 0.5 * (mesh.bbox_min() + mesh.bbox_max());
  const double radius = 0.5 * (mesh.bbox_max() - mesh.bbox_min()).norm();
  const double distance = 4.0 * radius;
  // A sphere of `radius` at the nearest depth fills 0.8 of the image.
  const double focal = 0.4 * image_px * (distance - radius) / radius;
  const Camera camera("symmetry", image_px, image_px, focal, focal, 0.5 * (image_px - 1),
                      0.5 * (image_px - 1));
  const double diameter_samples = 2.0 * radius * focal / distance * kSamplesPerAxis;
  RenderOptions options;
  options.roi = cv::Rect(0, 0, image_px, image_px);
  options.samples_per_axis = kSamplesPerAxis;
  options.depth = options.normal_in_cam = options.point_in_object = options.triangle_id = false;

  const Eigen::Vector3d& a = symmetry.axis;
  const Eigen::Vector3d u = a.unitOrthogonal();
  const Eigen::Vector3d v = a.cross(u);
  // (angle from the axis, azimuth) of the view directions, in degrees.
  constexpr std::array<std::array<double, 2>, 4> kViews = {
      {{90.0, 0.0}, {80.0, 100.0}, {60.0, 190.0}, {30.0, 290.0}}};
  constexpr std::array<double, 4> kTurnsDeg = {37.0, 113.0, 191.0, 263.0};
  double worst = 0.0;
  for (const auto& [polar_deg, azimuth_deg] : kViews) {
    const double polar = polar_deg * kPi / 180.0, azimuth = azimuth_deg * kPi / 180.0;
    const Eigen::Vector3d direction =
        std::cos(polar) * a + std::sin(polar) * (std::cos(azimuth) * u + std::sin(azimuth) * v);
    Eigen::Isometry3d template_from_cam = LookAtOrigin(distance * direction);
    template_from_cam.translation() += centre;
    const Eigen::Isometry3d cam_from_template = template_from_cam.inverse();
    const RenderedView base = caster.Render(camera, cam_from_template, options);
    for (double turn_deg : kTurnsDeg) {
      const RenderedView turned = caster.Render(
          camera, cam_from_template * symmetry.Rotation(turn_deg * kPi / 180.0), options);
      double differing = 0.0, boundary = 0.0;
      CompareMasks(base.mask, turned.mask, &differing, &boundary);
      if (boundary == 0.0) continue;
      worst = std::max(worst, differing / boundary / diameter_samples);
    }
  }
  return worst;
}

}  // namespace

StatusOr<std::optional<RotationalSymmetry>> DetectRotationalSymmetry(
    const RayCaster& caster, const SymmetryDetectionOptions& options,
    std::vector<SymmetryCandidate>* candidates) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  Eigen::Vector3d centroid;
  Eigen::Matrix3d moments;
  SurfaceMoments(caster.mesh(), &centroid, &moments);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(moments);
  const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
  const double largest = std::max(values[2], 1e-300);
  // Candidate k: the axis of eigenvector k, when the other two moments agree.
  std::vector<SymmetryCandidate> checked;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::abs(values[(k + 1) % 3] - values[(k + 2) % 3]) / largest;
    if (gap > options.moment_tolerance) continue;
    SymmetryCandidate candidate;
    candidate.symmetry = {eigen.eigenvectors().col(k).normalized(), centroid};
    candidate.moment_gap = gap;
    candidate.displacement = SilhouetteDisplacement(caster, candidate.symmetry, options.image_px);
    candidate.symmetric = candidate.displacement <= options.tolerance;
    checked.push_back(candidate);
  }
  std::optional<RotationalSymmetry> found;
  int passed = 0;
  for (const SymmetryCandidate& candidate : checked) {
    if (!candidate.symmetric) continue;
    ++passed;
    found = candidate.symmetry;
  }
  if (candidates != nullptr) *candidates = checked;
  if (passed != 1) return std::optional<RotationalSymmetry>();
  return found;
}

}  // namespace bcot
