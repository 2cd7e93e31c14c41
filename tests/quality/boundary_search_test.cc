// CountClippedPoints: the contour points whose boundary the image shows only in saturated
// channels, on disks lit beyond the sensor's full scale.
#include "bcot/quality/boundary_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "bcot/core/linear_rgb.h"
#include "test_util.h"

namespace bcot {
namespace {

constexpr double kRadius = 40.0;
const Eigen::Vector2d kCentre(80.3, 70.6);

// A disk of radius kRadius at kCentre on a background of linear colour `background` (R, G, B):
// the disk's linear colour is `upper` above its centre (y < centre) and `lower` below, values
// above 1 being light beyond full scale. Area-sampled 4×4, blurred by a Gaussian of σ = 0.7 px
// (optics) before the sensor clips at 1, then sRGB-encoded to 8 bits.
cv::Mat3b LitDisk(const Eigen::Vector3d& upper, const Eigen::Vector3d& lower,
                  const Eigen::Vector3d& background) {
  constexpr int kSub = 4;
  const cv::Size size(160, 140);
  cv::Mat3f linear(size);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int j = 0; j < kSub; ++j) {
        for (int i = 0; i < kSub; ++i) {
          const Eigen::Vector2d p(x - 0.5 + (i + 0.5) / kSub, y - 0.5 + (j + 0.5) / kSub);
          if ((p - kCentre).norm() >= kRadius) {
            sum += background;
          } else {
            sum += p.y() < kCentre.y() ? upper : lower;
          }
        }
      }
      sum /= kSub * kSub;
      linear(y, x) = cv::Vec3f(sum.z(), sum.y(), sum.x());  // B, G, R
    }
  }
  cv::GaussianBlur(linear, linear, cv::Size(0, 0), 0.7);
  // The sensor clips at full scale; the codes are sRGB (LinearTable's default).
  const LinearTable srgb;
  cv::Mat3b image(size);
  image.forEach([&](cv::Vec3b& code, const int* position) {
    const cv::Vec3f& value = linear(position[0], position[1]);
    for (int c = 0; c < 3; ++c) {
      code[c] = cv::saturate_cast<uchar>(srgb.Encode(std::clamp<double>(value[c], 0.0, 1.0)));
    }
  });
  return image;
}

// `count` points on the disk's true contour, outward normals, starting to the right of the
// centre and turning towards +y.
std::vector<ContourPoint> DiskContour(int count) {
  std::vector<ContourPoint> contour(count);
  for (int i = 0; i < count; ++i) {
    const double angle = 2 * test::kPi * (i + 0.5) / count;
    contour[i].normal = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    contour[i].pixel = kCentre + kRadius * contour[i].normal;
  }
  return contour;
}

const Eigen::Vector3d kGrey(0.2, 0.2, 0.2);

TEST(CountClippedPointsTest, AWhiteObjectBeyondFullScaleHasNoMeasurableBoundary) {
  const Eigen::Vector3d white(2.0, 2.0, 2.0);
  const std::vector<ContourPoint> contour = DiskContour(200);
  EXPECT_EQ(
      CountClippedPoints(contour, LitDisk(white, white, kGrey), LinearTable(), QualityOptions()),
      200);
}

TEST(CountClippedPointsTest, AnObjectBelowFullScaleIsNotCounted) {
  const Eigen::Vector3d orange(0.8, 0.3, 0.1);
  EXPECT_EQ(CountClippedPoints(DiskContour(200), LitDisk(orange, orange, kGrey), LinearTable(),
                               QualityOptions()),
            0);
}

TEST(CountClippedPointsTest, OneClippedChannelLeavesTheBoundaryInTheOthers) {
  // Red clips, green and blue still differ from the background: the edge fits measure there.
  const Eigen::Vector3d orange(2.0, 0.5, 0.05);
  EXPECT_EQ(CountClippedPoints(DiskContour(200), LitDisk(orange, orange, kGrey), LinearTable(),
                               QualityOptions()),
            0);
}

TEST(CountClippedPointsTest, OnlyTheSaturatedSideIsCounted) {
  // Lit beyond full scale above the centre, within range below: the upper half of the contour
  // (y < centre, the points 100..199) is counted, give or take the points next to the
  // horizontal diameter, whose windows see both halves.
  const std::vector<ContourPoint> contour = DiskContour(200);
  const int clipped = CountClippedPoints(
      contour, LitDisk(Eigen::Vector3d(3.0, 3.0, 3.0), Eigen::Vector3d(0.5, 0.5, 0.5), kGrey),
      LinearTable(), QualityOptions());
  EXPECT_NEAR(clipped, 100, 8);
  // None of the lower half's points far from the diameter is counted.
  std::vector<ContourPoint> lower(contour.begin() + 10, contour.begin() + 90);
  EXPECT_EQ(
      CountClippedPoints(
          lower, LitDisk(Eigen::Vector3d(3.0, 3.0, 3.0), Eigen::Vector3d(0.5, 0.5, 0.5), kGrey),
          LinearTable(), QualityOptions()),
      0);
}

TEST(CountClippedPointsTest, PointsWhoseWindowLeavesTheImageAreNotCounted) {
  const Eigen::Vector3d white(2.0, 2.0, 2.0);
  std::vector<ContourPoint> outside = DiskContour(1);
  outside[0].pixel = Eigen::Vector2d(1.0, 70.0);
  outside[0].normal = Eigen::Vector2d(-1.0, 0.0);
  EXPECT_EQ(
      CountClippedPoints(outside, LitDisk(white, white, kGrey), LinearTable(), QualityOptions()),
      0);
}

}  // namespace
}  // namespace bcot
