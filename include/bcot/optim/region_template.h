// The per-view linearisation template of the region energy for one round (DESIGN.md "Region
// energy" and "Rounds"; paper eq. 5–6, supplement §A): the band pixels around the silhouette
// projected at T0 = rig_from_objcentre, each with what RegionCostFunction needs to write its
// residual as an explicit function of the pose T.
//
// For every band pixel x (integer pixel centre, every stride_px-th row and column):
//   Φ0(x)   signed distance (px) to the projected contour at T0, negative inside. It is
//           computed from the exact sub-pixel contour of RayCaster::ExtractContour: with c the
//           nearest contour point and n its outward normal, Φ0 = sign((x − c)·n)·|x − c|.
//   ∇Φ0(x)  = n, the unit outward normal of the nearest contour point.
//   X       the attached model point in O_o: inside the rendered silhouette the surface point
//           under the pixel (from the render, O_t → O_o); outside, the model point of the
//           nearest contour point.
//   x_X(T0) = π(cam_from_rig · T0 · X), its projection at T0 (≈ x inside, ≈ c outside).
//   P_f(x)  from the view's colour model (P_b = 1 − P_f).
// The band is |Φ0| <= band_px, inside the image. Pixels whose nearest contour point is
// farther than band_px are dropped (e.g. where the contour was clipped at the image border).
//
// Frames: cam_from_rig (view extrinsics), rig_from_objcentre (the parameter block, O_o),
// objcentre_from_template from the caster's mesh; mm and px.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct RegionTemplateOptions {
  RegionTemplateOptions();
  // Half-width (px) of the band around the projected contour: pixels with |Φ0| <= band_px;
  // > 0. It bounds the capture range of one round (the contour must move less than this).
  double band_px = 12.0;
  // Subsampling: only pixels whose column and row are multiples of stride_px; >= 1. A
  // 640×480 view of a ~150 px object gives about 2–5k pixels at stride 2 with band_px 12.
  int stride_px = 2;
  // Contour extraction; defaults as ContourOptions except sample_spacing_px = 0.5, so the
  // nearest contour sample is within 0.25 px along the contour of the true nearest point.
  ContourOptions contour;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

struct RegionPixel {
  Eigen::Vector2d pixel;               // x, image coordinates (integer centre)
  double phi0 = 0.0;                   // Φ0(x), px, negative inside
  Eigen::Vector2d grad_phi0;           // ∇Φ0(x), unit
  Eigen::Vector3d point_in_objcentre;  // X in O_o, mm
  Eigen::Vector2d projection0;         // x_X(T0), px
  double p_foreground = 0.5;           // P_f(x)
  double p_background = 0.5;           // P_b(x) = 1 − P_f(x)
  bool inside = false;                 // rendered mask at x (X is the surface point under x)
};

struct RegionTemplate {
  Eigen::Isometry3d rig_from_objcentre = Eigen::Isometry3d::Identity();  // T0
  std::vector<RegionPixel> pixels;
};

// Builds the template of one view at T0. `silhouette` must be RenderSilhouette at
// cam_from_rig · T0 · objcentre_from_template (pass the one the colour model was updated
// with, or use the overload that renders it). Errors (kInvalidConfig / kInvalidInput): invalid
// options, invalid camera, image size different from the camera's, silhouette mask of another
// size, stride_px not a multiple of the silhouette's point stride (its model points exist only
// on that grid, see RenderSilhouette). An object outside the view gives an empty template (not an
// error).
StatusOr<RegionTemplate> BuildRegionTemplate(const RayCaster& caster, const Camera& camera,
                                             const Eigen::Isometry3d& cam_from_rig,
                                             const Eigen::Isometry3d& rig_from_objcentre,
                                             const cv::Mat3b& image, const ColorModel& color_model,
                                             const Silhouette& silhouette,
                                             const RegionTemplateOptions& options = {});
// The same, rendering the silhouette itself.
StatusOr<RegionTemplate> BuildRegionTemplate(const RayCaster& caster, const Camera& camera,
                                             const Eigen::Isometry3d& cam_from_rig,
                                             const Eigen::Isometry3d& rig_from_objcentre,
                                             const cv::Mat3b& image, const ColorModel& color_model,
                                             const RegionTemplateOptions& options = {});

}  // namespace bcot
