#include "bcot/core/camera.h"

#include <gtest/gtest.h>

#include "bcot/core/rig.h"
#include "bcot/core/se3.h"

namespace bcot {
namespace {

Camera MakeCamera(bool distorted) {
  Camera camera("cam0", 1280, 1024, 1500.0, 1495.0, 641.3, 509.8);
  if (distorted) camera.distortion = {-0.12, 0.08, 0.0012, -0.0008, -0.01};
  return camera;
}

class CameraTest : public ::testing::TestWithParam<bool> {};

TEST_P(CameraTest, ProjectionJacobianMatchesCentralDifferences) {
  const Camera camera = MakeCamera(GetParam());
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(10.0, -20.0, 600.0),
                                   Eigen::Vector3d(-150.0, 130.0, 450.0),
                                   Eigen::Vector3d(0.0, 0.0, 800.0)}) {
    Eigen::Matrix<double, 2, 3> analytic;
    camera.Project(p, &analytic);
    Eigen::Matrix<double, 2, 3> numeric;
    const double h = 1e-4;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * h;
      numeric.col(k) = (camera.Project(p + e) - camera.Project(p - e)) / (2.0 * h);
    }
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6) << p.transpose();
  }
}

TEST_P(CameraTest, PixelToRayInvertsProjection) {
  const Camera camera = MakeCamera(GetParam());
  for (int v = 0; v < camera.height; v += 97) {
    for (int u = 0; u < camera.width; u += 83) {
      const Eigen::Vector2d pixel(u, v);
      const Eigen::Vector3d ray = camera.PixelToRay(pixel);
      EXPECT_DOUBLE_EQ(ray.z(), 1.0);
      EXPECT_LT((camera.Project(250.0 * ray) - pixel).norm(), 1e-9) << pixel.transpose();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Distortion, CameraTest, ::testing::Values(false, true));

TEST(CameraTest, DistortionJacobianMatchesNumeric) {
  const Camera camera = MakeCamera(true);
  const Eigen::Vector2d n(0.31, -0.27);
  Eigen::Matrix2d analytic;
  camera.Distort(n, &analytic);
  Eigen::Matrix2d numeric;
  const double h = 1e-6;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d e = Eigen::Vector2d::Unit(k) * h;
    numeric.col(k) = (camera.Distort(n + e) - camera.Distort(n - e)) / (2.0 * h);
  }
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-8);
}

// Halving the image keeps the pixel-centre convention: the image corner (−½, −½) maps to
// (−½, −½) and a point's pixel (u, v) maps to ((u + ½)/2 − ½, (v + ½)/2 − ½).
TEST(CameraTest, ScaledKeepsPixelCentreConvention) {
  const Camera camera = MakeCamera(false);
  const Camera half = camera.Scaled(0.5);
  EXPECT_EQ(half.width, 640);
  EXPECT_EQ(half.height, 512);
  const Eigen::Vector3d p(40.0, -25.0, 700.0);
  const Eigen::Vector2d full = camera.Project(p);
  const Eigen::Vector2d expected = (full + Eigen::Vector2d(0.5, 0.5)) * 0.5 -
                                   Eigen::Vector2d(0.5, 0.5);
  EXPECT_LT((half.Project(p) - expected).norm(), 1e-12);
}

TEST(CameraTest, ValidateNamesEveryProblem) {
  Camera camera("bad", 0, 480, -1.0, 500.0, 320.0, 240.0);
  const Status status = camera.Validate("cameras[2]");
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("cameras[2]"), std::string::npos);
  EXPECT_NE(status.message().find("image_size"), std::string::npos);
  EXPECT_NE(status.message().find("focal"), std::string::npos);
  EXPECT_TRUE(MakeCamera(true).Validate().ok());
}

TEST(CameraTest, InImageUsesPixelEdges) {
  const Camera camera = MakeCamera(false);
  EXPECT_TRUE(camera.InImage({-0.5, -0.5}));
  EXPECT_FALSE(camera.InImage({-0.51, 3.0}));
  EXPECT_TRUE(camera.InImage({1279.4, 1023.4}));
  EXPECT_FALSE(camera.InImage({1279.4, 1023.4}, 1.0));
}

TEST(RigTest, FindAndValidate) {
  Rig rig;
  rig.Add({MakeCamera(false), Eigen::Isometry3d::Identity()});
  Camera second = MakeCamera(true);
  second.name = "cam1";
  Eigen::Isometry3d cam1_from_rig = ExpSE3((Vector6d() << 500, 0, 500, 0, -1.5708, 0).finished());
  rig.Add({second, cam1_from_rig});
  EXPECT_TRUE(rig.Validate().ok());
  EXPECT_EQ(rig.Find("cam1"), 1);
  EXPECT_EQ(rig.Find("nope"), -1);

  Rig duplicate = rig;
  duplicate.Add({MakeCamera(false), Eigen::Isometry3d::Identity()});
  const Status status = duplicate.Validate();
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("'cam0' is used twice"), std::string::npos) << status.message();

  Rig skewed;
  Eigen::Isometry3d skew = Eigen::Isometry3d::Identity();
  skew.linear()(0, 1) = 0.1;
  skewed.Add({MakeCamera(false), skew});
  EXPECT_FALSE(skewed.Validate().ok());
  EXPECT_FALSE(Rig().Validate().ok());
}

}  // namespace
}  // namespace bcot
