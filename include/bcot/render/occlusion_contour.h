// Occlusion contours: the image curves inside the silhouette where the mesh hides a part of
// itself (an ear in front of the head, one gear tooth in front of the next). Like the silhouette
// contour they are occluding contours of the surface, and the edge stage can measure the image
// step across them (frame_problem.h, `edge.occlusion_contours`): they constrain rotations out
// of the image plane, which change the silhouette least, from inside the object.
//
// Method (ExtractOcclusionContour):
//   1. a closest-hit render of the projected bounding box: depth z(x, y) per pixel;
//   2. candidate pairs of 4-neighbours p, q = p + e, both on the mesh, whose depths differ by
//      more than min_jump_fraction of the nearer one;
//   3. the normal n: the image gradient of z (central differences summed over p and q),
//      oriented from the near side to the far side; a pair is kept only along the axis e closer
//      to n, so each contour pixel gives one sample;
//   4. bisection along e, each time keeping the half bracket across which the ray depth changes
//      more, down to precision_px: a step of the surface keeps its size however small the
//      bracket, while a surface seen at a grazing angle, whose depth also changes fast from
//      pixel to pixel, does not; the pair is kept when the final bracket still spans half the
//      pair's depth change (and min_jump_fraction). The point is the bracket's centre, its
//      model point the hit at its near end.
// A ray that misses (background seen through a gap) counts as infinitely far; a final bracket
// that ends on a miss is the boundary of a hole in the silhouette and is left out.
//
// Frames and units as ray_caster.h (pixels: column x, row y, centre of pixel (0,0) at (0,0)).
// Thread safety: pure function of its arguments.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct OcclusionContourOptions {
  // Smallest depth step, as a fraction of the nearer depth (0.005: 3 mm at 600 mm); >= 0.
  double min_jump_fraction = 0.005;
  // Bisection stops when the bracket is below this width (px); in [1e-6, 0.5].
  double precision_px = 1.0 / 64.0;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// The occlusion contour samples of the mesh seen by `camera` at `cam_from_object`: pixel,
// unit normal from the near to the far surface, and model point (O_t, mm) on the near surface.
// `options` must be valid (CHECKed). Unordered; contour_id 0, is_hole false.
std::vector<ContourPoint> ExtractOcclusionContour(const RayCaster& caster, const Camera& camera,
                                                  const Eigen::Isometry3d& cam_from_object,
                                                  const OcclusionContourOptions& options = {});

}  // namespace bcot
