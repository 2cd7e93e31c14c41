// Drawing silhouette contours (RayCaster::ExtractContour) on images: the overlays of the
// quality report's thumbnails and of `bcot init`, and the silhouette masks filled from them.
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

// Sets to 255 every pixel of `mask` whose centre (integer coordinates) lies inside `contour`:
// each run of equal contour_id is a closed polygon (its last point joined to its first), and
// a centre is inside when a ray from it crosses the polygons an odd number of times, so holes
// stay empty. The other pixels are left as they are. With ExtractContour's samples this is
// the ray-cast mask of the silhouette except at pixel centres within its precision_px of the
// boundary and at parts thinner than its coarse grid, at the cost of a scan of the
// contour's edges. `mask` must not be null.
void FillContour(const std::vector<ContourPoint>& contour, cv::Mat1b* mask);

}  // namespace bcot
