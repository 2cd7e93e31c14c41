// The model's interior edges seen in one view, and which steps found near its silhouette they
// claim. Besides its silhouette, a mesh shows edges of its own inside it: its creases
// (crease_contour.h), where two faces meet at an angle, and its occlusion contours
// (occlusion_contour.h), where one part hides another. Both are steps in the image, and beside a
// silhouette without contrast they can be the stronger step within a few pixels of it: the rim
// of a spool's flange 3 px inside the silhouette of the spool seen almost end-on, where the
// flange's cylindrical side has the background's colour. A step found along a silhouette normal
// is attributed to the nearest of the model's edges: to an interior edge when one lies within
// `tolerance_px` of the step and nearer to it than the silhouette point (the step then says
// nothing about where the silhouette is). Used by the quality check (step 4b of
// bcot/quality/quality_report.h); in the edge stage's silhouette lines the same rule changed too
// few lines to matter (docs/notes/issue12_crease_contours.md, last section).
//
// Frames and units as ray_caster.h (pixels: column x, row y, centre of pixel (0,0) at (0,0)).
// Thread safety: const methods are safe to call concurrently.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/render/crease_contour.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

class InteriorEdges {
 public:
  // `points`: the interior edges' samples (pixels; spaced at most tolerance_px apart along
  // each edge, so a step on the edge lies within tolerance_px / 2 of one; non-finite ones are
  // left out); tolerance_px > 0 and finite (CHECKed).
  InteriorEdges(const std::vector<ContourPoint>& points, double tolerance_px);

  // Whether the step found at `found` along the normal of silhouette point `silhouette` lies
  // within tolerance_px of an interior edge sample and nearer to it than to `silhouette`.
  bool Claims(const Eigen::Vector2d& silhouette, const Eigen::Vector2d& found) const;

  int size() const { return static_cast<int>(points_.size()); }

 private:
  double tolerance_px_;
  // Samples bucketed into square cells of side cell_px_ (tolerance_px, or more where the samples
  // spread over more than 1,024 of them) over their bounding box, so a query reads the 3×3
  // cells around it.
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_px_ = 1.0;
  int columns_ = 0, rows_ = 0;
  std::vector<int> cell_start_;  // cells' ranges in points_, size columns_·rows_ + 1
  std::vector<Eigen::Vector2d> points_;
};

// The interior edges of `caster`'s mesh seen by `camera` at `cam_from_object` (O_t, mm):
// every seen sample of `creases` (FindCreases of the mesh), however close to another edge, one
// per tolerance_px, and with `occlusion_contours` also the occlusion contour (a depth render of
// the object's box: the larger cost).
InteriorEdges ProjectInteriorEdges(const RayCaster& caster, const Camera& camera,
                                   const Eigen::Isometry3d& cam_from_object,
                                   const std::vector<Crease>& creases, double crease_min_angle_deg,
                                   bool occlusion_contours, double tolerance_px);

}  // namespace bcot
