#include "bcot/render/occlusion_contour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "test_meshes.h"

namespace bcot {
namespace {

// Camera-frame depth (mm) of the closest hit through `pixel`, nullopt on a miss.
std::optional<double> HitDepth(const RayCaster& caster, const Camera& camera,
                               const Eigen::Isometry3d& cam_from_object,
                               const Eigen::Vector2d& pixel) {
  const std::optional<Eigen::Vector3d> hit = caster.Intersect(camera, cam_from_object, pixel);
  if (!hit.has_value()) return std::nullopt;
  return (cam_from_object * *hit).z();
}

// A torus seen 10° from edge-on: the near half of the tube hides the inner side of the far
// half, along an occlusion contour across the middle of the silhouette. Every sample lies on
// that depth step: its model point projects onto it, a ray just before it along the normal
// hits the near surface close to the model point, and a ray just after it hits far behind.
TEST(OcclusionContourTest, TorusSamplesLieOnTheDepthStepWithTheirModelPoints) {
  const RayCaster caster(test::MakeTorus(40.0, 12.0, 160, 48));
  const Camera camera("test", 640, 512, 600.0, 600.0, 320.0, 256.0);
  for (const Camera& view : {camera, [&] {
                               Camera distorted = camera;
                               distorted.distortion = {-0.25, 0.08, 0.0015, -0.001, -0.01};
                               return distorted;
                             }()}) {
    SCOPED_TRACE(view.distortion[0] == 0.0 ? "pinhole" : "distorted");
    Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
    cam_from_object.linear() =
        Eigen::AngleAxisd((90.0 - 10.0) * kPi / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
    cam_from_object.translation() = Eigen::Vector3d(10, -5, 450);
    const OcclusionContourOptions options;
    const std::vector<ContourPoint> points =
        ExtractOcclusionContour(caster, view, cam_from_object, options);
    // The step runs across the hole (2 × 28 mm at 450 mm: ~75 px), and the far tube beyond it.
    ASSERT_GT(points.size(), 60u);
    for (const ContourPoint& point : points) {
      SCOPED_TRACE(point.pixel.transpose());
      EXPECT_NEAR(point.normal.norm(), 1.0, 1e-9);
      const Eigen::Vector2d projected = view.Project(cam_from_object * point.point_in_object);
      EXPECT_LT((projected - point.pixel).norm(), options.precision_px + 1e-3);
      const double model_depth = (cam_from_object * point.point_in_object).z();
      const std::optional<double> before =
          HitDepth(caster, view, cam_from_object, point.pixel - 0.05 * point.normal);
      const std::optional<double> after =
          HitDepth(caster, view, cam_from_object, point.pixel + 0.05 * point.normal);
      ASSERT_TRUE(before.has_value());
      // The near surface is tangent to the rays at its occluding contour, so its depth falls
      // steeply away from it (by ~2 mm over these 0.05 px here), but never behind the rim.
      EXPECT_LT(*before, model_depth + 0.1);
      EXPECT_GT(*before, model_depth - 5.0);
      // Behind it lies the far side of the tube (or nothing): at least the tube's radius on.
      if (after.has_value()) {
        EXPECT_GT(*after, model_depth + 10.0);
      }
    }
  }
}

// A convex object hides no part of itself behind another: no occlusion contour.
TEST(OcclusionContourTest, ConvexObjectHasNone) {
  const RayCaster caster(test::MakeBox(Eigen::Vector3d(30, 20, 25)));
  const Camera camera("test", 640, 512, 600.0, 600.0, 320.0, 256.0);
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.linear() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 0.6, 0.3).normalized()).toRotationMatrix();
  cam_from_object.translation() = Eigen::Vector3d(0, 0, 400);
  EXPECT_TRUE(ExtractOcclusionContour(caster, camera, cam_from_object).empty());
}

TEST(OcclusionContourTest, InvalidOptionsNameTheField) {
  OcclusionContourOptions options;
  options.min_jump_fraction = -1.0;
  options.precision_px = 0.0;
  const Status status = options.Validate();
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("min_jump_fraction = -1"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("precision_px = 0"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace bcot
