// Pinhole camera with OpenCV's 5-parameter distortion (k1, k2, p1, p2, k3).
//
// Frame: OpenCV camera frame (x right, y down, z forward), units mm. Pixel centres sit at
// integer coordinates, so the image spans [−0.5, width − 0.5] × [−0.5, height − 0.5].
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "bcot/core/status.h"

namespace bcot {

class Camera {
 public:
  std::string name;
  int width = 0;
  int height = 0;
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3; all zero = ideal pinhole

  Camera() = default;
  Camera(std::string name, int width, int height, double fx, double fy, double cx, double cy);

  bool HasDistortion() const;
  Eigen::Matrix3d K() const;

  // Projects a point in the camera frame (z > 0) to a pixel. When `d_pixel_d_point` is given
  // it receives ∂pixel/∂p_in_cam (2×3), including distortion (DESIGN.md S.10–11).
  Eigen::Vector2d Project(const Eigen::Vector3d& p_in_cam,
                          Eigen::Matrix<double, 2, 3>* d_pixel_d_point = nullptr) const;

  // Distorts normalized coordinates (x/z, y/z) → distorted normalized coordinates, with the
  // 2×2 Jacobian when requested.
  Eigen::Vector2d Distort(const Eigen::Vector2d& normalized,
                          Eigen::Matrix2d* d_distorted_d_normalized = nullptr) const;

  // Inverse of the projection up to depth: the ray direction (x, y, 1) in the camera frame
  // whose projection is `pixel`. Undistortion is iterative (Gauss-Newton, converges to
  // 1e-12 for any distortion a real lens has).
  Eigen::Vector3d PixelToRay(const Eigen::Vector2d& pixel) const;

  // The same camera for an image resized by `factor` (e.g. 0.5 for 1280×1024 → 640×512),
  // keeping the pixel-centre convention: c' = (c + 0.5)·factor − 0.5.
  Camera Scaled(double factor) const;

  bool InImage(const Eigen::Vector2d& pixel, double margin_px = 0.0) const;

  // Lists every violation ("fx = -3, must be > 0"), prefixed with `context`.
  Status Validate(const std::string& context = "camera") const;
};

}  // namespace bcot
