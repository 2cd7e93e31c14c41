#include "bcot/render/interior_edges.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "test_meshes.h"
#include "test_util.h"

namespace bcot {
namespace {

ContourPoint At(double x, double y) {
  return {Eigen::Vector2d(x, y), Eigen::Vector2d(1.0, 0.0), Eigen::Vector3d::Zero()};
}

// The grid lookup answers as a search over every sample does.
TEST(InteriorEdgesTest, ClaimsAsABruteForceSearch) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(-20.0, 60.0);
  std::vector<ContourPoint> points;
  for (int i = 0; i < 400; ++i) points.push_back(At(coordinate(rng), 0.5 * coordinate(rng)));
  for (const double tolerance : {0.5, 1.0, 2.5}) {
    const InteriorEdges edges(points, tolerance);
    int claimed = 0;
    for (int q = 0; q < 3000; ++q) {
      const Eigen::Vector2d silhouette(coordinate(rng), 0.5 * coordinate(rng));
      const Eigen::Vector2d found =
          silhouette + Eigen::Vector2d(coordinate(rng), coordinate(rng)) * 0.05;
      const double reach = std::min(tolerance, (found - silhouette).norm());
      bool expected = false;
      for (const ContourPoint& point : points) {
        expected = expected || (point.pixel - found).squaredNorm() < reach * reach;
      }
      ASSERT_EQ(edges.Claims(silhouette, found), expected) << q << " tolerance " << tolerance;
      claimed += expected ? 1 : 0;
    }
    EXPECT_GT(claimed, 20) << tolerance;  // the queries test both answers
  }
}

// A tolerance far below the samples' spread coarsens the grid instead of allocating 10¹⁰ cells,
// and answers the same.
TEST(InteriorEdgesTest, ATinyToleranceOverAWideSpreadStaysExact) {
  const std::vector<ContourPoint> points = {At(0.0, 0.0), At(5000.0, 3000.0), At(10.0, 10.0)};
  const InteriorEdges edges(points, 1e-3);
  EXPECT_TRUE(edges.Claims(Eigen::Vector2d(10.0, 20.0), Eigen::Vector2d(10.0005, 10.0)));
  EXPECT_FALSE(edges.Claims(Eigen::Vector2d(10.0, 20.0), Eigen::Vector2d(10.002, 10.0)));
  EXPECT_FALSE(edges.Claims(Eigen::Vector2d(0, 0), Eigen::Vector2d(1e12, -1e12)));
  EXPECT_FALSE(edges.Claims(Eigen::Vector2d(0, 0), Eigen::Vector2d(std::nan(""), 0.0)));
}

TEST(InteriorEdgesTest, NothingIsClaimedWithoutEdges) {
  const InteriorEdges edges({}, 1.0);
  EXPECT_EQ(edges.size(), 0);
  EXPECT_FALSE(edges.Claims(Eigen::Vector2d(0, 0), Eigen::Vector2d(0.5, 0)));
}

// A box seen obliquely: the creases between its three seen faces are interior edges; a step on
// one of them is claimed, a step at the silhouette is not.
TEST(InteriorEdgesTest, ProjectsTheCreasesOfABox) {
  const Mesh box = test::MakeBox(Eigen::Vector3d(30, 20, 10));
  const RayCaster caster(box);
  const Camera camera("test", 640, 512, 600.0, 600.0, 320.0, 256.0);
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.linear() = (Eigen::AngleAxisd(0.55, Eigen::Vector3d::UnitX()) *
                              Eigen::AngleAxisd(0.75, Eigen::Vector3d::UnitY()))
                                 .toRotationMatrix();
  cam_from_object.translation() = Eigen::Vector3d(5, -3, 400);
  const std::vector<Crease> creases = FindCreases(box, 60.0);
  const InteriorEdges edges =
      ProjectInteriorEdges(caster, camera, cam_from_object, creases, 60.0, false, 1.0);
  ASSERT_GT(edges.size(), 20);
  // The three edges at the seen corner nearest to the camera lie between two seen faces each:
  // the middle of one of them is on an interior crease.
  Eigen::Vector3d nearest(30, 20, 10);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c((i & 1) ? 30 : -30, (i & 2) ? 20 : -20, (i & 4) ? 10 : -10);
    if ((cam_from_object * c).z() < (cam_from_object * nearest).z()) nearest = c;
  }
  const auto project = [&](double x) {
    return camera.Project(cam_from_object * Eigen::Vector3d(x, nearest.y(), nearest.z()));
  };
  const Eigen::Vector2d middle = project(0.0);
  const Eigen::Vector2d along = (project(1.0) - project(-1.0)).normalized();
  const Eigen::Vector2d across(-along.y(), along.x());
  // A silhouette point 5 px off the crease, the step 0.3 px off it: claimed by the crease.
  EXPECT_TRUE(edges.Claims(middle + 5.0 * across, middle + 0.3 * across));
  // The step nearer to the silhouette point (0.1 px) than to the crease (0.7 px): not claimed.
  EXPECT_FALSE(edges.Claims(middle + 0.8 * across, middle + 0.7 * across));
  // Nor one far from every crease.
  EXPECT_FALSE(edges.Claims(Eigen::Vector2d(5, 5), Eigen::Vector2d(8, 5)));
}

}  // namespace
}  // namespace bcot
