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

// A log encoding: every code step is the same ratio of light, 2^(stops / 255); white is 1 and
// code 0 is black.
TEST(LinearTableTest, LogEncodingSpansItsStops) {
  const LinearTable log(ImageResponse::Log(8.0));
  EXPECT_FLOAT_EQ(log[255], 1.0f);
  EXPECT_FLOAT_EQ(log[0], 0.0f);
  EXPECT_NEAR(log[1], std::exp2(-8.0 * 254.0 / 255.0), 1e-9);
  EXPECT_NEAR(log[128] / log[127], std::exp2(8.0 / 255.0), 1e-6);
  EXPECT_NEAR(std::log2(log[255] / log[1]), 8.0 * 254.0 / 255.0, 1e-5);
}

// Decode and Encode are the table as a continuous curve: at integer codes Decode is the table,
// between them linear; Encode inverts it for every response, including the flat start of a
// log encoding (code 0 = black) and values outside the table (clamped).
TEST(LinearTableTest, EncodeInvertsDecodeBetweenCodes) {
  for (const ImageResponse& response : {ImageResponse(), ImageResponse::Gamma(1.0),
                                        ImageResponse::Gamma(2.6), ImageResponse::Log(10.0)}) {
    SCOPED_TRACE(response.Name());
    const LinearTable table(response);
    EXPECT_DOUBLE_EQ(table.Decode(77.0), table[77]);
    EXPECT_DOUBLE_EQ(table.Decode(77.25), 0.75 * table[77] + 0.25 * table[78]);
    for (double code = 0.0; code <= 255.0; code += 0.37) {
      if (table.Decode(code) <= table[0]) continue;  // flat: no unique inverse
      EXPECT_NEAR(table.Encode(table.Decode(code)), code, 1e-3) << code;
    }
    EXPECT_EQ(table.Encode(-0.5), 0.0);
    EXPECT_EQ(table.Encode(1.5), 255.0);
    EXPECT_EQ(table.Decode(300.0), table[255]);
  }
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
  EXPECT_EQ(ImageResponse::Log(10.0).Name(), "log 10");
  EXPECT_TRUE(ImageResponse::Log(10.0).IsValid());
  EXPECT_FALSE(ImageResponse::Log(3.0).IsValid());
  EXPECT_FALSE(ImageResponse::Log(21.0).IsValid());
  EXPECT_NE(ImageResponse::Log(10.0), ImageResponse::Log(12.0));
  // The exponent matters only to a power law, the stops only to a log encoding.
  ImageResponse log_with_gamma = ImageResponse::Log(10.0);
  log_with_gamma.gamma = 1.0;
  EXPECT_EQ(log_with_gamma, ImageResponse::Log(10.0));
  ImageResponse gamma_with_stops = ImageResponse::Gamma(1.0);
  gamma_with_stops.log_stops = 5.0;
  EXPECT_EQ(gamma_with_stops, linear);
  EXPECT_EQ(srgb, ImageResponse());
  EXPECT_NE(linear, ImageResponse::Gamma(1.2));
  EXPECT_NE(linear, srgb);
}

}  // namespace
}  // namespace bcot
