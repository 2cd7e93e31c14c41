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

// Calls visit(y, x) for the pixels within 2.5 px of the edge (where 4:2:0 changes them).
template <typename Visit>
void ForEdgePixels(const cv::Mat3b& image, double angle, double offset_px, Visit visit) {
  for (int y = 4; y < image.rows - 4; ++y) {
    for (int x = 4; x < image.cols - 4; ++x) {
      const double s = (x - 40.0) * std::cos(angle) + (y - 32.0) * std::sin(angle) - offset_px;
      if (std::abs(s) <= 2.5) visit(y, x);
    }
  }
}

// RMS difference in codes over the pixels near the edge.
double EdgeRms(const cv::Mat3b& image, const cv::Mat3b& truth, double angle, double offset_px) {
  double sum = 0.0;
  int count = 0;
  ForEdgePixels(image, angle, offset_px, [&](int y, int x) {
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(image(y, x)[c]) - truth(y, x)[c];
      sum += d * d;
      ++count;
    }
  });
  return std::sqrt(sum / count);
}

TEST(ChromaRestorationTest, ValidatesItsOptions) {
  EXPECT_TRUE(ChromaRestorationOptions().Validate().ok());
  ChromaRestorationOptions options;
  options.radius_px = 0;
  options.degree = 5;
  options.misfit_floor_codes2 = 0.0;
  options.isophote_sigma_px = -1.0;
  options.hue_slope_codes = std::nan("");
  const Status status = options.Validate();
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("radius_px"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("degree"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("misfit_floor_codes2"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("isophote_sigma_px"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("hue_slope_codes"), std::string::npos) << status.message();
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
      // The polynomial's fidelity, without the blend that gives up some of it for noise: a hue
      // edge like orange on grey (slope |dC/dY| ≈ 4.5) is mostly kept decoded by the default.
      ChromaRestorationOptions ungated;
      ungated.hue_slope_codes = 0.0;
      const cv::Mat3b restored = RestoreSubsampledChroma(decoded, sampling, ungated);
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

// Adds zero-mean Gaussian noise of `sigma` codes to every channel (seeded).
cv::Mat3d WithNoise(const cv::Mat3d& codes, double sigma, int seed) {
  cv::Mat3d noise(codes.size());
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  return codes + noise;
}

// Chroma RMS (Cb, Cr codes) of `image` against `truth` near the edge.
double EdgeChromaRms(const cv::Mat3b& image, const cv::Mat3b& truth, double angle,
                     double offset_px) {
  double sum = 0.0;
  int count = 0;
  ForEdgePixels(image, angle, offset_px, [&](int y, int x) {
    const cv::Vec3d d = cv::Vec3d(image(y, x)) - cv::Vec3d(truth(y, x));  // B, G, R
    const double cb = -0.168736 * d[2] - 0.331264 * d[1] + 0.5 * d[0];
    const double cr = 0.5 * d[2] - 0.418688 * d[1] - 0.081312 * d[0];
    sum += cb * cb + cr * cr;
    count += 2;
  });
  return std::sqrt(sum / count);
}

// With sensor noise, the luma the polynomial reads carries its noise into chroma; averaged along
// the isophote it carries less, and the edge's colours come back closer to the noise-free codes.
TEST(ChromaRestorationTest, AveragingAlongTheIsophoteKeepsLumaNoiseOutOfChroma) {
  const double angle = 0.4, offset_px = 0.3;
  const cv::Mat3d clean = EdgeCodes({0.1, 0.25, 1.0}, {0.3, 0.3, 0.3}, angle, offset_px, 0.8);
  const cv::Mat3b truth = Rounded(clean);
  ChromaRestorationOptions own_luma, isophote;
  own_luma.isophote_sigma_px = 0.0;
  own_luma.hue_slope_codes = 0.0;
  isophote.hue_slope_codes = 0.0;
  double rms_own = 0.0, rms_isophote = 0.0;
  for (int seed = 1; seed <= 4; ++seed) {
    const cv::Mat3b decoded = Rounded(
        SimulateChromaSubsampling(WithNoise(clean, 2.0, seed), ChromaSampling::Jpeg420()));
    rms_own += EdgeChromaRms(RestoreSubsampledChroma(decoded, ChromaSampling::Jpeg420(), own_luma),
                             truth, angle, offset_px);
    rms_isophote += EdgeChromaRms(
        RestoreSubsampledChroma(decoded, ChromaSampling::Jpeg420(), isophote), truth, angle,
        offset_px);
  }
  EXPECT_LT(rms_isophote, 0.85 * rms_own) << rms_own / 4 << " → " << rms_isophote / 4;
}

// Two colours of nearly equal luma, with sensor noise: luma can hardly tell where one ends and
// its noise would be carried into chroma many times over, so the blend by the chroma-per-luma
// slope leans on the decoded chroma there and ends closer to the noise-free colours.
TEST(ChromaRestorationTest, LeansOnTheDecodedChromaWhereLumaCannotTellTheColoursApart) {
  // Linear BGR of two colours whose sRGB codes have about the same JFIF luma, one reddish, one
  // bluish, with noise of 4 codes (about a render's sensor noise at mid grey).
  const cv::Vec3d reddish{0.18, 0.16, 0.45}, bluish{0.60, 0.19, 0.12};
  const double angle = 0.9, offset_px = -0.2;
  const cv::Mat3d codes = WithNoise(EdgeCodes(reddish, bluish, angle, offset_px, 0.8), 4.0, 7);
  {
    const cv::Mat3b clean = Rounded(EdgeCodes(reddish, bluish, angle, offset_px, 0.8));
    const cv::Vec3d step = cv::Vec3d(clean(32, 10)) - cv::Vec3d(clean(32, 70));
    ASSERT_LT(std::abs(Luma(clean(32, 10)) - Luma(clean(32, 70))), 0.1 * cv::norm(step));
  }
  const cv::Mat3b decoded = Rounded(SimulateChromaSubsampling(codes, ChromaSampling::Jpeg420()));
  ChromaRestorationOptions ungated;
  ungated.hue_slope_codes = 0.0;
  const cv::Mat3b gated_out = RestoreSubsampledChroma(decoded, ChromaSampling::Jpeg420(), {});
  const cv::Mat3b ungated_out =
      RestoreSubsampledChroma(decoded, ChromaSampling::Jpeg420(), ungated);
  const cv::Mat3b truth = Rounded(EdgeCodes(reddish, bluish, angle, offset_px, 0.8));
  const double decoded_rms = EdgeChromaRms(decoded, truth, angle, offset_px);
  const double gated_rms = EdgeChromaRms(gated_out, truth, angle, offset_px);
  const double ungated_rms = EdgeChromaRms(ungated_out, truth, angle, offset_px);
  EXPECT_LT(gated_rms, ungated_rms);
  EXPECT_LT(gated_rms, 1.2 * decoded_rms) << decoded_rms << " " << gated_rms << " " << ungated_rms;
}

// Restoring a region reads only its neighbourhood (ChromaRestorationReachPx): its pixels come out
// as the whole image's restoration gives them, the other pixels as decoded.
TEST(ChromaRestorationTest, ARegionIsRestoredAsInTheWholeImage) {
  const cv::Mat3d clean = EdgeCodes({0.1, 0.25, 1.0}, {0.3, 0.3, 0.3}, 0.4, 0.3, 0.8);
  const cv::Mat3b decoded =
      Rounded(SimulateChromaSubsampling(WithNoise(clean, 2.0, 3), ChromaSampling::Jpeg420()));
  ChromaRestorationOptions own_luma;
  own_luma.isophote_sigma_px = 0.0;
  own_luma.radius_px = 2;
  // An odd origin; grown by the reach, the crop stays off the image's border on every side.
  const cv::Rect region(23, 21, 31, 17);
  for (const ChromaRestorationOptions& options : {ChromaRestorationOptions{}, own_luma}) {
    const int reach = ChromaRestorationReachPx(options);
    ASSERT_GT(region.x - reach, 0);
    ASSERT_GT(region.y - reach, 0);
    ASSERT_LT(region.br().x + reach, decoded.cols);
    ASSERT_LT(region.br().y + reach, decoded.rows);
    const cv::Mat3b whole = RestoreSubsampledChroma(decoded, ChromaSampling::Jpeg420(), options);
    ASSERT_GT(cv::norm(whole(region), decoded(region), cv::NORM_INF), 5.0);
    cv::Mat3b expected = decoded.clone();
    whole(region).copyTo(expected(region));
    const cv::Mat3b part =
        RestoreSubsampledChroma(decoded, ChromaSampling::Jpeg420(), options, region);
    EXPECT_LE(cv::norm(part, expected, cv::NORM_INF), 1.0) << "reach " << reach;
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
