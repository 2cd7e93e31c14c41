#include "bcot/core/chroma_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <vector>

namespace bcot {
namespace {

TEST(ChromaSamplingTest, NamesTheCommonSamplings) {
  EXPECT_EQ(ChromaSampling::Full().Name(), "4:4:4");
  EXPECT_EQ(ChromaSampling::Jpeg420().Name(), "4:2:0");
  EXPECT_EQ(ChromaSampling::Jpeg422().Name(), "4:2:2");
  EXPECT_EQ((ChromaSampling{1, 2}).Name(), "4:4:0");
  EXPECT_EQ((ChromaSampling{4, 1}).Name(), "4x1");
  EXPECT_FALSE(ChromaSampling::Full().subsampled());
  EXPECT_TRUE(ChromaSampling::Jpeg420().subsampled());
  EXPECT_TRUE(ChromaSampling::Jpeg422().simulated());
  EXPECT_FALSE((ChromaSampling{4, 1}).simulated());
}

// A smooth colour field with sharp coloured edges: a disc and a bar of saturated colours on a
// gradient, with a little noise.
cv::Mat3b ColourfulImage() {
  cv::Mat3b image(48, 64);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> noise(-3, 3);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      cv::Vec3d bgr(40 + 2 * x, 90 + y, 150 - x);
      if (std::hypot(x - 20.3, y - 22.7) < 11.0) bgr = cv::Vec3d(200, 60, 30);
      if (x > 40 && x < 47 + y / 8) bgr = cv::Vec3d(20, 160, 220);
      for (int c = 0; c < 3; ++c) {
        image(y, x)[c] = cv::saturate_cast<unsigned char>(bgr[c] + noise(rng));
      }
    }
  }
  return image;
}

// The model is libjpeg's codec without quantisation: a 4:2:0 JPEG at quality 100 (OpenCV writes
// colour JPEGs 4:2:0; its quantisation steps are 1) decodes to the simulated image within 4
// codes, 0.6 on average (the DCT's and the integer arithmetic's rounding, against continuous
// values), where it differs from the input by 4.4 codes on average and 91 at the coloured edges.
TEST(SimulateChromaSubsamplingTest, MatchesLibjpegAt420) {
  const cv::Mat3b image = ColourfulImage();
  std::vector<unsigned char> bytes;
  ASSERT_TRUE(cv::imencode(".jpg", image, bytes, {cv::IMWRITE_JPEG_QUALITY, 100}));
  const cv::Mat3b decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
  cv::Mat3d codes;
  image.convertTo(codes, CV_64F);
  const cv::Mat3d simulated = SimulateChromaSubsampling(codes, ChromaSampling::Jpeg420());
  double largest_model_error = 0.0, largest_input_change = 0.0;
  double model_error_sum = 0.0, input_change_sum = 0.0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double error = std::abs(simulated(y, x)[c] - decoded(y, x)[c]);
        largest_model_error = std::max(largest_model_error, error);
        model_error_sum += error;
        const double change = std::abs(double(image(y, x)[c]) - decoded(y, x)[c]);
        largest_input_change = std::max(largest_input_change, change);
        input_change_sum += change;
      }
    }
  }
  std::printf("mean |model - libjpeg| %.3f, mean |input - libjpeg| %.3f, largest %.1f / %.1f\n",
              model_error_sum / (image.total() * 3), input_change_sum / (image.total() * 3),
              largest_model_error, largest_input_change);
  EXPECT_LT(largest_model_error, 4.0);
  EXPECT_LT(model_error_sum, 0.25 * input_change_sum);
  EXPECT_GT(largest_input_change, 60.0);
}

// Luma is kept; 4:4:4 changes nothing; 4:2:2 averages across only (a horizontal edge, constant
// along x, comes back as it was).
TEST(SimulateChromaSubsamplingTest, KeepsLumaAndTheUnsampledAxis) {
  cv::Mat3d codes(8, 10);
  for (int y = 0; y < codes.rows; ++y) {
    for (int x = 0; x < codes.cols; ++x) {
      codes(y, x) = y < 3 ? cv::Vec3d(200, 50, 20) : cv::Vec3d(30, 120, 210);
    }
  }
  const auto luma = [](const cv::Vec3d& bgr) {
    return 0.114 * bgr[0] + 0.587 * bgr[1] + 0.299 * bgr[2];
  };
  const cv::Mat3d full = SimulateChromaSubsampling(codes, ChromaSampling::Full());
  const cv::Mat3d horizontal = SimulateChromaSubsampling(codes, ChromaSampling::Jpeg422());
  const cv::Mat3d both = SimulateChromaSubsampling(codes, ChromaSampling::Jpeg420());
  for (int y = 0; y < codes.rows; ++y) {
    for (int x = 0; x < codes.cols; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(full(y, x)[c], codes(y, x)[c], 1e-9);
        EXPECT_NEAR(horizontal(y, x)[c], codes(y, x)[c], 1e-9);
      }
      EXPECT_NEAR(luma(both(y, x)), luma(codes(y, x)), 1e-3);
    }
  }
  // Rows 2 and 3 straddle the edge inside one 2×2 block row (rows 2, 3): their colours mix.
  EXPECT_GT(std::abs(both(2, 4)[0] - codes(2, 4)[0]), 20.0);
  EXPECT_NEAR(both(0, 4)[0], codes(0, 4)[0], 1e-9);
}

}  // namespace
}  // namespace bcot
