#include "bcot/optim/region_template.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bcot/core/violations.h"

namespace bcot {

RegionTemplateOptions::RegionTemplateOptions() { contour.sample_spacing_px = 0.5; }

Status RegionTemplateOptions::Validate() const {
  std::vector<std::string> violations;
  if (!(band_px > 0.0) || !std::isfinite(band_px)) {
    violations.push_back(fmt::format("band_px = {}, must be finite and > 0", band_px));
  }
  if (stride_px < 1) {
    violations.push_back(fmt::format("stride_px = {}, must be >= 1", stride_px));
  }
  const Status contour_status = contour.Validate();
  if (!contour_status.ok()) violations.push_back("contour: " + contour_status.message());
  return internal::JoinViolations("region_template", violations);
}

namespace {

// Uniform grid over the contour points for nearest-neighbour queries within `cell` px.
class ContourGrid {
 public:
  ContourGrid(const std::vector<ContourPoint>& contour, double cell) : cell_(cell) {
    min_ = contour[0].pixel;
    Eigen::Vector2d max = contour[0].pixel;
    for (const ContourPoint& point : contour) {
      min_ = min_.cwiseMin(point.pixel);
      max = max.cwiseMax(point.pixel);
    }
    cols_ = static_cast<int>((max.x() - min_.x()) / cell_) + 1;
    rows_ = static_cast<int>((max.y() - min_.y()) / cell_) + 1;
    cells_.resize(static_cast<size_t>(cols_) * rows_);
    for (size_t i = 0; i < contour.size(); ++i) {
      const Eigen::Vector2i c = CellOf(contour[i].pixel);
      cells_[static_cast<size_t>(c.y()) * cols_ + c.x()].push_back(static_cast<int>(i));
    }
  }

  // Index of the nearest contour point within the 3×3 cells around `pixel` (so every point
  // closer than `cell` is considered), or −1.
  int Nearest(const std::vector<ContourPoint>& contour, const Eigen::Vector2d& pixel,
              double* distance_squared) const {
    const Eigen::Vector2i centre = CellOf(pixel);
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int gy = centre.y() - 1; gy <= centre.y() + 1; ++gy) {
      if (gy < 0 || gy >= rows_) continue;
      for (int gx = centre.x() - 1; gx <= centre.x() + 1; ++gx) {
        if (gx < 0 || gx >= cols_) continue;
        for (int i : cells_[static_cast<size_t>(gy) * cols_ + gx]) {
          const double d2 = (contour[i].pixel - pixel).squaredNorm();
          if (d2 < best_d2) {
            best_d2 = d2;
            best = i;
          }
        }
      }
    }
    *distance_squared = best_d2;
    return best;
  }

 private:
  Eigen::Vector2i CellOf(const Eigen::Vector2d& pixel) const {
    return Eigen::Vector2i(static_cast<int>(std::floor((pixel.x() - min_.x()) / cell_)),
                           static_cast<int>(std::floor((pixel.y() - min_.y()) / cell_)));
  }

  double cell_;
  Eigen::Vector2d min_;
  int cols_ = 0;
  int rows_ = 0;
  std::vector<std::vector<int>> cells_;
};

}  // namespace

