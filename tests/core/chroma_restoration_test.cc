#include "bcot/core/chroma_restoration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bcot/core/chroma_sampling.h"

namespace bcot {
namespace {

double SrgbEncode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// A straight edge between two linear colours (BGR, 0..1), blurred by a Gaussian of `blur_px`,
// at angle `angle` through the image centre offset by `offset_px`, sRGB-encoded to codes.
cv::Mat3d EdgeCodes(const cv::Vec3d& inside, const cv::Vec3d& outside, double angle,
                    double offset_px, double blur_px) {
  cv::Mat3d codes(64, 80);
  const double nx = std::cos(angle), ny = std::sin(angle);
  for (int y = 0; y < codes.rows; ++y) {
    for (int x = 0; x < codes.cols; ++x) {
      const double s = (x - 40.0) * nx + (y - 32.0) * ny - offset_px;
      const double inside_share = 0.5 * std::erfc(s / (blur_px * std::sqrt(2.0)));
      for (int c = 0; c < 3; ++c) {
        codes(y, x)[c] =
            255.0 * SrgbEncode(outside[c] + (inside[c] - outside[c]) * inside_share);
      }
    }
  }
  return codes;
}

cv::Mat3b Rounded(const cv::Mat3d& codes) {
  cv::Mat3b out;
  codes.convertTo(out, CV_8UC3);  // rounds and saturates
  return out;
}

double Luma(const cv::Vec3b& p) { return 0.299 * p[2] + 0.587 * p[1] + 0.114 * p[0]; }

// RMS difference in codes over the pixels within 2.5 px of the edge (where 4:2:0 changes them).
double EdgeRms(const cv::Mat3b& image, const cv::Mat3b& truth, double angle, double offset_px) {
  double sum = 0.0;
  int count = 0;
  for (int y = 4; y < image.rows - 4; ++y) {
    for (int x = 4; x < image.cols - 4; ++x) {
      const double s = (x - 40.0) * std::cos(angle) + (y - 32.0) * std::sin(angle) - offset_px;
      if (std::abs(s) > 2.5) continue;
      for (int c = 0; c < 3; ++c) {
        const double d = static_cast<double>(image(y, x)[c]) - truth(y, x)[c];
        sum += d * d;
        ++count;
      }
    }
  }
  return std::sqrt(sum / count);
}

TEST(ChromaRestorationTest, ValidatesItsOptions) {
  EXPECT_TRUE(ChromaRestorationOptions().Validate().ok());
  ChromaRestorationOptions options;
  options.radius_px = 0;
  options.degree = 5;
  options.misfit_floor_codes2 = 0.0;
  const Status status = options.Validate();
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("radius_px"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("degree"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("misfit_floor_codes2"), std::string::npos) << status.message();
}

TEST(ChromaRestorationTest, FullResolutionChromaIsLeftAsItIs) {
  const cv::Mat3b image = Rounded(EdgeCodes({0.1, 0.25, 1.0}, {0.3, 0.3, 0.3}, 0.3, 0.2, 0.8));
  const cv::Mat3b out = RestoreSubsampledChroma(image, ChromaSampling::Full(), {});
  EXPECT_EQ(cv::norm(out, image, cv::NORM_INF), 0.0);
}

// A saturated colour against grey, as 4:2:0 decodes it: the restoration brings the edge's pixels
// back close to the lossless codes and keeps each pixel's luma.
TEST(ChromaRestorationTest, BringsBackTheColoursOfATwoColourEdge) {
  struct Case {
    cv::Vec3d inside, outside;  // linear BGR
    double angle, offset_px;
  };
  const std::vector<Case> cases = {
      {{0.1, 0.25, 1.0}, {0.3, 0.3, 0.3}, 0.3, 0.2},     // orange on grey (the plastic bunny)
      {{0.1, 0.25, 1.0}, {0.3, 0.3, 0.3}, 1.2, -0.4},
      {{0.05, 0.3, 0.05}, {0.6, 0.6, 0.6}, 2.0, 0.7},    // green on light grey
      {{0.9, 0.4, 0.1}, {0.05, 0.05, 0.05}, -0.7, 0.1},  // blue on black
  };
  for (const ChromaSampling& sampling : {ChromaSampling::Jpeg420(), ChromaSampling::Jpeg422()}) {
    for (const Case& c : cases) {
      // 4:2:2 halves chroma across only: an edge along the rows keeps its colours, and there
      // the restoration's own error (the polynomial's fit of the sRGB bend, about a code) is
      // all it adds.
      if (sampling == ChromaSampling::Jpeg422() && std::abs(std::cos(c.angle)) < 0.5) continue;
      const cv::Mat3d codes = EdgeCodes(c.inside, c.outside, c.angle, c.offset_px, 0.8);
      const cv::Mat3b truth = Rounded(codes);
      const cv::Mat3b decoded = Rounded(SimulateChromaSubsampling(codes, sampling));
      const cv::Mat3b restored = RestoreSubsampledChroma(decoded, sampling, {});
      const double before = EdgeRms(decoded, truth, c.angle, c.offset_px);
      const double after = EdgeRms(restored, truth, c.angle, c.offset_px);
      SCOPED_TRACE(sampling.Name() + " angle " + std::to_string(c.angle));
      EXPECT_GT(before, 2.0);  // the case is one 4:2:0 damages
      EXPECT_LT(after, 0.5 * before);
      double worst_luma = 0.0;
      for (int y = 0; y < decoded.rows; ++y) {
        for (int x = 0; x < decoded.cols; ++x) {
          worst_luma = std::max(worst_luma, std::abs(Luma(restored(y, x)) - Luma(decoded(y, x))));
        }
      }
      EXPECT_LT(worst_luma, 1.5);
    }
  }
}

// Where chroma carries nothing (a grey edge), nothing changes beyond rounding.
TEST(ChromaRestorationTest, LeavesAGreyEdgeAlone) {
  const cv::Mat3d codes = EdgeCodes({0.8, 0.8, 0.8}, {0.05, 0.05, 0.05}, 0.5, 0.3, 0.8);
  const cv::Mat3b decoded = Rounded(SimulateChromaSubsampling(codes, ChromaSampling::Jpeg420()));
  const cv::Mat3b restored = RestoreSubsampledChroma(decoded, ChromaSampling::Jpeg420(), {});
  EXPECT_LE(cv::norm(restored, decoded, cv::NORM_INF), 2.0);
}

}  // namespace
}  // namespace bcot
