#include "bcot/optim/region_template.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "region_test_scene.h"

namespace bcot {
namespace {

TEST(RegionTemplateOptionsTest, ValidateListsEveryViolation) {
  EXPECT_TRUE(RegionTemplateOptions().Validate().ok());
  RegionTemplateOptions options;
  options.band_px = 0.0;
  options.stride_px = 0;
  options.contour.sample_spacing_px = -1.0;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"region_template: ", "band_px = 0, must be finite and > 0",
                           "stride_px = 0, must be >= 1", "contour: ", "sample_spacing_px"});
}

class RegionTemplateTest : public test::SpoolImageTest {
 protected:
  void SetUp() override {
    SpoolImageTest::SetUp();
    rig_from_objcentre_ = test::RigFromObjcentre(cam_from_objcentre_);
    silhouette_ =
        RenderSilhouette(*caster_, camera_, cam_from_objcentre_ * mesh_->objcentre_from_template(),
                         RegionTemplateOptions().contour);
    color_model_.Update(image_, silhouette_);
  }

  Eigen::Isometry3d rig_from_objcentre_;
  Silhouette silhouette_;
  GlobalColorModel color_model_{ColorModelOptions()};
};

TEST_F(RegionTemplateTest, BandPixelsHaveConsistentGeometry) {
  RegionTemplateOptions options;
  options.band_px = 10.0;
  options.stride_px = 2;
  const StatusOr<RegionTemplate> region_template =
      BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), rig_from_objcentre_, image_,
                          color_model_, silhouette_, options);
  ASSERT_TRUE(region_template.ok()) << region_template.status().message();
  const std::vector<RegionPixel>& pixels = region_template->pixels;
  EXPECT_GT(pixels.size(), 1500u);
  EXPECT_LT(pixels.size(), 6000u);
  EXPECT_TRUE(region_template->rig_from_objcentre.isApprox(rig_from_objcentre_));

  int inside_count = 0, outside_count = 0;
  double foreground_inside = 0.0, foreground_outside = 0.0;
  for (const RegionPixel& p : pixels) {
    const int x = static_cast<int>(p.pixel.x());
    const int y = static_cast<int>(p.pixel.y());
    ASSERT_EQ(x % 2, 0);
    ASSERT_EQ(y % 2, 0);
    ASSERT_TRUE(camera_.InImage(p.pixel));
    // Band width respected, unit gradient, P_f + P_b = 1.
    EXPECT_LE(std::abs(p.phi0), options.band_px + 1e-9);
    EXPECT_NEAR(p.grad_phi0.norm(), 1.0, 1e-9);
    EXPECT_NEAR(p.p_foreground + p.p_background, 1.0, 1e-12);
    // Φ0 is negative inside the silhouette (away from sub-pixel ambiguity at the contour).
    const bool in_mask = silhouette_.mask(y, x) != 0;
    if (p.phi0 < -1.0) {
      EXPECT_TRUE(in_mask) << p.pixel.transpose() << " phi " << p.phi0;
    }
    if (p.phi0 > 1.0) {
      EXPECT_FALSE(in_mask) << p.pixel.transpose() << " phi " << p.phi0;
    }
    // The attached point: inside, the surface point under the pixel reprojects to the pixel;
    // outside, the nearest contour point's model point reprojects |Φ0| away.
    const Eigen::Vector3d point_in_cam =
        test::TestCamFromRig() * rig_from_objcentre_ * p.point_in_objcentre;
    EXPECT_LT((camera_.Project(point_in_cam) - p.projection0).norm(), 1e-9);
    if (p.inside) {
      EXPECT_TRUE(in_mask);
      EXPECT_LT((p.projection0 - p.pixel).norm(), 1e-3) << p.pixel.transpose();
      ++inside_count;
      foreground_inside += p.p_foreground;
    } else {
      EXPECT_NEAR((p.projection0 - p.pixel).norm(), std::abs(p.phi0), 0.05) << p.pixel.transpose();
      // ∇Φ0 points from the contour towards an outside pixel.
      if (p.phi0 > 1.0) {
        EXPECT_GT(p.grad_phi0.dot(p.pixel - p.projection0), 0.0);
      }
      ++outside_count;
      foreground_outside += p.p_foreground;
    }
  }
  ASSERT_GT(inside_count, 300);
  ASSERT_GT(outside_count, 300);
  EXPECT_GT(foreground_inside / inside_count, 0.8);
  EXPECT_LT(foreground_outside / outside_count, 0.2);
}

