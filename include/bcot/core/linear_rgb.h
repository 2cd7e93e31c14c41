// Linear (radiance-proportional) RGB from 8-bit sRGB images. Optical blur acts on radiance, so
// the centre of a blurred step is found on linear values; on gamma-encoded values it moves
// towards the step's dark side.
#pragma once

#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>

namespace bcot {

// linear value of each 8-bit sRGB code (IEC 61966-2-1 decoding), in [0, 1].
const std::array<float, 256>& SrgbToLinearTable();

// True when bilinear sampling at `p` stays inside an image of `size` (p and its 2×2
// neighbours: 0 <= x < width − 1, 0 <= y < height − 1).
inline bool CanSampleBilinear(const cv::Size& size, const Eigen::Vector2d& p) {
  return p.x() >= 0.0 && p.y() >= 0.0 && p.x() < size.width - 1.0 && p.y() < size.height - 1.0;
}

// Bilinear linear-RGB colour (R, G, B order) of the BGR image at `p`; requires
// CanSampleBilinear(image.size(), p).
Eigen::Vector3d SampleLinearRgb(const cv::Mat3b& image, const Eigen::Vector2d& p);

// Per channel (R, G, B), the largest linear value among the pixels SampleLinearRgb mixes at `p`
// (those with a non-zero weight): tells whether a sample rests on a clipped pixel. Same
// requirement as SampleLinearRgb.
Eigen::Vector3d PeakLinearRgb(const cv::Mat3b& image, const Eigen::Vector2d& p);

}  // namespace bcot
