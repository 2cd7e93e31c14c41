// Step 5 of the quality measurement (bcot/quality/quality_report.h): the part of the raw
// boundary offsets that one small rigid motion of the object explains.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

// The offsets along the normals that the best rigid motion of the object explains (step 5):
// robust (Huber, then Tukey) least squares fit of a small motion δ = (ω, v) about
// `object_centre` (object frame) to the finite `offsets` (one per contour point, NaN = none),
// with the first-order model offset_i = n_iᵀ · ∂x_i/∂δ · δ; returns that model's offset at every
// contour point (all NaN when fewer than 6 offsets carry weight). `scale_px` > 0.
std::vector<double> FitRigidMotionOffsets(const std::vector<ContourPoint>& contour,
                                          const std::vector<double>& offsets, const Camera& camera,
                                          const Eigen::Isometry3d& cam_from_object,
                                          const Eigen::Vector3d& object_centre, double scale_px);

}  // namespace bcot