StatusOr<RegionTemplate> BuildRegionTemplate(const RayCaster& caster, const Camera& camera,
                                             const Eigen::Isometry3d& cam_from_rig,
                                             const Eigen::Isometry3d& rig_from_objcentre,
                                             const cv::Mat3b& image, const ColorModel& color_model,
                                             const Silhouette& silhouette,
                                             const RegionTemplateOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_RETURN_IF_ERROR(CheckSilhouetteInputs(camera, image, silhouette));
  if (options.stride_px % silhouette.view.point_stride_px != 0) {
    return Status::InvalidInput(fmt::format(
        "camera '{}': silhouette rendered with point stride {} px, the template's stride_px = {} "
        "is not a multiple of it",
        camera.name, silhouette.view.point_stride_px, options.stride_px));
  }
  RegionTemplate result;
  result.rig_from_objcentre = rig_from_objcentre;
  const std::vector<ContourPoint>& contour = silhouette.contour;
  if (contour.empty()) return result;

  const Eigen::Isometry3d objcentre_from_template = caster.mesh().objcentre_from_template();
  const Eigen::Isometry3d cam_from_objcentre = cam_from_rig * rig_from_objcentre;
  const double band = options.band_px;
  const int stride = options.stride_px;
  const ContourGrid grid(contour, band);

  Eigen::Vector2d lo = contour[0].pixel;
  Eigen::Vector2d hi = contour[0].pixel;
  for (const ContourPoint& point : contour) {
    lo = lo.cwiseMin(point.pixel);
    hi = hi.cwiseMax(point.pixel);
  }
  auto first_multiple = [stride](double value) {
    const int v = std::max(0, static_cast<int>(std::ceil(value)));
    return (v + stride - 1) / stride * stride;
  };
  const int x_begin = first_multiple(lo.x() - band);
  const int y_begin = first_multiple(lo.y() - band);
  const int x_end = std::min(camera.width - 1, static_cast<int>(std::floor(hi.x() + band)));
  const int y_end = std::min(camera.height - 1, static_cast<int>(std::floor(hi.y() + band)));

  const RenderedView& view = silhouette.view;
  std::vector<Eigen::Vector2i> integer_pixels;
  for (int y = y_begin; y <= y_end; y += stride) {
    for (int x = x_begin; x <= x_end; x += stride) {
      const Eigen::Vector2d pixel(x, y);
      double distance_squared = 0.0;
      const int nearest = grid.Nearest(contour, pixel, &distance_squared);
      if (nearest < 0 || distance_squared > band * band) continue;
      const ContourPoint& c = contour[nearest];
      RegionPixel region_pixel;
      region_pixel.pixel = pixel;
      const double distance = std::sqrt(distance_squared);
      region_pixel.phi0 = (pixel - c.pixel).dot(c.normal) < 0.0 ? -distance : distance;
      region_pixel.grad_phi0 = c.normal.normalized();
      // The surface point under an inside pixel, else the nearest contour point's.
      Eigen::Vector3d point_in_template = c.point_in_object;
      const int view_col = x - view.roi.x;
      const int view_row = y - view.roi.y;
      if (silhouette.mask(y, x) != 0 && view.samples_per_axis == 1 && view_col >= 0 &&
          view_row >= 0 && view_col < view.mask.cols && view_row < view.mask.rows &&
          view.mask(view_row, view_col) != 0) {
        const cv::Vec3f& p = view.point_in_object(view_row, view_col);
        point_in_template = Eigen::Vector3d(p[0], p[1], p[2]);
        region_pixel.inside = true;
      }
      region_pixel.point_in_objcentre = objcentre_from_template * point_in_template;
      const Eigen::Vector3d point_in_cam = cam_from_objcentre * region_pixel.point_in_objcentre;
      if (!(point_in_cam.z() > 0.0)) continue;
      region_pixel.projection0 = camera.Project(point_in_cam);
      result.pixels.push_back(region_pixel);
      integer_pixels.emplace_back(x, y);
    }
  }
  const std::vector<double> foreground = color_model.ForegroundPosteriors(image, integer_pixels);
  for (size_t i = 0; i < result.pixels.size(); ++i) {
    result.pixels[i].p_foreground = foreground[i];
    result.pixels[i].p_background = 1.0 - foreground[i];
  }
  return result;
}

StatusOr<RegionTemplate> BuildRegionTemplate(const RayCaster& caster, const Camera& camera,
                                             const Eigen::Isometry3d& cam_from_rig,
                                             const Eigen::Isometry3d& rig_from_objcentre,
                                             const cv::Mat3b& image, const ColorModel& color_model,
                                             const RegionTemplateOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_RETURN_IF_ERROR(camera.Validate());
  const Eigen::Isometry3d cam_from_template =
      cam_from_rig * rig_from_objcentre * caster.mesh().objcentre_from_template();
  const Silhouette silhouette =
      RenderSilhouette(caster, camera, cam_from_template, options.contour);
  return BuildRegionTemplate(caster, camera, cam_from_rig, rig_from_objcentre, image, color_model,
                             silhouette, options);
}

}  // namespace bcot
