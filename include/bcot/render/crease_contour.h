// Crease contours: the mesh edges where two faces meet at an angle (a machined part's edges,
// the rim of a flange), seen inside the silhouette. The surface normal jumps across such an
// edge, so under any light that shades the two faces differently the image has a step there,
// and the blur being symmetric, the step's centre is the edge's projection. Unlike a smooth
// silhouette rim, whose last pixel is seen at a grazing angle and mirrors what lies beyond it
// (docs/notes/issue12_rim_shading.md), both faces of a seen crease face the camera. Like the
// occlusion contours (occlusion_contour.h) they constrain the pose from inside the object,
// rotations out of the image plane included (frame_problem.h, `edge.crease_contours`).
//
// Method:
//   FindCreases (per mesh): vertices welded by position; every edge shared by exactly two
//   triangles whose normals (from the winding, so the mesh's winding must be consistent)
//   differ by more than min_angle_deg.
//   ExtractCreaseContour (per view): a crease counts when both its faces face the camera. Its
//   3D segment is sampled so that the samples' projections lie about sample_spacing_px apart;
//   a sample is kept when
//     1. the ray through its pixel hits the mesh at the sample (nothing in front of it), and
//     2. the rays at ½, 1, 2, …, ⌊clear_px⌋ px to either side along the 2D normal, and those a
//        pixel beside them along the crease, hit triangles whose normals lie within
//        min_angle_deg / 2 of that side's face: the image window an edge line measures across
//        holds this one crease and no other edge, corner, silhouette or occluder.
//   The 2D normal points from the crease's face `a` to its face `b`; the model point is the
//   sample on the segment.
//
// Frames and units as ray_caster.h (pixels: column x, row y, centre of pixel (0,0) at (0,0)).
// Thread safety: pure functions of their arguments.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

// One crease of a mesh, in O_t (mm): the segment a–b, and per face its unit normal (from the
// winding) and its vertex off the segment.
struct Crease {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_b = Eigen::Vector3d::Zero();
  Eigen::Vector3d opposite_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d opposite_b = Eigen::Vector3d::Zero();
};

struct CreaseContourOptions {
  // Smallest angle (deg) between the normals of an edge's two faces for a crease; in (0, 180).
  // 60: a machined part's edges count (the pinion's: 490 of its 510 edges above 40° lie above
  // 60°, the spool's all 369), a coarse mesh of a smooth surface keeps few (the 3,674-triangle
  // bunny: 357 edges above 30°, 129 above 45°, 58 above 60°).
  double min_angle_deg = 60.0;
  // Spacing (px) of the samples along a crease's projection; > 0.
  double sample_spacing_px = 1.0;
  // Half-width (px) of the window that must lie on the crease's own faces (rule 2); >= 0.
  // The edge stage sets it to its lines' window.
  double clear_px = 4.0;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// The creases of `mesh` sharper than `min_angle_deg` (in (0, 180), CHECKed).
std::vector<Crease> FindCreases(const Mesh& mesh, double min_angle_deg);

// The crease contour samples of `creases` (FindCreases of caster.mesh() with
// options.min_angle_deg) seen by `camera` at `cam_from_object`: pixel, unit normal from face a
// to face b, model point (O_t, mm). `options` must be valid (CHECKed). Unordered; contour_id 0,
// is_hole false.
std::vector<ContourPoint> ExtractCreaseContour(const RayCaster& caster, const Camera& camera,
                                               const Eigen::Isometry3d& cam_from_object,
                                               const std::vector<Crease>& creases,
                                               const CreaseContourOptions& options = {});

}  // namespace bcot
