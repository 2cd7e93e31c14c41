// Embree ray caster for one mesh: renders the templates the region energies linearise around
// (depth, mask, normals, per-pixel model points) and the silhouette contour with exact 3D
// model points, for a camera and a pose cam_from_object (object = template frame O_t, mm).
//
// The BVH is built once, in the object frame; rays are transformed instead of the mesh.
// Thread safety: Render/ExtractContour are const and may run concurrently from many threads.
// A moved-from RayCaster may only be destroyed or assigned to.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/render/mesh.h"

namespace bcot {

struct RenderOptions {
  static constexpr int kMaxSamplesPerAxis = 16;

  // Region to render in image pixels; empty = the projected bounding box of the mesh
  // grown by `margin_px` and clipped to the image. A non-empty roi is rendered as given, also
  // where it extends beyond the image (rays exist there too).
  cv::Rect roi;
  // Pixels added on every side of the projected bounding box; >= 0.
  int margin_px = 2;
  // n×n rays per pixel on a regular grid: sample (i, j) of pixel (u, v) is at
  // (u − ½ + (i + ½)/n, v − ½ + (j + ½)/n). Output images are roi.size() × n. In [1, 16].
  int samples_per_axis = 1;
  // Which images besides the mask Render fills (RenderedView); the others are left empty
  // (0×0), saving their allocation, clearing and writes. Without any, the mask is traced with
  // occlusion rays (any hit), cheaper than closest-hit rays. Default: all.
  bool depth = true;
  bool normal_in_cam = true;
  bool point_in_object = true;
  bool triangle_id = true;
  // > 1: depth, normals, points and triangle ids only at pixels whose image column and row are
  // multiples of point_stride_px (closest-hit rays on that grid; elsewhere the miss values),
  // the mask at every pixel from occlusion rays. For templates that read the geometry on a
  // pixel stride. >= 1; > 1 needs samples_per_axis = 1.
  int point_stride_px = 1;
  // With point_stride_px > 1: true = the mask at every pixel (occlusion rays); false = only at
  // the stride pixels (their closest-hit rays), elsewhere 0, for callers that take the mask
  // from the contour (FillContour). Needs one of the images above when false.
  bool mask_everywhere = true;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// One rendered view. All images have the same size (roi × samples_per_axis), except those
// RenderOptions left out (empty); the pixel (c, r) of an image covers image position
// roi.tl() + ((c + ½)/n − ½, (r + ½)/n − ½).
struct RenderedView {
  cv::Rect roi;
  int samples_per_axis = 1;
  int point_stride_px = 1;    // RenderOptions::point_stride_px it was rendered with
  cv::Mat1b mask;             // 255 where a ray hits the mesh, else 0
  cv::Mat1f depth;            // camera-frame z in mm; 0 where missed
  cv::Mat3f normal_in_cam;    // unit geometric normal facing the camera; 0 where missed
  cv::Mat3f point_in_object;  // hit point in O_t (mm); 0 where missed
  cv::Mat1i triangle_id;      // hit triangle index, −1 where missed
};

// A silhouette contour sample at sub-pixel precision.
struct ContourPoint {
  // On the silhouette boundary (image coordinates): the centre of the final bisection
  // bracket, so within precision_px / 2 of the mesh's exact silhouette.
  Eigen::Vector2d pixel;
  // Unit 2D normal pointing out of the silhouette (on a hole's boundary: into the hole).
  Eigen::Vector2d normal;
  // Model point (O_t, mm): the hit of the ray at the inside end of the final bracket, so its
  // projection is within precision_px / 2 of `pixel` and it lies on the mesh surface.
  Eigen::Vector3d point_in_object;
  int contour_id = 0;    // index of the closed contour it belongs to (0, 1, ... consecutive)
  bool is_hole = false;  // true on the boundary of a hole in the silhouette
};

struct ContourOptions {
  // Grid step (px) of the coarse mask the contours are traced on; >= 1. Parts of the
  // silhouette thinner than this can be missed.
  int coarse_step_px = 2;
  // Spacing (px) of the returned samples along each traced contour; > 0.
  double sample_spacing_px = 1.0;
  // Bisection along the normal stops when the bracket is below this width (px); in
  // [1e-6, 0.5].
  double precision_px = 1.0 / 64.0;
  // Pixels added around the projected bounding box before tracing; >= 0.
  int margin_px = 4;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

class RayCaster {
 public:
  // Builds the Embree scene. Not copyable; movable.
  explicit RayCaster(const Mesh& mesh);
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  const Mesh& mesh() const;

  // Projected bounding box of the mesh's 8 bbox corners (exact hull for distortion-free
  // cameras; with distortion the 12 box edges are sampled since they project to curves),
  // grown by `margin_px`, clipped to the image. Empty when the whole box is behind the camera
  // (z <= 1e-3 mm) or projects outside the image. When the box straddles the camera plane, or
  // the distortion polynomial folds over at a sampled point, the projection is unbounded or
  // unreliable and the full image rectangle is returned.
  cv::Rect ProjectedBoundingBox(const Camera& camera, const Eigen::Isometry3d& cam_from_object,
                                int margin_px) const;

  // Ray-casts every (sub)pixel of the roi; directions come from Camera::PixelToRay, so lens
  // distortion is honoured. Rows run in parallel on the calling TBB arena. An empty roi (e.g.
  // object behind the camera) gives empty images. `options` must be valid (CHECKed).
  RenderedView Render(const Camera& camera, const Eigen::Isometry3d& cam_from_object,
                      const RenderOptions& options = {}) const;
  // The same into `view`, reusing its image buffers when their size is unchanged: in a
  // tracking loop this saves the allocation and page faults of ~33 bytes per ray.
  void Render(const Camera& camera, const Eigen::Isometry3d& cam_from_object,
              const RenderOptions& options, RenderedView* view) const;

  // Silhouette contours (outer boundaries and holes), each point refined along its normal by
  // bisection with occlusion rays, then intersected once for its exact model point.
  // Method: occlusion rays on a coarse_step_px grid over the projected bounding box →
  // cv::findContours (RETR_CCOMP: outer boundaries and holes) → samples every
  // sample_spacing_px along each traced polyline → per sample, a hit/miss bracket along the
  // polyline normal (steps <= 1 px, up to 2·coarse_step_px + 1 px either way) → bisection to
  // precision_px → the normal re-estimated from the refined neighbours. Samples without a
  // bracket (parts thinner than the step, clipped image borders) and samples outside the
  // image are dropped. Points are ordered along each contour. `options` must be valid.
  // `rendered` (optional): a Render at the same camera and pose with samples_per_axis 1 and
  // margin_px = options.margin_px (so the same roi; CHECKed); the coarse grid's samples are
  // then read from its mask instead of being traced again. They are pixel centres of that mask;
  // for a coarse step of 2^k px without distortion they are the very rays the contour would
  // cast (scaling the row's direction increment by 2^k is exact), so the contour is the same.
  std::vector<ContourPoint> ExtractContour(const Camera& camera,
                                           const Eigen::Isometry3d& cam_from_object,
                                           const ContourOptions& options = {},
                                           const RenderedView* rendered = nullptr) const;

  // Casts one ray through `pixel` (distortion honoured); returns the closest hit in O_t, and
  // in `triangle` (when given) the index into mesh().triangles() of the triangle hit.
  std::optional<Eigen::Vector3d> Intersect(const Camera& camera,
                                           const Eigen::Isometry3d& cam_from_object,
                                           const Eigen::Vector2d& pixel,
                                           int* triangle = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bcot
