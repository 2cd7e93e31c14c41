#include "bcot/core/triangulation.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>

namespace bcot {

RigRay PixelRayInRig(const RigCamera& camera, const Eigen::Vector2d& pixel) {
  const Eigen::Isometry3d rig_from_cam = camera.cam_from_rig.inverse();
  RigRay ray;
  ray.origin_in_rig = rig_from_cam.translation();
  ray.direction_in_rig = (rig_from_cam.linear() * camera.camera.PixelToRay(pixel)).normalized();
  return ray;
}

StatusOr<Eigen::Vector3d> TriangulateRays(const std::vector<RigRay>& rays) {
  if (rays.size() < 2) {
    return Status::InvalidInput(
        fmt::format("triangulation needs at least two rays, got {}", rays.size()));
  }
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right = Eigen::Vector3d::Zero();
  for (const RigRay& ray : rays) {
    const Eigen::Vector3d& d = ray.direction_in_rig;
    const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - d * d.transpose();
    normal += projector;
    right += projector * ray.origin_in_rig;
  }
  // Normalised by the ray count: the eigenvalue along the common direction of parallel rays
  // is 0, and grows like sin² of the angle between them.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(normal / rays.size());
  if (eigen.eigenvalues().minCoeff() < 1e-6) {
    return Status::InvalidInput(
        "the rays are (nearly) parallel: the clicks do not fix a point in depth");
  }
  const Eigen::Vector3d point = normal.ldlt().solve(right);
  for (size_t i = 0; i < rays.size(); ++i) {
    if ((point - rays[i].origin_in_rig).dot(rays[i].direction_in_rig) <= 0.0) {
      return Status::InvalidInput(fmt::format(
          "the rays meet behind the centre of ray {} (the clicks do not show one point)", i + 1));
    }
  }
  return point;
}

double DistanceToRay(const RigRay& ray, const Eigen::Vector3d& point_in_rig) {
  const Eigen::Vector3d offset = point_in_rig - ray.origin_in_rig;
  return (offset - offset.dot(ray.direction_in_rig) * ray.direction_in_rig).norm();
}

}  // namespace bcot
