#include "bcot/core/image_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bcot/core/file_util.h"
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

// JPEGs are decoded by libjpeg straight into BGR; the pixels must be OpenCV's own decode's for
// the kinds a camera or a converter writes: baseline 4:2:0, optimised Huffman tables,
// progressive, greyscale, a size that is no multiple of the MCU. A file with an Exif orientation is
// left to OpenCV, which turns it; a CMYK-like failure of libjpeg falls back the same way (not built
// here).
TEST(ImageIoTest, JpegsDecodeToOpenCvsPixels) {
  test::TempDir dir;
  cv::Mat3b image = Gradient(157, 93);
  cv::randu(image(cv::Rect(40, 20, 60, 40)), cv::Scalar::all(0), cv::Scalar::all(255));
  cv::Mat1b grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  struct Case {
    std::string name;
    cv::Mat written;
    std::vector<int> params;
  };
  const std::vector<Case> cases = {
      {"default.jpg", image, {cv::IMWRITE_JPEG_QUALITY, 90}},
      {"optimized.jpg", image, {cv::IMWRITE_JPEG_QUALITY, 100, cv::IMWRITE_JPEG_OPTIMIZE, 1}},
      {"progressive.jpeg", image, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}},
      {"grey.jpg", grey, {}},
  };
  for (const Case& c : cases) {
    ASSERT_TRUE(cv::imwrite(dir.File(c.name), c.written, c.params)) << c.name;
    const StatusOr<cv::Mat3b> read = ReadColorImage(dir.File(c.name));
    ASSERT_TRUE(read.ok()) << read.status().message();
    const cv::Mat expected = cv::imread(dir.File(c.name), cv::IMREAD_COLOR);
    ASSERT_EQ(read->size(), expected.size()) << c.name;
    EXPECT_EQ(cv::norm(*read, expected, cv::NORM_INF), 0.0) << c.name;
  }
  // An APP1 Exif block with orientation 6 (turned 90° clockwise) after the SOI marker.
  const StatusOr<std::string> plain = ReadTextFile(dir.File("default.jpg"));
  ASSERT_TRUE(plain.ok());
  const std::string exif(
      "\xFF\xE1\x00\x22"
      "Exif\0\0II*\0\x08\0\0\0"
      "\x01\0\x12\x01\x03\0\x01\0\0\0\x06\0\0\0\0\0\0\0",
      4 + 32);
  test::WriteText(dir.File("turned.jpg"), plain->substr(0, 2) + exif + plain->substr(2));
  const StatusOr<cv::Mat3b> turned = ReadColorImage(dir.File("turned.jpg"));
  ASSERT_TRUE(turned.ok()) << turned.status().message();
  const cv::Mat expected = cv::imread(dir.File("turned.jpg"), cv::IMREAD_COLOR);
  ASSERT_EQ(expected.size(), cv::Size(93, 157));  // OpenCV applied the orientation
  ASSERT_EQ(turned->size(), expected.size());
  EXPECT_EQ(cv::norm(*turned, expected, cv::NORM_INF), 0.0);
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

// The chroma sampling comes from the frame header: OpenCV writes colour JPEGs 4:2:0; a grey
// JPEG has no chroma; a header declaring luma at 1×1 (4:4:4) is full; PNG is not a JPEG.
TEST(ReadChromaSamplingTest, ReadsTheJpegFrameHeader) {
  test::TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir.File("a.png"), Gradient(64, 48)));
  ASSERT_TRUE(cv::imwrite(dir.File("a.jpg"), Gradient(64, 48)));
  cv::Mat1b grey;
  cv::cvtColor(Gradient(64, 48), grey, cv::COLOR_BGR2GRAY);
  ASSERT_TRUE(cv::imwrite(dir.File("grey.jpg"), grey));
  EXPECT_EQ(ReadChromaSampling(dir.File("a.png")).value(), ChromaSampling::Full());
  EXPECT_EQ(ReadChromaSampling(dir.File("a.jpg")).value(), ChromaSampling::Jpeg420());
  EXPECT_EQ(ReadChromaSampling(dir.File("a.jpg"))->Name(), "4:2:0");
  EXPECT_EQ(ReadChromaSampling(dir.File("grey.jpg")).value(), ChromaSampling::Full());

  // The same colour file with its baseline frame header (SOF0: FF C0, length, precision,
  // height, width, 3 components of id, sampling HV, table) saying 1×1 for luma: 4:4:4.
  StatusOr<std::string> bytes = ReadFileContents(dir.File("a.jpg"));
  ASSERT_TRUE(bytes.ok());
  const size_t sof = bytes->find("\xFF\xC0");
  ASSERT_NE(sof, std::string::npos);
  ASSERT_EQ(static_cast<unsigned char>((*bytes)[sof + 9]), 3u);      // components
  ASSERT_EQ(static_cast<unsigned char>((*bytes)[sof + 11]), 0x22u);  // luma 2×2
  (*bytes)[sof + 11] = 0x11;
  test::WriteText(dir.File("full.jpg"), *bytes);
  EXPECT_EQ(ReadChromaSampling(dir.File("full.jpg")).value(), ChromaSampling::Full());
  // Luma 2×1: 4:2:2.
  (*bytes)[sof + 11] = 0x21;
  test::WriteText(dir.File("422.jpg"), *bytes);
  EXPECT_EQ(ReadChromaSampling(dir.File("422.jpg")).value(), ChromaSampling::Jpeg422());

  test::WriteText(dir.File("broken.jpg"), std::string("\xFF\xD8\xFF\xE0") + " not a header");
  const StatusOr<ChromaSampling> broken = ReadChromaSampling(dir.File("broken.jpg"));
  EXPECT_EQ(broken.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(broken.status().message(), HasSubstr("broken.jpg: corrupt JPEG header"));
  EXPECT_THAT(ReadChromaSampling(dir.File("missing.jpg")).status().message(),
              HasSubstr("missing.jpg: cannot read"));
}

}  // namespace
}  // namespace bcot
