#include "bcot/core/triangulation.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "bcot/core/se3.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

// Two distorted 640×512 cameras 600 mm from the rig origin, 90° apart (cam0 = rig frame).
std::vector<RigCamera> BinocularRig() {
  Camera camera("cam0", 640, 512, 880.0, 878.0, 321.4, 254.7);
  camera.distortion = {-0.12, 0.08, 0.0012, -0.0008, -0.01};
  RigCamera cam0{camera, Eigen::Isometry3d::Identity()};
  camera.name = "cam1";
  // cam1 looks at (0, 0, 600) in the rig frame from the side.
  Eigen::Isometry3d cam1_from_rig = Eigen::Isometry3d::Identity();
  cam1_from_rig.linear() = ExpSO3(Eigen::Vector3d(0.0, kPi / 2, 0.0));
  cam1_from_rig.translation() = -cam1_from_rig.linear() * Eigen::Vector3d(600.0, 0.0, 600.0);
  return {cam0, RigCamera{camera, cam1_from_rig}};
}

Eigen::Vector2d ProjectInto(const RigCamera& camera, const Eigen::Vector3d& point_in_rig) {
  return camera.camera.Project(camera.cam_from_rig * point_in_rig);
}

TEST(TriangulationTest, PixelRayPassesThroughThePointItSees) {
  const std::vector<RigCamera> rig = BinocularRig();
  const Eigen::Vector3d point(35.0, -20.0, 640.0);
  for (const RigCamera& camera : rig) {
    const RigRay ray = PixelRayInRig(camera, ProjectInto(camera, point));
    EXPECT_NEAR(ray.direction_in_rig.norm(), 1.0, 1e-12);
    EXPECT_LT(DistanceToRay(ray, point), 1e-6);
  }
}

TEST(TriangulationTest, TwoExactRaysRecoverThePoint) {
  const std::vector<RigCamera> rig = BinocularRig();
  for (const Eigen::Vector3d& point :
       {Eigen::Vector3d(35.0, -20.0, 640.0), Eigen::Vector3d(-80.0, 60.0, 520.0)}) {
    std::vector<RigRay> rays;
    for (const RigCamera& camera : rig) {
      rays.push_back(PixelRayInRig(camera, ProjectInto(camera, point)));
    }
    const StatusOr<Eigen::Vector3d> found = TriangulateRays(rays);
    ASSERT_TRUE(found.ok()) << found.status().message();
    EXPECT_LT((*found - point).norm(), 1e-6);
  }
}

TEST(TriangulationTest, ClicksFivePixelsOffStayWithinAFewMillimetres) {
  const std::vector<RigCamera> rig = BinocularRig();
  const Eigen::Vector3d point(20.0, 10.0, 600.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-5.0, 5.0);
  double worst_mm = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<RigRay> rays;
    for (const RigCamera& camera : rig) {
      const Eigen::Vector2d click =
          ProjectInto(camera, point) + Eigen::Vector2d(offset(rng), offset(rng));
      rays.push_back(PixelRayInRig(camera, click));
    }
    const StatusOr<Eigen::Vector3d> found = TriangulateRays(rays);
    ASSERT_TRUE(found.ok()) << found.status().message();
    worst_mm = std::max(worst_mm, (*found - point).norm());
  }
  // 5 px at f = 880 px and 600 mm is 3.4 mm per axis; two 90° views fix all three axes.
  EXPECT_LT(worst_mm, 6.0);
  EXPECT_GT(worst_mm, 1.0);  // the clicks really were perturbed
}

TEST(TriangulationTest, FewerThanTwoRaysOrParallelRaysAreErrors) {
  const std::vector<RigCamera> rig = BinocularRig();
  const RigRay ray = PixelRayInRig(rig[0], Eigen::Vector2d(300.0, 200.0));
  const StatusOr<Eigen::Vector3d> one = TriangulateRays({ray});
  ASSERT_FALSE(one.ok());
  EXPECT_THAT(one.status().message(), HasSubstr("at least two rays"));
  RigRay shifted = ray;
  shifted.origin_in_rig += Eigen::Vector3d(1.0, 0.0, 0.0);
  const StatusOr<Eigen::Vector3d> parallel = TriangulateRays({ray, shifted});
  ASSERT_FALSE(parallel.ok());
  EXPECT_THAT(parallel.status().message(), HasSubstr("parallel"));
}

TEST(TriangulationTest, RaysMeetingBehindACameraAreAnError) {
  RigRay a;
  a.origin_in_rig = Eigen::Vector3d(0.0, 0.0, 0.0);
  a.direction_in_rig = Eigen::Vector3d(0.0, 0.0, 1.0);
  RigRay b;
  // b's line meets a's at z = 100, in front of a but 100·√2 mm behind b's centre.
  b.origin_in_rig = Eigen::Vector3d(100.0, 0.0, 200.0);
  b.direction_in_rig = Eigen::Vector3d(1.0, 0.0, 1.0).normalized();
  const StatusOr<Eigen::Vector3d> found = TriangulateRays({a, b});
  ASSERT_FALSE(found.ok());
  EXPECT_THAT(found.status().message(), HasSubstr("behind"));
}

}  // namespace
}  // namespace bcot
