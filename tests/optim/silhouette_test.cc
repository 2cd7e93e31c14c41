#include "bcot/optim/silhouette.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "region_test_scene.h"

namespace bcot {
namespace {

using SilhouetteTest = test::BunnyCasterTest;

// A point stride > 1 takes the mask from the contour (FillContour) instead of a ray per pixel:
// the contour is the same, the mask differs by a few boundary pixels, the model points on the
// stride grid are the same.
TEST_F(SilhouetteTest, StridedSilhouetteHasTheContourAndAlmostTheMaskOfTheFullRender) {
  const Camera camera = test::TestCamera();
  const Eigen::Isometry3d cam_from_template =
      test::MakeCamFromObjcentre(Eigen::Vector3d(0.4, -0.2, 0.3), {12.0, -8.0, 420.0}) *
      mesh_->objcentre_from_template();
  ContourOptions options;
  options.sample_spacing_px = 0.5;
  const Silhouette full = RenderSilhouette(*caster_, camera, cam_from_template, options, 1);
  for (const int stride : {2, 64}) {
    const Silhouette strided =
        RenderSilhouette(*caster_, camera, cam_from_template, options, stride);
    ASSERT_EQ(strided.contour.size(), full.contour.size());
    for (size_t i = 0; i < full.contour.size(); ++i) {
      EXPECT_EQ(strided.contour[i].pixel, full.contour[i].pixel);
    }
    const int inside = cv::countNonZero(full.mask);
    ASSERT_GT(inside, 5000);
    EXPECT_LE(cv::countNonZero(strided.mask != full.mask), inside / 1000) << stride;
    ASSERT_EQ(strided.view.roi, full.view.roi);
    for (int r = 0; r < full.view.mask.rows; ++r) {
      for (int c = 0; c < full.view.mask.cols; ++c) {
        if ((full.view.roi.x + c) % stride != 0 || (full.view.roi.y + r) % stride != 0) continue;
        EXPECT_EQ(strided.view.mask(r, c), full.view.mask(r, c));
        if (full.view.mask(r, c) == 0) continue;
        EXPECT_EQ(cv::norm(strided.view.point_in_object(r, c) - full.view.point_in_object(r, c)),
                  0.0);
      }
    }
    const Silhouette contour_only =
        RenderSilhouetteContour(*caster_, camera, cam_from_template, options);
    EXPECT_EQ(contour_only.contour.size(), full.contour.size());
    EXPECT_LE(cv::countNonZero(contour_only.mask != full.mask), inside / 1000);
    EXPECT_TRUE(contour_only.view.point_in_object.empty());
  }
}

// Where the object leaves the image its contour has gaps, so the mask is ray cast there as
// before: the strided and the full render agree pixel for pixel.
TEST_F(SilhouetteTest, ObjectCutByTheImageBorderKeepsTheRayCastMask) {
  const Camera camera = test::TestCamera();
  const Eigen::Isometry3d cam_from_template =
      test::MakeCamFromObjcentre(Eigen::Vector3d(0.1, 0.5, -0.2), {-180.0, 0.0, 420.0}) *
      mesh_->objcentre_from_template();
  const Silhouette full = RenderSilhouette(*caster_, camera, cam_from_template, {}, 1);
  ASSERT_GT(cv::countNonZero(full.mask.col(0)), 10);  // the object is cut by the left border
  const Silhouette strided = RenderSilhouette(*caster_, camera, cam_from_template, {}, 2);
  EXPECT_EQ(cv::countNonZero(strided.mask != full.mask), 0);
  const Silhouette mask_only = RenderSilhouetteMask(*caster_, camera, cam_from_template);
  EXPECT_EQ(cv::countNonZero(mask_only.mask != full.mask), 0);
  EXPECT_TRUE(mask_only.contour.empty());
}

}  // namespace
}  // namespace bcot
