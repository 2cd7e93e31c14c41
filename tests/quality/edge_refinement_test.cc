// Step 4 of the quality measurement: the boundary moved to the centre of the image's blurred
// step (RefineOffsetsOnEdges), on a disk whose rim is shaded the way a key light from one side
// shades a real object.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "bcot/core/linear_rgb.h"
#include "bcot/quality/boundary_search.h"
#include "test_util.h"

namespace bcot {
namespace {

constexpr double kRadius = 40.0;

// A disk of radius kRadius centred at `centre` on a grey-blue background: linear radiance with
// the object's colour darkening linearly over its outer 8 px to 15 % at the silhouette (a
// surface turning away from the light), area-sampled 8×8, blurred by a Gaussian of σ = 0.7 px
// (optics), then sRGB-encoded to 8 bits.
cv::Mat3b ShadedDisk(const cv::Size& size, const Eigen::Vector2d& centre) {
  constexpr int kSub = 8;
  cv::Mat3f linear(size);
  const cv::Vec3f object(0.05f, 0.25f, 0.6f);      // B, G, R
  const cv::Vec3f background(0.3f, 0.22f, 0.18f);  // B, G, R
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      cv::Vec3f sum(0, 0, 0);
      for (int j = 0; j < kSub; ++j) {
        for (int i = 0; i < kSub; ++i) {
          const Eigen::Vector2d p(x - 0.5 + (i + 0.5) / kSub, y - 0.5 + (j + 0.5) / kSub);
          const double r = (p - centre).norm() / kRadius;
          const double shade = 0.15 + 0.85 * std::min(1.0, (1.0 - r) * kRadius / 8.0);
          sum += r < 1.0 ? object * static_cast<float>(shade) : background;
        }
      }
      linear(y, x) = sum / static_cast<float>(kSub * kSub);
    }
  }
  cv::GaussianBlur(linear, linear, cv::Size(0, 0), 0.7);
  cv::Mat3b image(size);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp<double>(linear(y, x)[c], 0.0, 1.0);
        const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
        image(y, x)[c] = cv::saturate_cast<uchar>(255.0 * encoded);
      }
    }
  }
  return image;
}

std::vector<ContourPoint> Circle(const Eigen::Vector2d& centre, double radius, int count) {
  std::vector<ContourPoint> contour(count);
  for (int i = 0; i < count; ++i) {
    const double angle = 2 * test::kPi * i / count;
    contour[i].normal = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    contour[i].pixel = centre + radius * contour[i].normal;
  }
  return contour;
}

TEST(EdgeRefinementTest, SrgbDecodingMatchesTheStandard) {
  const LinearTable table;  // sRGB
  EXPECT_FLOAT_EQ(table[0], 0.0f);
  EXPECT_FLOAT_EQ(table[255], 1.0f);
  EXPECT_NEAR(table[10], 10 / 255.0 / 12.92, 1e-7);                             // linear segment
  EXPECT_NEAR(table[128], std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);  // power segment
  cv::Mat3b image(2, 2, cv::Vec3b(0, 0, 0));
  image(0, 1) = cv::Vec3b(255, 128, 10);  // B, G, R
  const Eigen::Vector3d half = SampleLinearRgb(image, table, Eigen::Vector2d(0.5, 0.0));
  EXPECT_NEAR(half.x(), 0.5 * table[10], 1e-6);  // R
  EXPECT_NEAR(half.z(), 0.5, 1e-6);              // B
  // The peak over the pixels a sample mixes: both neighbours at x = 0.5, one at x = 0.
  EXPECT_NEAR(PeakLinearRgb(image, table, Eigen::Vector2d(0.5, 0.0)).z(), 1.0, 1e-6);
  EXPECT_NEAR(PeakLinearRgb(image, table, Eigen::Vector2d(0.5, 0.0)).x(), table[10], 1e-6);
  EXPECT_EQ(PeakLinearRgb(image, table, Eigen::Vector2d(0.0, 0.0)), Eigen::Vector3d::Zero());
  EXPECT_TRUE(CanSampleBilinear(image.size(), Eigen::Vector2d(0.99, 0.99)));
  EXPECT_FALSE(CanSampleBilinear(image.size(), Eigen::Vector2d(1.0, 0.5)));
  EXPECT_FALSE(CanSampleBilinear(image.size(), Eigen::Vector2d(-0.01, 0.5)));
}

// Wherever the previous step put the boundary (a posterior crossing moved inward by the dark
// rim, or outward), the refinement returns the geometric edge.
TEST(EdgeRefinementTest, FindsTheGeometricEdgeOfAShadedRim) {
  const Eigen::Vector2d centre(80.3, 79.6);
  const cv::Mat3b image = ShadedDisk(cv::Size(160, 160), centre);
  const std::vector<ContourPoint> contour = Circle(centre, kRadius, 48);
  for (double found : {-1.5, -0.6, 0.0, 0.8, 1.6}) {
    const std::vector<double> offsets(contour.size(), found);
    const RefinedOffsets refined =
        RefineOffsetsOnEdges(contour, offsets, image, LinearTable(), QualityOptions());
    EXPECT_EQ(refined.ambiguous, 0) << "found at " << found;
    // 8-bit quantisation of the dark rim scatters single points by up to ~0.15 px; their mean
    // (the bias a pose would inherit) stays within 0.02 px.
    double sum = 0.0;
    for (size_t i = 0; i < contour.size(); ++i) {
      ASSERT_TRUE(std::isfinite(refined.offsets[i])) << "found at " << found << ", point " << i;
      EXPECT_NEAR(refined.offsets[i], 0.0, 0.2) << "found at " << found << ", point " << i;
      EXPECT_GT(refined.sigmas_px[i], 0.0);
      EXPECT_LT(refined.sigmas_px[i], 0.2);
      sum += refined.offsets[i];
    }
    EXPECT_NEAR(sum / contour.size(), 0.0, 0.02) << "found at " << found;
  }
}

TEST(EdgeRefinementTest, NoEdgeNoOffset) {
  const Eigen::Vector2d centre(80, 80);
  const std::vector<ContourPoint> contour = Circle(centre, kRadius, 16);
  // A flat image: no step anywhere.
  const cv::Mat3b flat(160, 160, cv::Vec3b(90, 120, 150));
  const RefinedOffsets none = RefineOffsetsOnEdges(
      contour, std::vector<double>(contour.size(), 0.0), flat, LinearTable(), QualityOptions());
  EXPECT_EQ(none.ambiguous, 16);
  for (double offset : none.offsets) EXPECT_FALSE(std::isfinite(offset));
  // Points the previous step did not find stay unfound and are not counted as ambiguous; a
  // window that leaves the image is ambiguous.
  const cv::Mat3b image = ShadedDisk(cv::Size(160, 160), centre);
  std::vector<double> offsets(contour.size(), std::nan(""));
  offsets[0] = 37.0;  // x = 157: the ±4.5 px profile window leaves the 160 px image
  offsets[1] = 0.0;
  const RefinedOffsets some =
      RefineOffsetsOnEdges(contour, offsets, image, LinearTable(), QualityOptions());
  EXPECT_EQ(some.ambiguous, 1);
  EXPECT_TRUE(std::isfinite(some.offsets[1]));
  for (size_t i = 0; i < contour.size(); ++i) {
    if (i != 1) {
      EXPECT_FALSE(std::isfinite(some.offsets[i])) << i;
    }
  }
}

}  // namespace
}  // namespace bcot
