#include "bcot/core/linear_rgb.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bcot {
namespace {

TEST(ImageResponseTest, PowerLawsDecodeCodesByTheirExponent) {
  const LinearTable linear(ImageResponse::Gamma(1.0));
  const LinearTable squared(ImageResponse::Gamma(2.0));
  for (int code : {0, 1, 64, 128, 200, 255}) {
    SCOPED_TRACE(code);
    EXPECT_NEAR(linear[code], code / 255.0, 1e-7);
    EXPECT_NEAR(squared[code], std::pow(code / 255.0, 2.0), 1e-7);
  }
  // sRGB: linear toe below code 11, power segment above; close to γ 2.2 in mid-tones.
  const LinearTable srgb;
  EXPECT_NEAR(srgb[10], 10 / 255.0 / 12.92, 1e-7);
  EXPECT_NEAR(srgb[128], std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);
  EXPECT_NEAR(srgb[128], std::pow(128 / 255.0, 2.2), 0.01);
}

TEST(ImageResponseTest, NamesValidityAndEquality) {
  const ImageResponse srgb;
  const ImageResponse linear = ImageResponse::Gamma(1.0);
  const ImageResponse automatic = ImageResponse::Auto();
  EXPECT_EQ(srgb.Name(), "srgb");
  EXPECT_EQ(linear.Name(), "gamma 1");
  EXPECT_EQ(ImageResponse::Gamma(1.8).Name(), "gamma 1.8");
  EXPECT_EQ(automatic.Name(), "auto");
  EXPECT_TRUE(srgb.IsValid() && srgb.IsResolved());
  EXPECT_TRUE(automatic.IsValid());
  EXPECT_FALSE(automatic.IsResolved());
  EXPECT_FALSE(ImageResponse::Gamma(0.1).IsValid());
  EXPECT_FALSE(ImageResponse::Gamma(5.5).IsValid());
  // The exponent matters only to a power law.
  EXPECT_EQ(srgb, ImageResponse());
  EXPECT_NE(linear, ImageResponse::Gamma(1.2));
  EXPECT_NE(linear, srgb);
}

}  // namespace
}  // namespace bcot
