#include "bcot/core/linear_rgb.h"

#include <cmath>

namespace bcot {

const std::array<float, 256>& SrgbToLinearTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double v = i / 255.0;
      t[i] = static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table;
}

Eigen::Vector3d SampleLinearRgb(const cv::Mat3b& image, const Eigen::Vector2d& p) {
  const std::array<float, 256>& lut = SrgbToLinearTable();
  const int x0 = static_cast<int>(std::floor(p.x()));
  const int y0 = static_cast<int>(std::floor(p.y()));
  const double fx = p.x() - x0, fy = p.y() - y0;
  const double weights[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const int dx[4] = {0, 1, 0, 1}, dy[4] = {0, 0, 1, 1};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    const cv::Vec3b& px = image(y0 + dy[k], x0 + dx[k]);
    sum += weights[k] * Eigen::Vector3d(lut[px[2]], lut[px[1]], lut[px[0]]);
  }
  return sum;
}

Eigen::Vector3d PeakLinearRgb(const cv::Mat3b& image, const Eigen::Vector2d& p) {
  const std::array<float, 256>& lut = SrgbToLinearTable();
  const int x0 = static_cast<int>(std::floor(p.x()));
  const int y0 = static_cast<int>(std::floor(p.y()));
  const int x1 = p.x() > x0 ? x0 + 1 : x0;
  const int y1 = p.y() > y0 ? y0 + 1 : y0;
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const cv::Vec3b& px = image(y, x);
      peak = peak.cwiseMax(Eigen::Vector3d(lut[px[2]], lut[px[1]], lut[px[0]]));
    }
  }
  return peak;
}

}  // namespace bcot
