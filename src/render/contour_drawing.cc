#include "bcot/render/contour_drawing.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "bcot/core/status.h"

namespace bcot {

void DrawContour(const std::vector<ContourPoint>& contour, const cv::Scalar& color, cv::Mat* image,
                 const Eigen::Vector2d& origin, double scale, int thickness) {
  BCOT_CHECK(image != nullptr);
  constexpr int kShift = 4;  // fixed-point bits for sub-pixel drawing
  std::vector<std::vector<cv::Point>> polylines;
  int current = -1;
  for (const ContourPoint& point : contour) {
    if (point.contour_id != current || polylines.empty()) {
      polylines.emplace_back();
      current = point.contour_id;
    }
    const Eigen::Vector2d p = (point.pixel - origin) * scale;
    polylines.back().emplace_back(int(std::lround(p.x() * (1 << kShift))),
                                  int(std::lround(p.y() * (1 << kShift))));
  }
  cv::polylines(*image, polylines, true, color, thickness, cv::LINE_AA, kShift);
}

}  // namespace bcot
