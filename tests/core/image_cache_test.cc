#include "bcot/core/image_cache.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

Camera CameraOfSize(int width, int height) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = 100.0;
  camera.cx = (width - 1) / 2.0;
  camera.cy = (height - 1) / 2.0;
  return camera;
}

// A 64×48 PNG whose pixels depend on `seed`, at `dir`/`name`.
std::string WriteImage(const test::TempDir& dir, const std::string& name, int seed) {
  cv::Mat3b image(48, 64);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image(y, x) = cv::Vec3b(x + seed, y * seed, x ^ y);
  }
  const std::string path = dir.File(name);
  EXPECT_TRUE(cv::imwrite(path, image));
  return path;
}

bool SamePixels(const cv::Mat3b& a, const cv::Mat3b& b) {
  return a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(DecodedImageCacheTest, KeepsImagesInReadOrderUntilTheBudgetIsSpent) {
  test::TempDir dir;
  const Camera camera = CameraOfSize(64, 48);
  const size_t image_bytes = 64 * 48 * 3;
  const std::string paths[] = {WriteImage(dir, "0.png", 1), WriteImage(dir, "1.png", 2),
                               WriteImage(dir, "2.png", 3)};
  DecodedImageCache cache(2 * image_bytes + 100);
  cv::Mat3b first_read[3];
  for (int i = 0; i < 3; ++i) {
    StatusOr<cv::Mat3b> image = cache.Read(paths[i], camera);
    ASSERT_TRUE(image.ok()) << image.status().message();
    first_read[i] = *image;
  }
  EXPECT_EQ(cache.bytes(), 2 * image_bytes);
  EXPECT_EQ(cache.hits(), 0u);
  // The first two are answered from memory (they read even with the files gone), the third is
  // decoded again.
  for (const std::string& path : paths) std::filesystem::remove(path);
  for (int i = 0; i < 2; ++i) {
    StatusOr<cv::Mat3b> image = cache.Read(paths[i], camera);
    ASSERT_TRUE(image.ok()) << image.status().message();
    EXPECT_TRUE(SamePixels(*image, first_read[i]));
  }
  EXPECT_EQ(cache.hits(), 2u);
  const StatusOr<cv::Mat3b> third = cache.Read(paths[2], camera);
  ASSERT_FALSE(third.ok());
  EXPECT_THAT(third.status().message(), HasSubstr("2.png"));
}

TEST(DecodedImageCacheTest, KeptImagesAreSharedNotCopied) {
  test::TempDir dir;
  const Camera camera = CameraOfSize(64, 48);
  const std::string path = WriteImage(dir, "a.png", 5);
  DecodedImageCache cache(size_t{1} << 20);
  const StatusOr<cv::Mat3b> decoded = cache.Read(path, camera);
  ASSERT_TRUE(decoded.ok());
  const StatusOr<cv::Mat3b> kept = cache.Read(path, camera);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ(cache.hits(), 1u);
  // The same pixels, not a copy of them.
  EXPECT_EQ(kept->data, decoded->data);
  EXPECT_TRUE(SamePixels(*kept, *decoded));
  // An image that was not kept (budget spent) is the reader's alone.
  DecodedImageCache full(0);
  const StatusOr<cv::Mat3b> first = full.Read(path, camera);
  const StatusOr<cv::Mat3b> second = full.Read(path, camera);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_NE(first->data, second->data);
  EXPECT_EQ(full.hits(), 0u);
}

TEST(DecodedImageCacheTest, KeptImagesAreCheckedAgainstEachCamera) {
  test::TempDir dir;
  const std::string path = WriteImage(dir, "a.png", 7);
  DecodedImageCache cache(size_t{1} << 20);
  ASSERT_TRUE(cache.Read(path, CameraOfSize(64, 48)).ok());
  const StatusOr<cv::Mat3b> wrong = cache.Read(path, CameraOfSize(80, 48));
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(wrong.status().message(), HasSubstr("a.png: image is 64x48"));
}

TEST(DecodedImageCacheTest, ZeroBudgetKeepsNothing) {
  test::TempDir dir;
  const std::string path = WriteImage(dir, "a.png", 11);
  DecodedImageCache cache(0);
  ASSERT_TRUE(cache.Read(path, CameraOfSize(64, 48)).ok());
  ASSERT_TRUE(cache.Read(path, CameraOfSize(64, 48)).ok());
  EXPECT_EQ(cache.bytes(), 0u);
  EXPECT_EQ(cache.hits(), 0u);
  const StatusOr<cv::Mat3b> missing = cache.Read(dir.File("none.png"), CameraOfSize(64, 48));
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.status().message(), HasSubstr("none.png"));
}

}  // namespace
}  // namespace bcot
