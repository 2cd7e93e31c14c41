// Rays through pixels of a rig's cameras and the least-squares point closest to several of
// them (bcot init: the object centre from a click in each of two or more views).
//
// A pixel's ray starts at the camera centre o = rig_from_cam · 0 and runs along the unit
// direction d = R_rig_from_cam · PixelToRay(pixel) / |·| (lens distortion undone by
// Camera::PixelToRay). The triangulated point minimises the sum of squared distances to the
// rays, Σ_i |(I − d_i d_iᵀ)(X − o_i)|², i.e. solves
//
//   Σ_i (I − d_i d_iᵀ) · X = Σ_i (I − d_i d_iᵀ) · o_i
//
// (for two rays: the midpoint of their common perpendicular). Frames: rig, mm.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

struct RigRay {
  Eigen::Vector3d origin_in_rig = Eigen::Vector3d::Zero();      // camera centre, mm
  Eigen::Vector3d direction_in_rig = Eigen::Vector3d::UnitZ();  // unit
};

// The ray of `camera` through `pixel` (any pixel position; distortion honoured).
RigRay PixelRayInRig(const RigCamera& camera, const Eigen::Vector2d& pixel);

// The least-squares point of the rays (see the header comment). kInvalidInput when there are
// fewer than two rays, when they are (nearly) parallel (the normal matrix's smallest
// eigenvalue below 1e-6, i.e. under ~0.06° between the most different rays), or when the point
// lies behind the centre of one of them.
StatusOr<Eigen::Vector3d> TriangulateRays(const std::vector<RigRay>& rays);

// Distance (mm) of `point_in_rig` from the ray.
double DistanceToRay(const RigRay& ray, const Eigen::Vector3d& point_in_rig);

}  // namespace bcot
