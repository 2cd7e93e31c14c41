#include "bcot/render/crease_contour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "test_meshes.h"
#include "test_util.h"

namespace bcot {
namespace {

Camera TestCamera() { return Camera("test", 640, 512, 600.0, 600.0, 320.0, 256.0); }

// A box centred 400 mm in front of the camera, turned so that three of its faces are seen.
Eigen::Isometry3d ObliqueBoxPose() {
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.linear() = (Eigen::AngleAxisd(0.55, Eigen::Vector3d::UnitX()) *
                              Eigen::AngleAxisd(0.75, Eigen::Vector3d::UnitY()))
                                 .toRotationMatrix();
  cam_from_object.translation() = Eigen::Vector3d(5, -3, 400);
  return cam_from_object;
}

// The corner of the box with half sides `half` (centred at the origin) nearest to the camera.
Eigen::Vector3d NearestCorner(const Eigen::Vector3d& half,
                              const Eigen::Isometry3d& cam_from_object) {
  Eigen::Vector3d nearest = half;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                            (i & 4) ? half.z() : -half.z());
    if ((cam_from_object * c).z() < (cam_from_object * nearest).z()) nearest = c;
  }
  return nearest;
}

TEST(CreaseContourOptionsTest, ValidateNamesEveryViolation) {
  EXPECT_TRUE(CreaseContourOptions().Validate().ok());
  CreaseContourOptions options;
  options.min_angle_deg = 180.0;
  options.sample_spacing_px = 0.0;
  options.clear_px = -1.0;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"min_angle_deg = 180", "sample_spacing_px = 0", "clear_px = -1"});
}

// A box's 12 edges are its creases (90°); the diagonals that split its faces (0°) are not, and
// neither is any edge of a finely tessellated torus (7.5° between neighbouring facets).
TEST(CreaseContourTest, FindsTheEdgesOfABoxAndNoneOfASmoothSurface) {
  const std::vector<Crease> creases = FindCreases(test::MakeBox(Eigen::Vector3d(30, 20, 10)), 40.0);
  ASSERT_EQ(creases.size(), 12u);
  for (const Crease& crease : creases) {
    EXPECT_NEAR(crease.normal_a.dot(crease.normal_b), 0.0, 1e-12);
    // Both ends on the box's corners, the segment along one axis.
    const Eigen::Vector3d d = (crease.b - crease.a).cwiseAbs();
    EXPECT_EQ((d.array() > 0.0).count(), 1);
    // Each face's off-edge vertex lies in that face's plane.
    EXPECT_NEAR(crease.normal_a.dot(crease.opposite_a - crease.a), 0.0, 1e-9);
    EXPECT_NEAR(crease.normal_b.dot(crease.opposite_b - crease.a), 0.0, 1e-9);
  }
  EXPECT_TRUE(FindCreases(test::MakeTorus(40.0, 12.0, 160, 48), 40.0).empty());
}

