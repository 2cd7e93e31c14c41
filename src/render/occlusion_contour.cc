#include "bcot/render/occlusion_contour.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "bcot/core/violations.h"

namespace bcot {

Status OcclusionContourOptions::Validate() const {
  std::vector<std::string> violations;
  if (!(min_jump_fraction >= 0.0) || !std::isfinite(min_jump_fraction)) {
    violations.push_back(
        fmt::format("min_jump_fraction = {}, must be finite and >= 0", min_jump_fraction));
  }
  if (!(precision_px >= 1e-6 && precision_px <= 0.5)) {
    violations.push_back(fmt::format("precision_px = {}, must be in [1e-6, 0.5]", precision_px));
  }
  return internal::JoinViolations("occlusion contour", violations);
}

namespace {

// The depth step a pixel pair's bisection must keep, as a fraction of the pair's (a surface seen
// at a grazing angle changes its depth by far less over 1/64 px than over a pixel).
constexpr double kRetainedJump = 0.5;

// The rendered depth of the view, with 0 where the ray missed (RenderedView::depth).
class DepthImage {
 public:
  explicit DepthImage(const RenderedView& view) : view_(view) {}

  // Depth at view pixel (col, row); 0 outside the render or where missed.
  double At(int col, int row) const {
    if (col < 0 || row < 0 || col >= view_.depth.cols || row >= view_.depth.rows) return 0.0;
    return view_.depth(row, col);
  }

  // Central-difference gradient at (col, row); a component is 0 where a neighbour missed.
  Eigen::Vector2d Gradient(int col, int row) const {
    Eigen::Vector2d g = Eigen::Vector2d::Zero();
    const double left = At(col - 1, row), right = At(col + 1, row);
    const double up = At(col, row - 1), down = At(col, row + 1);
    if (left > 0.0 && right > 0.0) g.x() = right - left;
    if (up > 0.0 && down > 0.0) g.y() = down - up;
    return g;
  }

 private:
  const RenderedView& view_;
};

}  // namespace

std::vector<ContourPoint> ExtractOcclusionContour(const RayCaster& caster, const Camera& camera,
                                                  const Eigen::Isometry3d& cam_from_object,
                                                  const OcclusionContourOptions& options) {
  BCOT_CHECK(options.Validate().ok());
  RenderOptions render_options;
  render_options.margin_px = 2;
  render_options.normal_in_cam = render_options.point_in_object = false;
  render_options.triangle_id = false;
  const RenderedView view = caster.Render(camera, cam_from_object, render_options);
  std::vector<ContourPoint> points;
  if (view.depth.empty()) return points;
  const DepthImage depth(view);
  // Depth of the closest hit through `pixel`; +inf on a miss (background behind a gap).
  auto hit_depth = [&](const Eigen::Vector2d& pixel) {
    const std::optional<Eigen::Vector3d> hit = caster.Intersect(camera, cam_from_object, pixel);
    return hit.has_value() ? (cam_from_object * *hit).z() : std::numeric_limits<double>::infinity();
  };
  for (int axis = 0; axis < 2; ++axis) {
    const int dx = axis == 0 ? 1 : 0;
    const int dy = 1 - dx;
    for (int row = 0; row < view.depth.rows; ++row) {
      for (int col = 0; col < view.depth.cols; ++col) {
        const double z_p = depth.At(col, row);
        const double z_q = depth.At(col + dx, row + dy);
        if (!(z_p > 0.0 && z_q > 0.0)) continue;
        const double jump = std::abs(z_q - z_p);
        if (jump < options.min_jump_fraction * std::min(z_p, z_q)) continue;
        const Eigen::Vector2d gradient =
            depth.Gradient(col, row) + depth.Gradient(col + dx, row + dy);
        // One sample per contour pixel: the pair along the axis nearer the normal.
        const bool along_x = std::abs(gradient.x()) >= std::abs(gradient.y());
        if (along_x != (axis == 0) || gradient.norm() == 0.0) continue;
        // Bisection towards the larger depth change: a step of the surface keeps its size in
        // an ever smaller bracket, a steep but continuous surface does not.
        Eigen::Vector2d a(view.roi.x + col, view.roi.y + row);
        Eigen::Vector2d b = a + Eigen::Vector2d(dx, dy);
        double z_a = hit_depth(a), z_b = hit_depth(b);
        if (std::isinf(z_a) || std::isinf(z_b)) continue;
        while ((b - a).norm() > options.precision_px) {
          const Eigen::Vector2d mid = 0.5 * (a + b);
          const double z_mid = hit_depth(mid);
          if (std::abs(z_mid - z_a) > std::abs(z_b - z_mid)) {
            b = mid;
            z_b = z_mid;
          } else {
            a = mid;
            z_a = z_mid;
          }
        }
        // A bracket ending on a miss is the boundary of a hole: the silhouette contour's.
        if (std::isinf(z_a) || std::isinf(z_b)) continue;
        const double step = std::abs(z_b - z_a);
        if (!(step >= kRetainedJump * jump) ||
            step < options.min_jump_fraction * std::min(z_a, z_b)) {
          continue;
        }
        const Eigen::Vector2d near_end = z_a < z_b ? a : b;
        const Eigen::Vector2d far_end = z_a < z_b ? b : a;
        ContourPoint point;
        point.pixel = 0.5 * (a + b);
        point.normal = gradient.normalized();
        if (point.normal.dot(far_end - near_end) < 0.0) point.normal = -point.normal;
        // The same ray as the bisection's at that end: its hit, on the near surface.
        point.point_in_object = *caster.Intersect(camera, cam_from_object, near_end);
        points.push_back(point);
      }
    }
  }
  return points;
}

}  // namespace bcot
