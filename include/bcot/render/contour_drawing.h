// Drawing silhouette contours (RayCaster::ExtractContour) on images: the overlays of the
// quality report's thumbnails and of `bcot init`.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "bcot/render/ray_caster.h"

namespace bcot {

// Draws every contour of `contour` (one closed, anti-aliased polyline per contour_id, at
// sub-pixel precision) on `image` (8-bit, any channel count matching `color`), each point
// mapped to (pixel − origin)·scale: origin = a crop's top-left corner, scale = its resize
// factor. `image` must not be null.
void DrawContour(const std::vector<ContourPoint>& contour, const cv::Scalar& color, cv::Mat* image,
                 const Eigen::Vector2d& origin = Eigen::Vector2d::Zero(), double scale = 1.0,
                 int thickness = 1);

}  // namespace bcot
