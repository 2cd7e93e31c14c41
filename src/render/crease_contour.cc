#include "bcot/render/crease_contour.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "bcot/core/se3.h"
#include "bcot/core/violations.h"

namespace bcot {

Status CreaseContourOptions::Validate() const {
  std::vector<std::string> violations;
  if (!(min_angle_deg > 0.0 && min_angle_deg < 180.0)) {
    violations.push_back(fmt::format("min_angle_deg = {}, must be in (0, 180)", min_angle_deg));
  }
  if (!(sample_spacing_px > 0.0) || !std::isfinite(sample_spacing_px)) {
    violations.push_back(
        fmt::format("sample_spacing_px = {}, must be finite and > 0", sample_spacing_px));
  }
  if (!(clear_px >= 0.0) || !std::isfinite(clear_px)) {
    violations.push_back(fmt::format("clear_px = {}, must be finite and >= 0", clear_px));
  }
  return internal::JoinViolations("crease contour", violations);
}

namespace {

// Unit normal of a triangle from its winding (zero for a degenerate one).
Eigen::Vector3d TriangleNormal(const Mesh& mesh, int triangle) {
  const Eigen::Vector3i& t = mesh.triangles()[triangle];
  const Eigen::Vector3d p0 = mesh.vertices()[t[0]].cast<double>();
  const Eigen::Vector3d p1 = mesh.vertices()[t[1]].cast<double>();
  const Eigen::Vector3d p2 = mesh.vertices()[t[2]].cast<double>();
  const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
  const double norm = n.norm();
  return norm > 0.0 ? Eigen::Vector3d(n / norm) : Eigen::Vector3d::Zero();
}

// Rule 2 of the header for the sample at `pixel` of `crease`: the rays at ½, 1, …, clear_steps
// px to either side along `normal` (face a's side negative), and a pixel beside each along
// `tangent`, hit triangles whose normals are within the angle of `min_cos_side` of that side's
// face.
bool WindowOnOwnFaces(const RayCaster& caster, const Camera& camera,
                      const Eigen::Isometry3d& cam_from_object, const Crease& crease,
                      const Eigen::Vector2d& pixel, const Eigen::Vector2d& normal,
                      const Eigen::Vector2d& tangent, int clear_steps, double min_cos_side) {
  for (int step = 0; step <= clear_steps; ++step) {
    const double distance = std::max(0.5, static_cast<double>(step));
    for (int side = -1; side <= 1; side += 2) {
      const Eigen::Vector3d& face = side < 0 ? crease.normal_a : crease.normal_b;
      for (int lateral = -1; lateral <= 1; ++lateral) {
        int triangle = -1;
        const auto hit =
            caster.Intersect(camera, cam_from_object,
                             pixel + side * distance * normal + lateral * tangent, &triangle);
        if (!hit || triangle < 0 ||
            TriangleNormal(caster.mesh(), triangle).dot(face) < min_cos_side) {
          return false;
        }
      }
    }
  }
  return true;
}

}  // namespace

std::vector<Crease> FindCreases(const Mesh& mesh, double min_angle_deg) {
  BCOT_CHECK(min_angle_deg > 0.0 && min_angle_deg < 180.0);
  // Vertices welded by position: files that repeat a vertex per face still share their edges.
  std::map<std::array<float, 3>, int> welded;
  std::vector<int> weld_of(mesh.vertices().size());
  for (size_t i = 0; i < mesh.vertices().size(); ++i) {
    const Eigen::Vector3f& v = mesh.vertices()[i];
    weld_of[i] = welded.emplace(std::array<float, 3>{v.x(), v.y(), v.z()}, static_cast<int>(i))
                     .first->second;
  }
  // Per welded edge (lower id first): its triangles and, for each, the vertex off the edge.
  struct EdgeFaces {
    std::vector<std::pair<int, int>> faces;  // (triangle, its third vertex)
  };
  std::map<std::pair<int, int>, EdgeFaces> edges;
  for (size_t t = 0; t < mesh.triangles().size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles()[t];
    const std::array<int, 3> w = {weld_of[tri[0]], weld_of[tri[1]], weld_of[tri[2]]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;
    for (int k = 0; k < 3; ++k) {
      const int i = w[k], j = w[(k + 1) % 3];
      edges[{std::min(i, j), std::max(i, j)}].faces.emplace_back(static_cast<int>(t),
                                                                 w[(k + 2) % 3]);
    }
  }
  const double max_cos = std::cos(min_angle_deg * kPi / 180.0);
  std::vector<Crease> creases;
  for (const auto& [edge, faces] : edges) {
    if (faces.faces.size() != 2) continue;  // a border or a non-manifold edge
    const Eigen::Vector3d na = TriangleNormal(mesh, faces.faces[0].first);
    const Eigen::Vector3d nb = TriangleNormal(mesh, faces.faces[1].first);
    if (na.isZero() || nb.isZero() || !(na.dot(nb) < max_cos)) continue;
    Crease crease;
    crease.a = mesh.vertices()[edge.first].cast<double>();
    crease.b = mesh.vertices()[edge.second].cast<double>();
    crease.normal_a = na;
    crease.normal_b = nb;
    crease.opposite_a = mesh.vertices()[faces.faces[0].second].cast<double>();
    crease.opposite_b = mesh.vertices()[faces.faces[1].second].cast<double>();
    creases.push_back(crease);
  }
  return creases;
}

std::vector<ContourPoint> ExtractCreaseContour(const RayCaster& caster, const Camera& camera,
                                               const Eigen::Isometry3d& cam_from_object,
                                               const std::vector<Crease>& creases,
                                               const CreaseContourOptions& options) {
  BCOT_CHECK(options.Validate().ok());
  const Eigen::Matrix3d& cam_from_object_rotation = cam_from_object.linear();
  const double min_cos_side = std::cos(0.5 * options.min_angle_deg * kPi / 180.0);
  const int clear_steps = static_cast<int>(std::floor(options.clear_px + 1e-9));
  constexpr double kMinDepthMm = 1e-3;
  std::vector<ContourPoint> points;
  for (const Crease& crease : creases) {
    const Eigen::Vector3d a = cam_from_object * crease.a;
    const Eigen::Vector3d b = cam_from_object * crease.b;
    if (a.z() <= kMinDepthMm || b.z() <= kMinDepthMm) continue;
    // Both faces must face the camera (a face's points p have n·p < 0 in the camera frame).
    const Eigen::Vector3d na = cam_from_object_rotation * crease.normal_a;
    const Eigen::Vector3d nb = cam_from_object_rotation * crease.normal_b;
    if (!(na.dot(a) < 0.0) || !(nb.dot(a) < 0.0)) continue;
    const Eigen::Vector2d pa = camera.Project(a), pb = camera.Project(b);
    const int samples = static_cast<int>(std::floor((pb - pa).norm() / options.sample_spacing_px));
    if (samples < 1) continue;
    const Eigen::Vector3d opposite_a = cam_from_object * crease.opposite_a;
    const Eigen::Vector3d opposite_b = cam_from_object * crease.opposite_b;
    if (opposite_a.z() <= kMinDepthMm || opposite_b.z() <= kMinDepthMm) continue;
    const Eigen::Vector2d off_a = camera.Project(opposite_a), off_b = camera.Project(opposite_b);
    for (int k = 0; k < samples; ++k) {
      const double u = (k + 0.5) / samples;
      const Eigen::Vector3d x_in_object = crease.a + u * (crease.b - crease.a);
      const Eigen::Vector3d x = cam_from_object * x_in_object;
      const Eigen::Vector2d pixel = camera.Project(x);
      if (!camera.InImage(pixel, options.clear_px + 1.0)) continue;
      // The projection's local direction (distortion bends it) and its normal from a to b.
      const double du = std::min(0.5 / samples, 1e-3);
      const Eigen::Vector2d tangent =
          (camera.Project(a + (u + du) * (b - a)) - camera.Project(a + (u - du) * (b - a)))
              .normalized();
      Eigen::Vector2d normal(-tangent.y(), tangent.x());
      const double side_a = normal.dot(off_a - pixel), side_b = normal.dot(off_b - pixel);
      if (side_a * side_b >= 0.0) continue;  // a face seen edge-on
      if (side_a > 0.0) normal = -normal;
      // 1. Nothing in front of the sample: the ray through its pixel hits it (to 0.05 px).
      const std::optional<Eigen::Vector3d> hit = caster.Intersect(camera, cam_from_object, pixel);
      const double tolerance_mm = 0.05 * x.z() / std::min(camera.fx, camera.fy);
      if (!hit || (*hit - x_in_object).norm() > tolerance_mm) continue;
      // 2. The window holds this crease alone, also a pixel to either side along the crease
      //    (the blur and the bilinear samples reach that far, so a corner within a pixel is
      //    not a clean step).
      if (!WindowOnOwnFaces(caster, camera, cam_from_object, crease, pixel, normal, tangent,
                            clear_steps, min_cos_side)) {
        continue;
      }
      ContourPoint point;
      point.pixel = pixel;
      point.normal = normal;
      point.point_in_object = x_in_object;
      points.push_back(point);
    }
  }
  return points;
}

}  // namespace bcot
