// Step 4b of the quality measurement: a boundary found on one of the model's own interior edges
// (a crease, an occlusion contour) near the silhouette is not taken for the silhouette.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <random>

#include "bcot/core/linear_rgb.h"
#include "bcot/quality/boundary_search.h"
#include "bcot/quality/quality_report.h"
#include "bcot/render/crease_contour.h"
#include "bcot/render/ray_caster.h"
#include "test_meshes.h"
#include "test_util.h"

namespace bcot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(DropInteriorEdgeMatchesTest, DropsOnlyBoundariesFoundOnAnInteriorEdgeOffTheContour) {
  // A contour along x = 0 with outward normal +x; an interior edge along x = −3.
  std::vector<ContourPoint> contour, interior;
  for (int i = 0; i < 6; ++i) {
    contour.push_back(
        {Eigen::Vector2d(0.0, 10.0 * i), Eigen::Vector2d(1.0, 0.0), Eigen::Vector3d::Zero()});
  }
  for (int k = 0; k <= 100; ++k) {
    ContourPoint point{Eigen::Vector2d(-3.0, 0.5 * k), Eigen::Vector2d(1.0, 0.0),
                       Eigen::Vector3d::Zero()};
    interior.push_back(point);
  }
  std::vector<double> offsets = {-3.2, -0.4, 2.5, kNaN, -2.3, -1.6};
  EXPECT_EQ(DropInteriorEdgeMatches(contour, InteriorEdges(interior, 1.0), &offsets), 2);
  EXPECT_TRUE(std::isnan(offsets[0]));  // on the interior edge
  EXPECT_EQ(offsets[1], -0.4);          // at the silhouette
  EXPECT_EQ(offsets[2], 2.5);           // outside, on no interior edge
  EXPECT_TRUE(std::isnan(offsets[3]));  // none found
  EXPECT_TRUE(std::isnan(offsets[4]));  // within 1 px of the interior edge
  EXPECT_EQ(offsets[5], -1.6);          // 1.4 px from it
}

// A disc (a flange: radius 40 mm, 24 mm thick) seen almost end-on, tilted 12° so that on one side
// its cylindrical rim shows as a band about 3 px wide between the cap's rim (a 90° crease) and
// the silhouette. The cap is bright; the band has exactly the background's colour, so on that
// side the silhouette has no contrast and the crease is the nearest step.
class FlangeScene : public ::testing::Test {
 protected:
  FlangeScene()
      : mesh_(test::MakeCylinder(40.0, 12.0, 96)),
        caster_(mesh_),
        camera_("cam0", 320, 256, 500.0, 500.0, 159.5, 127.5) {
    cam_from_object_.linear() =
        (Eigen::AngleAxisd(12.0 * test::kPi / 180.0, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(test::kPi, Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
    cam_from_object_.translation() = Eigen::Vector3d(4.0, -3.0, 450.0);
    image_ = Render();
  }

  // The scene rendered with 4×4 rays per pixel in linear light, blurred (σ 0.7 px), sRGB-encoded
  // with seeded noise of about one code.
  cv::Mat3b Render() const {
    const cv::Vec3f background(0.20f, 0.22f, 0.25f), cap(0.45f, 0.50f, 0.55f);  // BGR, linear
    RenderOptions options;
    options.roi = cv::Rect(0, 0, camera_.width, camera_.height);
    options.samples_per_axis = 4;
    const RenderedView view = caster_.Render(camera_, cam_from_object_, options);
    cv::Mat3f fine(view.mask.size(), background);
    for (int y = 0; y < fine.rows; ++y) {
      for (int x = 0; x < fine.cols; ++x) {
        if (view.mask(y, x) != 0 && std::abs(view.normal_in_cam(y, x)[2]) > 0.9f) fine(y, x) = cap;
      }
    }
    cv::Mat3f linear;
    cv::resize(fine, linear, cv::Size(camera_.width, camera_.height), 0, 0, cv::INTER_AREA);
    cv::GaussianBlur(linear, linear, cv::Size(0, 0), 0.7);
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    cv::Mat3b image(linear.size());
    const LinearTable table{ImageResponse()};
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        for (int c = 0; c < 3; ++c) {
          image(y, x)[c] = cv::saturate_cast<uchar>(table.Encode(linear(y, x)[c]) + noise(rng));
        }
      }
    }
    return image;
  }

  ViewFrameQuality Measure(const Eigen::Isometry3d& cam_from_object, bool interior_edges) const {
    QualityOptions options;
    options.interior_edges = interior_edges;
    return MeasureFrameView(caster_, camera_, cam_from_object, image_, options,
                            LinearTable(ImageResponse()),
                            FindCreases(mesh_, options.crease_min_angle_deg), 1);
  }

  Mesh mesh_;
  RayCaster caster_;
  Camera camera_;
  Eigen::Isometry3d cam_from_object_ = Eigen::Isometry3d::Identity();
  cv::Mat3b image_;
};

TEST_F(FlangeScene, TheCapsRimIsNotTakenForTheSilhouette) {
  // Without step 4b the band's side measures the crease, and the true pose looks pixels off.
  const ViewFrameQuality without = Measure(cam_from_object_, false);
  EXPECT_GT(without.p90_px, 1.5);
  const ViewFrameQuality with = Measure(cam_from_object_, true);
  EXPECT_LT(with.p90_px, 0.5);
  EXPECT_FALSE(with.bad);
  EXPECT_GT(with.ambiguous, without.ambiguous + 10);
}

TEST_F(FlangeScene, AShiftedPoseIsStillBad) {
  // 3 px along the image's x axis at the object's depth.
  Eigen::Isometry3d shifted = cam_from_object_;
  shifted.translation().x() += 3.0 * cam_from_object_.translation().z() / camera_.fx;
  const ViewFrameQuality quality = Measure(shifted, true);
  EXPECT_TRUE(quality.bad) << quality.p90_px << " ± " << quality.statistic_sigma_px;
  EXPECT_GT(quality.p90_px, 2.5);
}

}  // namespace
}  // namespace bcot
