#include "bcot/render/interior_edges.h"

#include <algorithm>
#include <cmath>

#include "bcot/core/status.h"
#include "bcot/render/occlusion_contour.h"

namespace bcot {

namespace {

// Cells per side at the most: a tiny tolerance over a large image coarsens the grid instead of
// allocating it (a query reads the cells within one of its own, which covers the reach as long
// as a cell is at least the tolerance).
constexpr double kMaxCellsPerSide = 1024.0;

}  // namespace

InteriorEdges::InteriorEdges(const std::vector<ContourPoint>& points, double tolerance_px)
    : tolerance_px_(tolerance_px) {
  BCOT_CHECK(tolerance_px > 0.0 && std::isfinite(tolerance_px));
  points_.reserve(points.size());
  for (const ContourPoint& point : points) {
    if (point.pixel.allFinite()) points_.push_back(point.pixel);
  }
  if (points_.empty()) return;
  Eigen::Vector2d lower = points_.front(), upper = points_.front();
  for (const Eigen::Vector2d& point : points_) {
    lower = lower.cwiseMin(point);
    upper = upper.cwiseMax(point);
  }
  origin_ = lower;
  cell_px_ = std::max(tolerance_px, (upper - lower).maxCoeff() / kMaxCellsPerSide);
  columns_ = static_cast<int>(std::floor((upper.x() - lower.x()) / cell_px_)) + 1;
  rows_ = static_cast<int>(std::floor((upper.y() - lower.y()) / cell_px_)) + 1;
  // Counting sort of the samples by cell.
  std::vector<int> cell_of(points_.size());
  cell_start_.assign(static_cast<size_t>(columns_) * rows_ + 1, 0);
  for (size_t i = 0; i < points_.size(); ++i) {
    const Eigen::Vector2d cell = (points_[i] - origin_) / cell_px_;
    const int column = std::min(static_cast<int>(cell.x()), columns_ - 1);
    const int row = std::min(static_cast<int>(cell.y()), rows_ - 1);
    cell_of[i] = row * columns_ + column;
    ++cell_start_[cell_of[i] + 1];
  }
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  std::vector<Eigen::Vector2d> sorted(points_.size());
  for (size_t i = 0; i < points_.size(); ++i) sorted[next[cell_of[i]]++] = points_[i];
  points_ = std::move(sorted);
}

bool InteriorEdges::Claims(const Eigen::Vector2d& silhouette, const Eigen::Vector2d& found) const {
  if (points_.empty() || !found.allFinite() || !silhouette.allFinite()) return false;
  const double reach = std::min(tolerance_px_, (found - silhouette).norm());
  const Eigen::Vector2d cell = (found - origin_) / cell_px_;
  // More than a cell beyond the samples' box (cell coordinates [0, columns_) × [0, rows_)): no
  // sample within the reach.
  if (cell.x() < -1.0 || cell.y() < -1.0 || cell.x() > columns_ + 1.0 || cell.y() > rows_ + 1.0) {
    return false;
  }
  const int column = static_cast<int>(std::floor(cell.x()));
  const int row = static_cast<int>(std::floor(cell.y()));
  for (int r = std::max(row - 1, 0); r <= std::min(row + 1, rows_ - 1); ++r) {
    for (int c = std::max(column - 1, 0); c <= std::min(column + 1, columns_ - 1); ++c) {
      const int index = r * columns_ + c;
      for (int k = cell_start_[index]; k < cell_start_[index + 1]; ++k) {
        if ((points_[k] - found).squaredNorm() < reach * reach) return true;
      }
    }
  }
  return false;
}

InteriorEdges ProjectInteriorEdges(const RayCaster& caster, const Camera& camera,
                                   const Eigen::Isometry3d& cam_from_object,
                                   const std::vector<Crease>& creases, double crease_min_angle_deg,
                                   bool occlusion_contours, double tolerance_px) {
  CreaseContourOptions options;
  options.min_angle_deg = crease_min_angle_deg;
  options.clear_px = 0.0;
  options.sample_spacing_px = tolerance_px;
  std::vector<ContourPoint> points =
      ExtractCreaseContour(caster, camera, cam_from_object, creases, options);
  if (occlusion_contours) {
    const std::vector<ContourPoint> occlusion =
        ExtractOcclusionContour(caster, camera, cam_from_object);
    points.insert(points.end(), occlusion.begin(), occlusion.end());
  }
  return InteriorEdges(points, tolerance_px);
}

}  // namespace bcot
