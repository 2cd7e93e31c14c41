#include "bcot/core/image_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

cv::Mat3b Gradient(int width, int height) {
  cv::Mat3b image(height, width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image(y, x) = cv::Vec3b(x % 256, y % 256, (x + y) % 256);
  }
  return image;
}

// Keeps the first `fraction` of the file's bytes.
void Truncate(const std::string& path, double fraction) {
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, static_cast<uintmax_t>(size * fraction));
}

TEST(ImageIoTest, ReadsCompleteImagesAndChecksTheCameraSize) {
  test::TempDir dir;
  for (const char* name : {"a.png", "a.jpg"}) {
    ASSERT_TRUE(cv::imwrite(dir.File(name), Gradient(64, 48)));
    const StatusOr<cv::Mat3b> image = ReadColorImage(dir.File(name));
    ASSERT_TRUE(image.ok()) << image.status().message();
    EXPECT_EQ(image->size(), cv::Size(64, 48));
    const Camera camera("cam0", 80, 48, 50.0, 50.0, 40.0, 24.0);
    const StatusOr<cv::Mat3b> wrong = ReadCameraImage(dir.File(name), camera);
    EXPECT_EQ(wrong.status().code(), StatusCode::kInvalidInput);
    EXPECT_THAT(wrong.status().message(), HasSubstr("image is 64x48, camera 'cam0'"));
  }
}

// A truncated JPEG decodes with grey rows and a truncated PNG partly: both must be errors.
TEST(ImageIoTest, TruncatedFilesAreErrorsNamingTheFile) {
  test::TempDir dir;
  for (const double fraction : {0.9, 0.5, 0.1}) {
    ASSERT_TRUE(cv::imwrite(dir.File("t.jpg"), Gradient(64, 48)));
    Truncate(dir.File("t.jpg"), fraction);
    const StatusOr<cv::Mat3b> jpeg = ReadColorImage(dir.File("t.jpg"));
    EXPECT_EQ(jpeg.status().code(), StatusCode::kInvalidInput);
    EXPECT_THAT(jpeg.status().message(), HasSubstr("t.jpg: corrupt JPEG")) << fraction;

    ASSERT_TRUE(cv::imwrite(dir.File("t.png"), Gradient(64, 48)));
    Truncate(dir.File("t.png"), fraction);
    const StatusOr<cv::Mat3b> png = ReadColorImage(dir.File("t.png"));
    EXPECT_EQ(png.status().code(), StatusCode::kInvalidInput);
    EXPECT_THAT(png.status().message(), HasSubstr("t.png: corrupt PNG")) << fraction;
  }
  test::WriteText(dir.File("text.png"), "not an image");
  EXPECT_THAT(ReadColorImage(dir.File("text.png")).status().message(), HasSubstr("text.png"));
  EXPECT_THAT(ReadColorImage(dir.File("missing.png")).status().message(),
              HasSubstr("missing.png: cannot read"));
  // An empty file and a directory are errors naming the path, not a decoder exception.
  test::WriteText(dir.File("empty.bmp"), "");
  const StatusOr<cv::Mat3b> empty = ReadColorImage(dir.File("empty.bmp"));
  EXPECT_EQ(empty.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(empty.status().message(), HasSubstr("empty.bmp: cannot read the image"));
  ASSERT_TRUE(std::filesystem::create_directory(dir.File("folder.jpg")));
  const StatusOr<cv::Mat3b> folder = ReadColorImage(dir.File("folder.jpg"));
  EXPECT_FALSE(folder.ok());
  EXPECT_THAT(folder.status().message(), HasSubstr("folder.jpg"));
}

}  // namespace
}  // namespace bcot