TEST_F(RegionTemplateTest, SignedDistanceAgreesWithTheMaskDistanceTransform) {
  RegionTemplateOptions options;
  options.stride_px = 3;
  const StatusOr<RegionTemplate> region_template =
      BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), rig_from_objcentre_, image_,
                          color_model_, options);  // renders its own silhouette
  ASSERT_TRUE(region_template.ok());
  EXPECT_GT(region_template->pixels.size(), 500u);
  cv::Mat1f distance_outside, distance_inside;
  cv::distanceTransform(silhouette_.mask == 0, distance_outside, cv::DIST_L2,
                        cv::DIST_MASK_PRECISE);
  cv::distanceTransform(silhouette_.mask != 0, distance_inside, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  for (const RegionPixel& p : region_template->pixels) {
    const int x = static_cast<int>(p.pixel.x());
    const int y = static_cast<int>(p.pixel.y());
    ASSERT_EQ(x % 3, 0);
    // Pixel-grid distance transforms are off by up to about a pixel from the sub-pixel truth.
    const double mask_phi =
        silhouette_.mask(y, x) != 0 ? -(distance_inside(y, x) - 0.5) : distance_outside(y, x) - 0.5;
    EXPECT_NEAR(p.phi0, mask_phi, 1.0) << p.pixel.transpose();
  }
}

// A silhouette whose model points were rendered on the template's stride gives the same
// template as a full render; a stride that is not a multiple of the render's is an error.
TEST_F(RegionTemplateTest, StridedSilhouetteGivesTheSameTemplate) {
  RegionTemplateOptions options;
  options.stride_px = 4;
  const Silhouette strided =
      RenderSilhouette(*caster_, camera_, cam_from_objcentre_ * mesh_->objcentre_from_template(),
                       options.contour, /*point_stride_px=*/4);
  const StatusOr<RegionTemplate> expected =
      BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), rig_from_objcentre_, image_,
                          color_model_, silhouette_, options);
  const StatusOr<RegionTemplate> actual =
      BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), rig_from_objcentre_, image_,
                          color_model_, strided, options);
  ASSERT_TRUE(expected.ok() && actual.ok());
  ASSERT_EQ(actual->pixels.size(), expected->pixels.size());
  for (size_t i = 0; i < actual->pixels.size(); ++i) {
    EXPECT_EQ(actual->pixels[i].pixel, expected->pixels[i].pixel);
    EXPECT_EQ(actual->pixels[i].inside, expected->pixels[i].inside);
    EXPECT_NEAR(
        (actual->pixels[i].point_in_objcentre - expected->pixels[i].point_in_objcentre).norm(), 0.0,
        1e-3);
  }
  options.stride_px = 6;
  const StatusOr<RegionTemplate> mismatched =
      BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), rig_from_objcentre_, image_,
                          color_model_, strided, options);
  ASSERT_FALSE(mismatched.ok());
  EXPECT_EQ(mismatched.status().code(), StatusCode::kInvalidInput);
  EXPECT_NE(mismatched.status().message().find("point stride 4"), std::string::npos);
}

TEST_F(RegionTemplateTest, RejectsMismatchedInputsAndHandlesAnInvisibleObject) {
  const cv::Mat3b small(100, 100, cv::Vec3b(0, 0, 0));
  StatusOr<RegionTemplate> result =
      BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), rig_from_objcentre_, small,
                          color_model_, silhouette_);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidInput);
  EXPECT_NE(result.status().message().find("image is 100x100"), std::string::npos);

  RegionTemplateOptions bad;
  bad.band_px = -1.0;
  result = BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), rig_from_objcentre_,
                               image_, color_model_, silhouette_, bad);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidConfig);

  // Behind the camera: no silhouette, an empty template, not an error.
  const Eigen::Isometry3d behind =
      test::RigFromObjcentre(test::MakeCamFromObjcentre({0.0, 0.0, 0.0}, {0.0, 0.0, -500.0}));
  result =
      BuildRegionTemplate(*caster_, camera_, test::TestCamFromRig(), behind, image_, color_model_);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_TRUE(result->pixels.empty());
}

}  // namespace
}  // namespace bcot