// A box seen obliquely shows three faces; the three edges between them are the seen creases.
// Every sample lies on one of them (its model point on the edge, projecting onto its pixel),
// its normal crosses the edge's projection, and the window of clear_px either side lies on the
// edge's own two faces (also a pixel beside the sample), so no sample lies within a pixel of the
// corner where the three meet.
TEST(CreaseContourTest, ObliqueBoxGivesItsThreeSeenEdgesAwayFromTheCorner) {
  const Eigen::Vector3d half(30, 30, 30);
  const RayCaster caster(test::MakeBox(half));
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = ObliqueBoxPose();
  const std::vector<Crease> creases = FindCreases(caster.mesh(), 40.0);
  CreaseContourOptions options;
  const std::vector<ContourPoint> points =
      ExtractCreaseContour(caster, camera, cam_from_object, creases, options);
  // The corner nearest to the camera: where the three seen faces meet.
  const Eigen::Vector3d corner = NearestCorner(half, cam_from_object);
  const Eigen::Vector2d corner_pixel = camera.Project(cam_from_object * corner);
  // Three edges of ~60 mm at ~400 mm: ~90 px each before the windows' margins.
  ASSERT_GT(points.size(), 150u);
  int edges_seen[3] = {0, 0, 0};
  for (const ContourPoint& point : points) {
    SCOPED_TRACE(point.pixel.transpose());
    const Eigen::Vector3d& x = point.point_in_object;
    // On an edge through the nearest corner: two coordinates at that corner's.
    int free_axis = -1;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(x[k] - corner[k]) > 1e-9) {
        EXPECT_EQ(free_axis, -1) << "more than one coordinate off the corner";
        free_axis = k;
      }
    }
    ASSERT_GE(free_axis, 0);
    ++edges_seen[free_axis];
    EXPECT_LT((camera.Project(cam_from_object * x) - point.pixel).norm(), 1e-9);
    EXPECT_NEAR(point.normal.norm(), 1.0, 1e-12);
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();
    direction[free_axis] = 1.0;
    const Eigen::Vector2d along = camera.Project(cam_from_object * (x + direction)) - point.pixel;
    EXPECT_NEAR(point.normal.dot(along.normalized()), 0.0, 1e-6);
    // The window lies on the edge's two faces: the rays at whole pixels along the normal hit
    // the plane of one face on one side and of the other face on the other.
    Eigen::Vector3d plane_normal[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    for (int side = 0; side < 2; ++side) {
      for (int t = 1; t <= static_cast<int>(options.clear_px); ++t) {
        const std::optional<Eigen::Vector3d> hit = caster.Intersect(
            camera, cam_from_object, point.pixel + (side == 0 ? -t : t) * point.normal);
        ASSERT_TRUE(hit.has_value());
        // The box face a hit lies on: the axis whose coordinate is at ±half.
        Eigen::Vector3d face = Eigen::Vector3d::Zero();
        for (int k = 0; k < 3; ++k) {
          if (std::abs(std::abs((*hit)[k]) - half[k]) < 1e-2) face[k] = (*hit)[k] > 0 ? 1 : -1;
        }
        ASSERT_EQ(face.cwiseAbs().sum(), 1.0) << "hit on an edge or off the faces";
        if (t == 1) plane_normal[side] = face;
        EXPECT_EQ(face, plane_normal[side]) << "side " << side << " at " << t << " px";
      }
    }
    EXPECT_NE(plane_normal[0], plane_normal[1]);
  }
  // Near the corner the window would cross onto the third face.
  int near_corner = 0;
  for (const ContourPoint& point : points) near_corner += (point.pixel - corner_pixel).norm() < 1.0;
  EXPECT_EQ(near_corner, 0);
  for (int k = 0; k < 3; ++k) EXPECT_GT(edges_seen[k], 30) << "edge along axis " << k;
}

// A second box in front of part of an edge hides the samples behind it and those whose window
// reaches the occluder's outline.
TEST(CreaseContourTest, OccludedSamplesAreLeftOut) {
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = ObliqueBoxPose();
  const Mesh box = test::MakeBox(30.0);
  const RayCaster alone(box);
  const std::vector<Crease> creases = FindCreases(box, 40.0);
  const std::vector<ContourPoint> unoccluded =
      ExtractCreaseContour(alone, camera, cam_from_object, creases);
  // A small box in front of the middle of a seen edge (the one along x through the corner
  // nearest to the camera), at 250 mm, with its own creases left out of the list so that only
  // the occlusion changes.
  const Eigen::Vector3d corner = NearestCorner(Eigen::Vector3d::Constant(30.0), cam_from_object);
  const Eigen::Vector3d edge_middle = cam_from_object * Eigen::Vector3d(0, corner.y(), corner.z());
  const Eigen::Vector3d front_in_object =
      cam_from_object.inverse() * (edge_middle * (250.0 / edge_middle.z()));
  std::vector<Eigen::Vector3f> vertices = box.vertices();
  std::vector<Eigen::Vector3i> triangles = box.triangles();
  const Mesh small = test::MakeBox(4.0);
  for (const Eigen::Vector3i& t : small.triangles()) {
    triangles.emplace_back(t + Eigen::Vector3i::Constant(static_cast<int>(vertices.size())));
  }
  for (const Eigen::Vector3f& v : small.vertices()) {
    vertices.push_back(v + front_in_object.cast<float>());
  }
  const RayCaster occluded(Mesh::FromArrays(std::move(vertices), std::move(triangles)));
  const std::vector<ContourPoint> points =
      ExtractCreaseContour(occluded, camera, cam_from_object, creases);
  ASSERT_FALSE(points.empty());
  // The small box covers ~19 px of the edge, and its outline is within the window of more.
  EXPECT_LT(points.size() + 20, unoccluded.size());
  for (const ContourPoint& point : points) {
    const std::optional<Eigen::Vector3d> hit =
        occluded.Intersect(camera, cam_from_object, point.pixel);
    ASSERT_TRUE(hit.has_value());
    EXPECT_LT((*hit - point.point_in_object).norm(), 1e-3);
  }
}

}  // namespace
}  // namespace bcot
