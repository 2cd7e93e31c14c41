#include "bcot/render/contour_drawing.h"

#include <algorithm>
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

void FillContour(const std::vector<ContourPoint>& contour, cv::Mat1b* mask) {
  BCOT_CHECK(mask != nullptr);
  // Scanline fill: for every row (centres at integer y) the x of each polygon edge crossing it,
  // an edge counting for the rows y0 <= y < y1 of its end points' span (half-open, so a
  // vertex on a row is crossed once), then the centres between the 1st and 2nd, 3rd and 4th,
  // ... sorted crossing.
  std::vector<std::vector<double>> crossings(mask->rows);
  for (size_t begin = 0; begin < contour.size();) {
    size_t end = begin + 1;
    while (end < contour.size() && contour[end].contour_id == contour[begin].contour_id) ++end;
    for (size_t i = begin; i < end; ++i) {
      const Eigen::Vector2d& a = contour[i].pixel;
      const Eigen::Vector2d& b = contour[i + 1 < end ? i + 1 : begin].pixel;
      if (!a.allFinite() || !b.allFinite() || a.y() == b.y()) continue;  // crosses no row
      const double y_low = std::min(a.y(), b.y());
      const double y_high = std::max(a.y(), b.y());
      const int first_row = static_cast<int>(std::max(0.0, std::ceil(y_low)));
      const int last_row = static_cast<int>(std::min<double>(mask->rows, std::ceil(y_high))) - 1;
      for (int row = first_row; row <= last_row; ++row) {
        crossings[row].push_back(a.x() + (row - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
      }
    }
    begin = end;
  }
  for (int row = 0; row < mask->rows; ++row) {
    std::vector<double>& x = crossings[row];
    std::sort(x.begin(), x.end());
    uchar* pixels = mask->ptr(row);
    for (size_t k = 0; k + 1 < x.size(); k += 2) {
      const double first = std::max(0.0, std::ceil(x[k]));
      const double last = std::min<double>(mask->cols - 1, std::floor(x[k + 1]));
      for (int col = static_cast<int>(first); col <= static_cast<int>(last); ++col) {
        pixels[col] = 255;
      }
    }
  }
}

}  // namespace bcot
