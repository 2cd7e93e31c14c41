#include "bcot/render/contour_drawing.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "bcot/render/ray_caster.h"
#include "test_meshes.h"

namespace bcot {
namespace {

Camera TestCamera() { return Camera("test", 640, 512, 600.0, 600.0, 320.0, 256.0); }

// The ray-cast mask of the whole image (one ray per pixel centre).
cv::Mat1b RayCastMask(const RayCaster& caster, const Camera& camera,
                      const Eigen::Isometry3d& cam_from_object) {
  RenderOptions options;
  options.roi = cv::Rect(0, 0, camera.width, camera.height);
  options.depth = options.normal_in_cam = options.point_in_object = options.triangle_id = false;
  return caster.Render(camera, cam_from_object, options).mask;
}

cv::Mat1b FilledMask(const std::vector<ContourPoint>& contour, const Camera& camera) {
  cv::Mat1b mask = cv::Mat1b::zeros(camera.height, camera.width);
  FillContour(contour, &mask);
  return mask;
}

// A cube face-on: the silhouette is the front face, ±66.67 px around the principal point, so
// no pixel centre lies within 0.3 px of its sides and the filled mask is the ray-cast one.
TEST(FillContourTest, CubeFaceOnIsItsRayCastMask) {
  const Mesh cube = test::MakeBox(50.0);
  const RayCaster caster(cube);
  const Camera camera = TestCamera();
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.translation() = Eigen::Vector3d(0.0, 0.0, 500.0);
  const cv::Mat1b filled = FilledMask(caster.ExtractContour(camera, cam_from_object), camera);
  const cv::Mat1b cast = RayCastMask(caster, camera, cam_from_object);
  EXPECT_EQ(cv::countNonZero(cast), 133 * 133);
  EXPECT_EQ(cv::countNonZero(filled != cast), 0);
}

// A tilted torus through a distorted lens: its hole stays empty, and the few pixels where the
// filled mask differs from the rays lie at the contour.
TEST(FillContourTest, TorusKeepsItsHoleAndDiffersOnlyAtTheContour) {
  const Mesh torus = test::MakeTorus(40.0, 12.0, 160, 48);
  const RayCaster caster(torus);
  Camera camera = TestCamera();
  camera.distortion = {-0.25, 0.08, 0.0015, -0.001, -0.01};
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.linear() =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 0.3, 0).normalized()).toRotationMatrix();
  cam_from_object.translation() = Eigen::Vector3d(20.0, -15.0, 450.0);
  ContourOptions options;
  options.sample_spacing_px = 0.5;
  const std::vector<ContourPoint> contour = caster.ExtractContour(camera, cam_from_object, options);
  const cv::Mat1b filled = FilledMask(contour, camera);
  const cv::Mat1b cast = RayCastMask(caster, camera, cam_from_object);
  const Eigen::Vector2d centre = camera.Project(cam_from_object.translation());
  const cv::Point hole(static_cast<int>(std::lround(centre.x())),
                       static_cast<int>(std::lround(centre.y())));
  EXPECT_EQ(cast(hole), 0);
  EXPECT_EQ(filled(hole), 0);
  ASSERT_GT(cv::countNonZero(cast), 10000);
  int differing = 0;
  for (int y = 0; y < cast.rows; ++y) {
    for (int x = 0; x < cast.cols; ++x) {
      if (filled(y, x) == cast(y, x)) continue;
      ++differing;
      double nearest = std::numeric_limits<double>::infinity();
      for (const ContourPoint& point : contour) {
        nearest = std::min(nearest, (point.pixel - Eigen::Vector2d(x, y)).norm());
      }
      EXPECT_LT(nearest, 0.75) << "pixel " << x << ", " << y;
    }
  }
  EXPECT_LE(differing, static_cast<int>(0.01 * contour.size()));
}

TEST(FillContourTest, LeavesPixelsOutsideAsTheyAre) {
  std::vector<ContourPoint> square(4);
  const double corners[4][2] = {{10.2, 10.2}, {20.8, 10.2}, {20.8, 20.8}, {10.2, 20.8}};
  for (int i = 0; i < 4; ++i) square[i].pixel = Eigen::Vector2d(corners[i][0], corners[i][1]);
  cv::Mat1b mask(32, 32, uchar{7});
  FillContour(square, &mask);
  EXPECT_EQ(cv::countNonZero(mask == 255), 10 * 10);  // centres 11..20 in x and y
  EXPECT_EQ(mask(10, 10), 7);
  EXPECT_EQ(mask(11, 11), 255);
  EXPECT_EQ(mask(20, 20), 255);
  EXPECT_EQ(mask(21, 15), 7);
}

}  // namespace
}  // namespace bcot
