#include "bcot/core/camera.h"

#include <Eigen/Dense>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace bcot {

Camera::Camera(std::string name, int width, int height, double fx, double fy, double cx,
               double cy)
    : name(std::move(name)), width(width), height(height), fx(fx), fy(fy), cx(cx), cy(cy) {}

bool Camera::HasDistortion() const {
  for (double d : distortion) {
    if (d != 0.0) return true;
  }
  return false;
}

Eigen::Matrix3d Camera::K() const {
  Eigen::Matrix3d k;
  k << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return k;
}

Eigen::Vector2d Camera::Distort(const Eigen::Vector2d& normalized,
                                Eigen::Matrix2d* d_distorted_d_normalized) const {
  const auto [k1, k2, p1, p2, k3] = distortion;
  const double x = normalized.x();
  const double y = normalized.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const Eigen::Vector2d distorted(x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
                                  y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y);
  if (d_distorted_d_normalized != nullptr) {
    // d radial / d r2, then chain through r2 = x² + y².
    const double d_radial = k1 + r2 * (2.0 * k2 + 3.0 * r2 * k3);
    Eigen::Matrix2d& j = *d_distorted_d_normalized;
    j(0, 0) = radial + 2.0 * x * x * d_radial + 2.0 * p1 * y + 6.0 * p2 * x;
    j(0, 1) = 2.0 * x * y * d_radial + 2.0 * p1 * x + 2.0 * p2 * y;
    j(1, 0) = 2.0 * x * y * d_radial + 2.0 * p1 * x + 2.0 * p2 * y;
    j(1, 1) = radial + 2.0 * y * y * d_radial + 6.0 * p1 * y + 2.0 * p2 * x;
  }
  return distorted;
}

Eigen::Vector2d Camera::Project(const Eigen::Vector3d& p_in_cam,
                                Eigen::Matrix<double, 2, 3>* d_pixel_d_point) const {
  const double inv_z = 1.0 / p_in_cam.z();
  const Eigen::Vector2d normalized(p_in_cam.x() * inv_z, p_in_cam.y() * inv_z);
  if (!HasDistortion()) {
    if (d_pixel_d_point != nullptr) {
      *d_pixel_d_point << fx * inv_z, 0.0, -fx * normalized.x() * inv_z,  //
          0.0, fy * inv_z, -fy * normalized.y() * inv_z;
    }
    return {fx * normalized.x() + cx, fy * normalized.y() + cy};
  }
  Eigen::Matrix2d d_dist;
  const Eigen::Vector2d distorted = Distort(normalized, d_pixel_d_point ? &d_dist : nullptr);
  if (d_pixel_d_point != nullptr) {
    Eigen::Matrix<double, 2, 3> d_norm_d_point;
    d_norm_d_point << inv_z, 0.0, -normalized.x() * inv_z,  //
        0.0, inv_z, -normalized.y() * inv_z;
    *d_pixel_d_point = Eigen::DiagonalMatrix<double, 2>(fx, fy) * d_dist * d_norm_d_point;
  }
  return {fx * distorted.x() + cx, fy * distorted.y() + cy};
}

Eigen::Vector3d Camera::PixelToRay(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d target((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  Eigen::Vector2d normalized = target;
  if (HasDistortion()) {
    // Solve Distort(n) = target by Gauss-Newton from n = target.
    for (int iteration = 0; iteration < 20; ++iteration) {
      Eigen::Matrix2d jacobian;
      const Eigen::Vector2d residual = Distort(normalized, &jacobian) - target;
      if (residual.squaredNorm() < 1e-26) break;
      normalized -= jacobian.partialPivLu().solve(residual);
    }
  }
  return {normalized.x(), normalized.y(), 1.0};
}

Camera Camera::Scaled(double factor) const {
  Camera scaled = *this;
  scaled.width = static_cast<int>(std::lround(width * factor));
  scaled.height = static_cast<int>(std::lround(height * factor));
  scaled.fx = fx * factor;
  scaled.fy = fy * factor;
  scaled.cx = (cx + 0.5) * factor - 0.5;
  scaled.cy = (cy + 0.5) * factor - 0.5;
  return scaled;
}

bool Camera::InImage(const Eigen::Vector2d& pixel, double margin_px) const {
  return pixel.x() >= -0.5 + margin_px && pixel.y() >= -0.5 + margin_px &&
         pixel.x() <= width - 0.5 - margin_px && pixel.y() <= height - 0.5 - margin_px;
}

Status Camera::Validate(const std::string& context) const {
  std::vector<std::string> problems;
  if (width <= 0 || height <= 0) {
    problems.push_back(fmt::format("image_size = [{}, {}], must be positive", width, height));
  }
  if (!(fx > 0.0) || !(fy > 0.0) || !std::isfinite(fx) || !std::isfinite(fy)) {
    problems.push_back(fmt::format("K focal lengths = ({}, {}), must be finite and > 0", fx, fy));
  }
  if (!std::isfinite(cx) || !std::isfinite(cy)) {
    problems.push_back("K principal point must be finite");
  }
  for (double d : distortion) {
    if (!std::isfinite(d)) problems.push_back("distortion must be finite");
  }
  if (problems.empty()) return Status::Ok();
  std::string message = context + ": " + problems[0];
  for (size_t i = 1; i < problems.size(); ++i) message += "; " + problems[i];
  return Status::InvalidInput(message);
}

}  // namespace bcot
