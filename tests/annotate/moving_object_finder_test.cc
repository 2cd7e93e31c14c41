// FindMovingObject on small image sequences written to disk: a disc crossing a textured,
// noisy, static scene is found at its centre in every frame; a disc that never moves, or a
// sequence of two frames, is not.
#include "bcot/annotate/moving_object_finder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <vector>

#include "test_util.h"

namespace bcot {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 480;
constexpr double kRadius = 40.0;

// Disc centre at frame f of n: left to right across the image, or fixed when !moving.
Eigen::Vector2d DiscCentre(int f, int n, bool moving) {
  const double t = moving ? static_cast<double>(f) / (n - 1) : 0.3;
  return Eigen::Vector2d(100.0 + 440.0 * t, 200.0 + 60.0 * t);
}

// One camera, `n` frames of a red disc (anti-aliased, 4×4 supersampled coverage) over a textured
// grey-green scene with sensor noise (σ = 3 grey levels), as PNG files in `dir`.
Sequence DiscSequence(const test::TempDir& dir, int n, bool moving) {
  Sequence sequence;
  sequence.rig.Add({Camera("cam0", kWidth, kHeight, 600, 600, 319.5, 239.5), {}});
  sequence.num_frames = n;
  sequence.image_paths.resize(1);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 3.0);
  for (int f = 0; f < n; ++f) {
    const Eigen::Vector2d centre = DiscCentre(f, n, moving);
    cv::Mat3b image(kHeight, kWidth);
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        int inside = 0;
        for (int j = 0; j < 4; ++j) {
          for (int i = 0; i < 4; ++i) {
            const Eigen::Vector2d p(x - 0.375 + 0.25 * i, y - 0.375 + 0.25 * j);
            inside += (p - centre).norm() < kRadius;
          }
        }
        const double coverage = inside / 16.0;
        const double texture = 30.0 * std::sin(x / 9.0) * std::cos(y / 13.0);
        const cv::Vec3d scene(90 + texture, 130 + texture, 100 - texture);
        const cv::Vec3d disc(40, 50, 200);
        for (int c = 0; c < 3; ++c) {
          image(y, x)[c] =
              cv::saturate_cast<uchar>((1 - coverage) * scene[c] + coverage * disc[c] + noise(rng));
        }
      }
    }
    const std::string path = dir.File("frame" + std::to_string(f) + ".png");
    BCOT_CHECK(cv::imwrite(path, image));
    sequence.image_paths[0].push_back(path);
  }
  return sequence;
}

TEST(MovingObjectFinderTest, FindsAMovingDiscAtItsCentreInEveryFrame) {
  test::TempDir dir;
  const int n = 12;
  const Sequence sequence = DiscSequence(dir, n, /*moving=*/true);
  for (int f : {0, 5, n - 1}) {
    const StatusOr<std::vector<MovingObjectView>> views =
        FindMovingObject(sequence, f, MovingObjectOptions());
    ASSERT_TRUE(views.ok()) << views.status().message();
    ASSERT_EQ(views->size(), 1u);
    const MovingObjectView& view = views->front();
    EXPECT_EQ(view.camera, "cam0");
    ASSERT_TRUE(view.found) << "frame " << f;
    // Centroid of the region found vs the disc centre; the work scale is 2 px per px.
    EXPECT_LT((view.centroid_px - DiscCentre(f, n, true)).norm(), 1.5) << "frame " << f;
    const double disc_fraction = kPi * kRadius * kRadius / (kWidth * kHeight);
    EXPECT_NEAR(view.area_fraction, disc_fraction, 0.1 * disc_fraction) << "frame " << f;
  }
}

TEST(MovingObjectFinderTest, AStillObjectIsNotFound) {
  test::TempDir dir;
  const Sequence sequence = DiscSequence(dir, 6, /*moving=*/false);
  const StatusOr<std::vector<MovingObjectView>> views =
      FindMovingObject(sequence, 0, MovingObjectOptions());
  ASSERT_TRUE(views.ok()) << views.status().message();
  EXPECT_FALSE(views->front().found);
  EXPECT_LT(views->front().changed_fraction, 1e-3);
}

TEST(MovingObjectFinderTest, NeedsThreeFramesAndValidOptions) {
  test::TempDir dir;
  const Sequence two = DiscSequence(dir, 2, /*moving=*/true);
  const StatusOr<std::vector<MovingObjectView>> views =
      FindMovingObject(two, 0, MovingObjectOptions());
  ASSERT_FALSE(views.ok());
  test::ExpectErrorNaming(views.status(), StatusCode::kInvalidInput,
                          {"at least 3 frames", "--click"});

  MovingObjectOptions options;
  options.frames = 2;
  options.min_area_fraction = 1.0;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"init.motion_frames = 2", "init.motion_min_area_fraction = 1"});
}

}  // namespace
}  // namespace bcot
