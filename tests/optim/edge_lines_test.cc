#include "bcot/optim/edge_lines.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "test_util.h"

namespace bcot {
namespace {

// Profile of a blurred step from `inside` to `outside` at `edge` (px) with blur `width`, on
// linear trends `inside_slope` / `outside_slope` (per px) on either side, sampled at offsets
// first + k·step.
std::vector<double> StepProfile(double edge, double width, double inside, double outside,
                                double inside_slope, double outside_slope, double first,
                                double step, int count, double noise = 0.0, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gaussian(0.0, noise);
  std::vector<double> values(count);
  for (int k = 0; k < count; ++k) {
    const double s = first + k * step;
    // Sharp profile convolved with a Gaussian of σ = width, numerically.
    double sum = 0.0, weights = 0.0;
    for (int j = -200; j <= 200; ++j) {
      const double u = s + j * width * 0.02;
      const double w = std::exp(-0.5 * (j * 0.02) * (j * 0.02));
      const double sharp =
          u < edge ? inside + inside_slope * (u - edge) : outside + outside_slope * (u - edge);
      sum += w * sharp;
      weights += w;
    }
    values[k] = sum / weights + (noise > 0.0 ? gaussian(rng) : 0.0);
  }
  return values;
}

TEST(EdgeLineOptionsTest, DefaultsAreValidAndViolationsAreListed) {
  EXPECT_TRUE(EdgeLineOptions().Validate().ok());
  EdgeLineOptions options;
  options.step_px = 0.0;
  options.min_width_px = 3.0;
  options.crease_min_angle_deg = 0.0;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"step_px", "min_width_px", "crease_min_angle_deg = 0"});
}

// Samples `spacing` px apart around a circle of `radius` px centred at `centre`, one traced
// contour.
void AppendCircle(const Eigen::Vector2d& centre, double radius, double spacing, int contour_id,
                  std::vector<ContourPoint>* contour) {
  const int count = static_cast<int>(std::round(2.0 * M_PI * radius / spacing));
  for (int i = 0; i < count; ++i) {
    const double angle = 2.0 * M_PI * i / count;
    ContourPoint point;
    point.normal = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    point.pixel = centre + radius * point.normal;
    point.point_in_object = Eigen::Vector3d::Zero();
    point.contour_id = contour_id;
    contour->push_back(point);
  }
}

TEST(NumEdgeLinesTest, OneLinePerSpacingOfContourAtMostNumLines) {
  std::vector<ContourPoint> contour;
  AppendCircle({100.0, 100.0}, 50.0, 0.5, 0, &contour);  // 314 px
  // A second traced contour far away: the step from one to the other does not count.
  AppendCircle({400.0, 100.0}, 20.0, 0.5, 1, &contour);  // 126 px
  EdgeLineOptions options;
  options.line_spacing_px = 1.0;
  EXPECT_NEAR(NumEdgeLines(contour, options), 2.0 * M_PI * 70.0, 2.0);
  options.line_spacing_px = 4.0;
  EXPECT_NEAR(NumEdgeLines(contour, options), 2.0 * M_PI * 70.0 / 4.0, 1.0);
  options.num_lines = 50;
  EXPECT_EQ(NumEdgeLines(contour, options), 50);
  EXPECT_EQ(NumEdgeLines({}, options), 0);
  EXPECT_EQ(NumEdgeLines({contour[0]}, options), 1);
  options.line_spacing_px = 0.0;
  EXPECT_NE(options.Validate().message().find("line_spacing_px"), std::string::npos);
}

TEST(FitEdgeProfileTest, FindsTheCentreOfABlurredStep) {
  const EdgeLineOptions options;
  for (double edge : {-0.8, -0.37, 0.0, 0.21, 1.3}) {
    const std::vector<double> profile =
        StepProfile(edge, 0.8, 0.6, 0.2, 0.0, 0.0, -4.0, options.step_px, 33);
    EdgeFit fit;
    ASSERT_TRUE(FitEdgeProfile(profile, -4.0, options, &fit)) << edge;
    EXPECT_NEAR(fit.mean_px, edge, 0.005) << edge;
    EXPECT_NEAR(fit.width_px, 0.8, 0.02);
  }
}

// A shaded rim: the object's radiance changes linearly up to its edge (a ramp inside only) and
// the background has its own gradient. The step centre stays within 0.05 px of the edge (a
// single shared trend instead of the kink term put it 0.42 px off here).
TEST(FitEdgeProfileTest, ShadingRampsMoveTheCentreLittle) {
  const EdgeLineOptions options;
  const double edge = 0.3;
  const std::vector<double> profile =
      StepProfile(edge, 0.7, 0.3, 0.1, -0.05, 0.01, -4.0, options.step_px, 33);
  EdgeFit fit;
  ASSERT_TRUE(FitEdgeProfile(profile, -4.0, options, &fit));
  EXPECT_NEAR(fit.mean_px, edge, 0.05);
}

TEST(FitEdgeProfileTest, NoisyStepHasAnHonestSigma) {
  const EdgeLineOptions options;
  std::vector<double> errors;
  double mean_sigma = 0.0;
  for (unsigned seed = 1; seed <= 200; ++seed) {
    const std::vector<double> profile =
        StepProfile(0.2, 0.8, 0.5, 0.3, 0.0, 0.0, -4.0, options.step_px, 33, 0.01, seed);
    EdgeFit fit;
    if (!FitEdgeProfile(profile, -4.0, options, &fit)) continue;
    errors.push_back(fit.mean_px - 0.2);
    mean_sigma += fit.sigma_px;
  }
  ASSERT_GT(errors.size(), 190u);
  mean_sigma /= errors.size();
  double square = 0.0;
  for (double e : errors) square += e * e;
  const double rms = std::sqrt(square / errors.size());
  EXPECT_LT(rms, 0.25);
  EXPECT_GT(mean_sigma, 0.5 * rms);
  EXPECT_LT(mean_sigma, 2.0 * rms);
}

TEST(FitEdgeProfileTest, RejectsFlatAndRisingProfiles) {
  const EdgeLineOptions options;
  EdgeFit fit;
  EXPECT_FALSE(FitEdgeProfile(std::vector<double>(33, 0.4), -4.0, options, &fit));
  // Rising from inside to outside: the contrast direction says the profile must fall.
  const std::vector<double> rising =
      StepProfile(0.0, 0.8, 0.2, 0.6, 0.0, 0.0, -4.0, options.step_px, 33);
  EXPECT_FALSE(FitEdgeProfile(rising, -4.0, options, &fit));
  // An edge beyond the search range.
  const std::vector<double> far =
      StepProfile(3.0, 0.8, 0.6, 0.2, 0.0, 0.0, -4.0, options.step_px, 33);
  EXPECT_FALSE(FitEdgeProfile(far, -4.0, options, &fit));
}

// A vertical edge at x = edge_x (inside on the left) in an 8-bit image: linear radiance
// `inside` → `outside` per channel (BGR), blurred by a Gaussian of σ = blur_px, then clipped to
// full scale by the sensor and encoded by the camera's `response` (the order of a camera:
// optics, then saturation).
cv::Mat3b ClippedEdgeImage(double edge_x, double blur_px, const Eigen::Vector3d& inside,
                           const Eigen::Vector3d& outside, const ImageResponse& response = {}) {
  cv::Mat3b image(40, 100);
  for (int x = 0; x < image.cols; ++x) {
    const double outside_fraction = 0.5 * std::erfc(-(x - edge_x) / (blur_px * std::sqrt(2.0)));
    cv::Vec3b pixel;
    for (int c = 0; c < 3; ++c) {
      const double linear = std::min(
          1.0, inside[c] + (outside[c] - inside[c]) * outside_fraction);  // the sensor clips
      const double encoded = response.kind == ImageResponse::Kind::kGamma
                                 ? std::pow(linear, 1.0 / response.gamma)
                             : linear <= 0.0031308 ? 12.92 * linear
                                                   : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
      pixel[c] = static_cast<unsigned char>(std::lround(255.0 * encoded));
    }
    for (int y = 0; y < image.rows; ++y) image(y, x) = pixel;
  }
  return image;
}

// A bright object whose red channel is beyond full scale (a lit orange surface): the sensor
// clips the blurred step after the optics, so the clipped channel's 50 % point moves towards
// the dark side. Measured on the channels that are not clipped, the edge is found as well as
// for the same surface below full scale (within 0.05 px: bilinear sampling of 8-bit pixel
// values leaves a few hundredths of a pixel that depend on the edge's sub-pixel phase); with
// the clipped channel in, it is found 0.15 px or more outside.
TEST(FitEdgeAcrossTest, ClippedChannelsAreLeftOut) {
  const Eigen::Vector3d clipped(0.05, 0.35, 1.8);    // BGR: orange, red beyond full scale
  const Eigen::Vector3d unclipped(0.05, 0.35, 0.9);  // the same surface in dimmer light
  const Eigen::Vector3d wall(0.15, 0.12, 0.20);
  const Eigen::Vector2d centre(50.0, 20.0), normal(1.0, 0.0);
  EdgeLineOptions ignored;
  ignored.clip_level = 2.0;  // never clipped
  for (double edge : {-0.3, 0.0, 0.35}) {
    SCOPED_TRACE(edge);
    EdgeFit reference, fit, biased;
    ASSERT_EQ(FitEdgeAcross(ClippedEdgeImage(50.0 + edge, 0.8, unclipped, wall), LinearTable(),
                            centre, normal, EdgeLineOptions(), &reference),
              EdgeAcross::kFound);
    EXPECT_NEAR(reference.mean_px, edge, 0.05);
    const cv::Mat3b image = ClippedEdgeImage(50.0 + edge, 0.8, clipped, wall);
    ASSERT_EQ(FitEdgeAcross(image, LinearTable(), centre, normal, EdgeLineOptions(), &fit),
              EdgeAcross::kFound);
    EXPECT_NEAR(fit.mean_px, edge, 0.05);
    ASSERT_EQ(FitEdgeAcross(image, LinearTable(), centre, normal, ignored, &biased),
              EdgeAcross::kFound);
    EXPECT_GT(biased.mean_px - reference.mean_px, 0.15);
  }
}

// A linear camera's edge decoded as sRGB bends every blurred step: its centre moves towards the
// bright side (here the object, 4× brighter than the wall: found 0.3 px inside); the camera's
// own response finds it within the 8-bit sampling error.
constexpr double kWrongResponseShiftPx = 0.2;

TEST(FitEdgeAcrossTest, EdgesAreDecodedWithTheCameraResponse) {
  const ImageResponse linear = ImageResponse::Gamma(1.0);
  const Eigen::Vector3d object(0.2, 0.45, 0.8), wall(0.05, 0.1, 0.2);  // BGR, linear
  const Eigen::Vector2d centre(50.0, 20.0), normal(1.0, 0.0);
  for (double edge : {-0.3, 0.0, 0.35}) {
    SCOPED_TRACE(edge);
    const cv::Mat3b image = ClippedEdgeImage(50.0 + edge, 0.7, object, wall, linear);
    EdgeFit right, wrong;
    ASSERT_EQ(FitEdgeAcross(image, LinearTable(linear), centre, normal, EdgeLineOptions(), &right),
              EdgeAcross::kFound);
    EXPECT_NEAR(right.mean_px, edge, 0.05);
    ASSERT_EQ(FitEdgeAcross(image, LinearTable(), centre, normal, EdgeLineOptions(), &wrong),
              EdgeAcross::kFound);
    EXPECT_LT(wrong.mean_px - edge, -kWrongResponseShiftPx);
  }
}

// A straight edge through `point` with outward unit `normal` (inside, `inside` linear BGR; the
// other side `outside`), blurred by a Gaussian of σ = blur_px, clipped to full scale by the
// sensor and sRGB-encoded.
cv::Mat3b ObliqueEdgeImage(const Eigen::Vector2d& point, const Eigen::Vector2d& normal,
                           double blur_px, const Eigen::Vector3d& inside,
                           const Eigen::Vector3d& outside) {
  cv::Mat3b image(96, 96);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const double distance = normal.dot(Eigen::Vector2d(x, y) - point);
      const double outside_fraction = 0.5 * std::erfc(-distance / (blur_px * std::sqrt(2.0)));
      for (int c = 0; c < 3; ++c) {
        const double linear =
            std::min(1.0, inside[c] + (outside[c] - inside[c]) * outside_fraction);
        const double encoded =
            linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
        image(y, x)[c] = static_cast<unsigned char>(std::lround(255.0 * encoded));
      }
    }
  }
  return image;
}

// Mean and root mean square of the edge's error across lines along it, over the lines found,
// and the fraction found, measured on `image` (whose edge passes through `point` with `normal`)
// as stored with `sampling`.
struct EdgeErrors {
  double mean_px = 0.0;
  double rms_px = 0.0;
  double found = 0.0;
};
EdgeErrors ErrorsAlongEdge(const cv::Mat3b& image, const Eigen::Vector2d& point,
                           const Eigen::Vector2d& normal, const ChromaSampling& sampling,
                           const EdgeLineOptions& options = EdgeLineOptions()) {
  const Eigen::Vector2d tangent(-normal.y(), normal.x());
  double sum = 0.0, squares = 0.0;
  int lines = 0, found = 0;
  for (double t = -20.0; t <= 20.0; t += 0.5) {
    ++lines;
    EdgeFit fit;
    if (FitEdgeAcross(image, LinearTable(), point + t * tangent, normal, options, &fit, sampling) !=
        EdgeAcross::kFound) {
      continue;
    }
    sum += fit.mean_px;
    squares += fit.mean_px * fit.mean_px;
    ++found;
  }
  if (found == 0) return {std::nan(""), std::nan(""), 0.0};
  return {sum / found, std::sqrt(squares / found), static_cast<double>(found) / lines};
}

// The codec model is libjpeg's: real 4:2:0 JPEGs (quality 100, so quantisation is small) of
// straight edges between colours that differ more in hue than in brightness, at sub-pixel
// positions. At angles away from the pixel axes, measured as full-resolution colour, the edges
// move outward by 0.08–0.17 px on average along them (0.09–0.25 px RMS); with the codec's shift
// taken off, by at most 0.05 px (0.02 px over all cases, RMS 0.03–0.1 px), and at least 95 % of
// the lines are still found (a line whose simulated fits fail is rejected). Along a pixel
// axis the shift depends on the edge's position in the 2×2 blocks so strongly (−0.34…+0.73 px)
// that the fit's centre and width do not identify the edge: there the correction is weak or the
// lines are rejected (reported, not asserted).
constexpr double kCorrectedChromaMeanPx = 0.06;
constexpr double kCorrectedChromaRmsPx = 0.12;

TEST(FitEdgeAcrossTest, SubsampledChromaIsCorrectedFor) {
  const Eigen::Vector3d blue(0.55, 0.12, 0.03), orange(0.03, 0.18, 0.6);  // BGR, linear
  const Eigen::Vector3d dark_blue(0.25, 0.05, 0.01), green(0.05, 0.3, 0.08);
  double uncorrected_sum = 0.0, corrected_sum = 0.0;
  int oblique_cases = 0;
  for (const auto& [inside, outside] : {std::pair(blue, orange), std::pair(dark_blue, green)}) {
    for (double angle_deg : {0.0, 20.0, 45.0, 70.0}) {
      for (double offset : {0.0, 0.25, 0.5, 0.75}) {
        SCOPED_TRACE(testing::Message() << (inside == blue ? "blue" : "dark blue") << ", angle "
                                        << angle_deg << ", offset " << offset);
        const double angle = angle_deg * M_PI / 180.0;
        const Eigen::Vector2d normal(std::cos(angle), std::sin(angle));
        const Eigen::Vector2d point(48.0 + offset, 48.0 + 0.5 * offset);
        const cv::Mat3b image = ObliqueEdgeImage(point, normal, 0.7, inside, outside);
        std::vector<unsigned char> bytes;
        // OpenCV writes colour JPEGs 4:2:0 (ReadChromaSamplingTest).
        ASSERT_TRUE(cv::imencode(".jpg", image, bytes, {cv::IMWRITE_JPEG_QUALITY, 100}));
        const cv::Mat3b decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
        const EdgeErrors uncorrected =
            ErrorsAlongEdge(decoded, point, normal, ChromaSampling::Full());
        const EdgeErrors corrected =
            ErrorsAlongEdge(decoded, point, normal, ChromaSampling::Jpeg420());
        std::printf(
            "%-9s angle %2.0f offset %.2f: 4:2:0 as full colour %+.3f / %.3f px, "
            "corrected %+.3f / %.3f px (%.0f %% found)\n",
            inside == blue ? "blue" : "dark blue", angle_deg, offset, uncorrected.mean_px,
            uncorrected.rms_px, corrected.mean_px, corrected.rms_px, 100.0 * corrected.found);
        if (angle_deg == 0.0) continue;
        EXPECT_GT(uncorrected.mean_px, 0.05);
        EXPECT_GE(corrected.found, 0.95);
        EXPECT_LT(std::abs(corrected.mean_px), kCorrectedChromaMeanPx);
        EXPECT_LT(corrected.rms_px, kCorrectedChromaRmsPx);
        uncorrected_sum += uncorrected.mean_px;
        corrected_sum += corrected.mean_px;
        ++oblique_cases;
      }
    }
  }
  EXPECT_GT(uncorrected_sum / oblique_cases, 0.1);
  EXPECT_LT(std::abs(corrected_sum / oblique_cases), 0.03);
}

// A 4:2:0 JPEG of a lit orange surface whose red is beyond full scale: the sensor clips the
// blurred red step after the optics, so its clipped top reaches towards the wall, and the codec
// carries that shape into the decoded green and blue (whose chroma they share), where the edge
// is measured. Drawn at full scale in the codec's simulation (edge.saturated_level_fit off), the
// red makes the correction wrong by 0.11–0.40 px outward (on average +0.20 px at 1.6× full scale,
// +0.32 px at 3×); with the level above full scale fitted (edge_lines.h, "Subsampled chroma"),
// the edge is found within 0.1 px in every case and within 0.03 px on average, as for the same
// surface below full scale. The fit on the decoded frame itself (before the correction) fails on up
// to 11 % of the lines of a channel at 3× full scale: their green and blue are too far from a
// blurred step.
constexpr double kCorrectedClippedChromaPx = 0.1;

TEST(FitEdgeAcrossTest, SubsampledChromaOfAClippedChannelIsCorrectedFor) {
  const Eigen::Vector3d wall(0.22, 0.16, 0.10);  // BGR, linear
  const double reds[] = {0.9, 1.6, 3.0};
  EdgeLineOptions at_full_scale;
  at_full_scale.saturated_level_fit = false;
  double sums[3] = {0.0, 0.0, 0.0}, full_scale_sums[3] = {0.0, 0.0, 0.0};
  int cases = 0;
  for (double angle_deg : {20.0, 45.0, 70.0}) {
    for (double offset : {0.0, 0.25, 0.5, 0.75}) {
      const double angle = angle_deg * M_PI / 180.0;
      const Eigen::Vector2d normal(std::cos(angle), std::sin(angle));
      const Eigen::Vector2d point(48.0 + offset, 48.0 + 0.5 * offset);
      EdgeErrors errors[3];
      for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(testing::Message()
                     << "angle " << angle_deg << ", offset " << offset << ", red " << reds[k]);
        const cv::Mat3b image =
            ObliqueEdgeImage(point, normal, 0.7, Eigen::Vector3d(0.04, 0.30, reds[k]), wall);
        std::vector<unsigned char> bytes;
        ASSERT_TRUE(cv::imencode(".jpg", image, bytes, {cv::IMWRITE_JPEG_QUALITY, 100}));
        const cv::Mat3b decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
        errors[k] = ErrorsAlongEdge(decoded, point, normal, ChromaSampling::Jpeg420());
        full_scale_sums[k] +=
            ErrorsAlongEdge(decoded, point, normal, ChromaSampling::Jpeg420(), at_full_scale)
                .mean_px;
        EXPECT_GE(errors[k].found, reds[k] < 1.0 ? 0.95 : 0.85);
        EXPECT_LT(std::abs(errors[k].mean_px),
                  reds[k] < 1.0 ? kCorrectedChromaMeanPx : kCorrectedClippedChromaPx);
        sums[k] += errors[k].mean_px;
      }
      std::printf(
          "angle %2.0f offset %.2f, corrected: red 0.9 %+.3f px (%.0f %% found), 1.6 %+.3f px "
          "(%.0f %%), 3.0 %+.3f px (%.0f %%)\n",
          angle_deg, offset, errors[0].mean_px, 100.0 * errors[0].found, errors[1].mean_px,
          100.0 * errors[1].found, errors[2].mean_px, 100.0 * errors[2].found);
      ++cases;
    }
  }
  for (int k = 0; k < 3; ++k) {
    std::printf("red %.1f: mean %+.3f px fitted, %+.3f px drawn at full scale\n", reds[k],
                sums[k] / cases, full_scale_sums[k] / cases);
    EXPECT_LT(std::abs(sums[k] / cases), 0.03);
  }
  // Below full scale the option changes nothing; above, drawing at full scale is 0.1 px off.
  EXPECT_DOUBLE_EQ(full_scale_sums[0], sums[0]);
  EXPECT_GT(full_scale_sums[1] / cases, 0.1);
  EXPECT_GT(full_scale_sums[2] / cases, 0.1);
}

// With the restoration on, the edge stage's last round measures a 4:2:0 frame on a copy whose
// chroma is restored around the contour (EdgeImageOf), read as full colour; off, or with chroma
// at full resolution, on the frame itself. The pixels away from the contour stay as decoded.
// Printed beside: where the lines find these clean two-colour edges on the decoded frame read as
// full colour, with the per-line correction, and on the restored copy, at the default ridge and
// at 0.01 codes² (docs/notes/issue12_jpeg_chroma.md, "The restoration moved into the edge
// stage").
TEST(EdgeImageOfTest, RestoresTheChromaAroundTheContourOnly) {
  const Eigen::Vector3d blue(0.55, 0.12, 0.03), orange(0.03, 0.18, 0.6);  // BGR, linear
  const Eigen::Vector3d dark_blue(0.25, 0.05, 0.01), green(0.05, 0.3, 0.08);
  ChromaRestorationOptions restoration;
  restoration.enabled = true;
  const EdgeLineOptions options;
  for (const auto& [inside, outside] : {std::pair(blue, orange), std::pair(dark_blue, green)}) {
    for (double angle_deg : {20.0, 45.0, 70.0}) {
      SCOPED_TRACE(testing::Message() << (inside == blue ? "blue" : "dark blue") << ", angle "
                                      << angle_deg);
      const double angle = angle_deg * M_PI / 180.0;
      const Eigen::Vector2d normal(std::cos(angle), std::sin(angle)), point(48.25, 48.125);
      std::vector<unsigned char> bytes;
      ASSERT_TRUE(cv::imencode(".jpg", ObliqueEdgeImage(point, normal, 0.7, inside, outside),
                               bytes, {cv::IMWRITE_JPEG_QUALITY, 100}));
      const cv::Mat3b decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
      Silhouette silhouette;  // the contour along the edge, as ErrorsAlongEdge's lines
      const Eigen::Vector2d tangent(-normal.y(), normal.x());
      for (double t = -20.0; t <= 20.0; t += 0.5) {
        ContourPoint contour_point;
        contour_point.pixel = point + t * tangent;
        contour_point.normal = normal;
        contour_point.point_in_object.setZero();
        silhouette.contour.push_back(contour_point);
      }

      const EdgeImage off = EdgeImageOf(decoded, ChromaSampling::Jpeg420(),
                                        ChromaRestorationOptions(), silhouette, options);
      EXPECT_EQ(off.image.data, decoded.data);
      EXPECT_TRUE(off.sampling.subsampled());
      EXPECT_EQ(EdgeImageOf(decoded, ChromaSampling::Full(), restoration, silhouette, options)
                    .image.data,
                decoded.data);

      const EdgeImage restored =
          EdgeImageOf(decoded, ChromaSampling::Jpeg420(), restoration, silhouette, options);
      EXPECT_FALSE(restored.sampling.subsampled());
      // Only the contour's box grown by the lines' window and a pixel (5 px) is written.
      double top = 1e9, bottom = -1e9;
      for (const ContourPoint& p : silhouette.contour) {
        top = std::min(top, p.pixel.y());
        bottom = std::max(bottom, p.pixel.y());
      }
      const int first_row = static_cast<int>(std::floor(top)) - 6;
      const int last_row = static_cast<int>(std::ceil(bottom)) + 7;
      ASSERT_GT(first_row, 0);
      ASSERT_LT(last_row, decoded.rows - 1);
      EXPECT_EQ(cv::norm(restored.image.rowRange(0, first_row), decoded.rowRange(0, first_row),
                         cv::NORM_INF),
                0.0);
      EXPECT_EQ(cv::norm(restored.image.rowRange(last_row, decoded.rows),
                         decoded.rowRange(last_row, decoded.rows), cv::NORM_INF),
                0.0);
      EXPECT_GT(cv::norm(restored.image, decoded, cv::NORM_INF), 5.0);

      const EdgeErrors as_full = ErrorsAlongEdge(decoded, point, normal, ChromaSampling::Full());
      const EdgeErrors corrected =
          ErrorsAlongEdge(decoded, point, normal, ChromaSampling::Jpeg420());
      const EdgeErrors on_restored =
          ErrorsAlongEdge(restored.image, point, normal, restored.sampling);
      ChromaRestorationOptions small_ridge = restoration;
      small_ridge.ridge_luma_codes2 = 0.01;
      const EdgeImage restored_small_ridge =
          EdgeImageOf(decoded, ChromaSampling::Jpeg420(), small_ridge, silhouette, options);
      const EdgeErrors on_small_ridge = ErrorsAlongEdge(restored_small_ridge.image, point, normal,
                                                        restored_small_ridge.sampling);
      std::printf(
          "%-9s angle %2.0f: as full colour %+.3f / %.3f px, corrected %+.3f / %.3f px, "
          "restored %+.3f / %.3f px (ridge 0.01: %+.3f / %.3f px)\n",
          inside == blue ? "blue" : "dark blue", angle_deg, as_full.mean_px, as_full.rms_px,
          corrected.mean_px, corrected.rms_px, on_restored.mean_px, on_restored.rms_px,
          on_small_ridge.mean_px, on_small_ridge.rms_px);
      EXPECT_GE(on_restored.found, 0.95);
    }
  }
}

// Changes a view's image before it is tracked, given its camera and the true cam_from_object.
using ImageEdit =
    std::function<void(const RayCaster&, const Camera&, const Eigen::Isometry3d&, cv::Mat3b*)>;

// A `bcot synth` scene (config + overrides) synthesized into a temporary directory, with its
// ground truth and mesh (CHECKed to load).
struct SynthesizedScene {
  SynthesizedScene(const std::string& config, const std::vector<std::string>& overrides) {
    StatusOr<SynthOptions> synth = ReadSynthOptions(test::SourcePath(config), overrides);
    BCOT_CHECK(synth.ok());
    const std::string out = dir.File("seq");
    BCOT_CHECK(Synthesize(*synth, out).ok());
    StatusOr<Sequence> loaded = LoadSequence(out);
    BCOT_CHECK(loaded.ok());
    sequence = *std::move(loaded);
    StatusOr<std::vector<Eigen::Isometry3d>> poses = ReadPoseFile(out + "/gt/rig_from_object.txt");
    BCOT_CHECK(poses.ok());
    truth = *std::move(poses);
    StatusOr<Mesh> loaded_mesh = Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm);
    BCOT_CHECK(loaded_mesh.ok());
    mesh = std::make_unique<Mesh>(*std::move(loaded_mesh));
  }

  const test::TempDir dir;
  Sequence sequence;
  std::vector<Eigen::Isometry3d> truth;  // rig_from_object per frame
  std::unique_ptr<Mesh> mesh;
};

// Norm of the mean signed error (mm) of the object centre per camera, tracking frames 1..6 of
// a `bcot synth` scene (config + overrides) from the truth with `options`, each image changed
// by `edit` when given, the views' chroma read as stored with `chroma`.
std::vector<double> TrackedBiasNorms(const std::string& config,
                                     const std::vector<std::string>& overrides,
                                     const MultiViewTrackerOptions& options,
                                     const ImageEdit& edit = nullptr,
                                     const ChromaSampling& chroma = ChromaSampling::Full()) {
  const SynthesizedScene scene(config, overrides);
  const Sequence& sequence = scene.sequence;
  const std::vector<Eigen::Isometry3d>& truth = scene.truth;
  const RayCaster caster(*scene.mesh);
  const Eigen::Isometry3d objcentre_from_template = scene.mesh->objcentre_from_template();
  std::vector<TrackedView> views;
  for (int c = 0; c < sequence.rig.size(); ++c) {
    views.push_back({sequence.rig[c].camera, sequence.rig[c].cam_from_rig, 1.0, chroma});
  }
  auto images_of = [&](int frame) {
    std::vector<cv::Mat3b> images;
    for (int c = 0; c < sequence.rig.size(); ++c) {
      images.emplace_back(cv::imread(sequence.image_paths[c][frame]));
      if (edit) {
        edit(caster, sequence.rig[c].camera, sequence.rig[c].cam_from_rig * truth[frame],
             &images.back());
      }
    }
    return images;
  };
  StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
      MultiViewTracker::Create(caster, views, options);
  BCOT_CHECK(tracker.ok());
  Eigen::Isometry3d pose = truth[0] * objcentre_from_template.inverse();
  BCOT_CHECK((*tracker)->Reset(images_of(0), pose).ok());
  std::vector<Eigen::Vector3d> sum(views.size(), Eigen::Vector3d::Zero());
  for (int frame = 1; frame < sequence.num_frames; ++frame) {
    BCOT_CHECK((*tracker)->Track(images_of(frame), &pose).ok());
    const Eigen::Isometry3d expected = truth[frame] * objcentre_from_template.inverse();
    for (size_t c = 0; c < views.size(); ++c) {
      sum[c] += (views[c].cam_from_rig * pose).translation() -
                (views[c].cam_from_rig * expected).translation();
    }
  }
  std::vector<double> norms;
  for (const Eigen::Vector3d& s : sum) norms.push_back(s.norm() / (sequence.num_frames - 1));
  return norms;
}

// End to end: the shaded-rim scene (configs/synth/shaded_rim.yaml: key light from above, low
// ambient, background tinted towards the object colour, 0.6 px blur, JPEG 4:2:0) tracked from
// the truth. With the region energy alone the mean signed error of the object centre is
// 0.6–0.7 mm per camera (the colour posteriors put the contour up to 1 px outside the true one
// on the dark lower rim and ~0.5 px elsewhere); the edge stage brings it below 0.25 mm.
constexpr double kRegionBiasAtLeastMm = 0.4;
constexpr double kEdgeBiasBelowMm = 0.25;

TEST(EdgeStageTest, RemovesMostOfTheShadedRimBias) {
  const std::vector<std::string> overrides = {"motion.num_frames=7", "render.threads=2",
                                              "object.specular=0"};
  MultiViewTrackerOptions region_only;
  region_only.frame.edge.enabled = false;
  const std::vector<double> region =
      TrackedBiasNorms("configs/synth/shaded_rim.yaml", overrides, region_only);
  const std::vector<double> edge =
      TrackedBiasNorms("configs/synth/shaded_rim.yaml", overrides, MultiViewTrackerOptions());
  for (size_t c = 0; c < region.size(); ++c) {
    SCOPED_TRACE(c);
    EXPECT_GT(region[c], kRegionBiasAtLeastMm);
    EXPECT_LT(edge[c], kEdgeBiasBelowMm);
  }
}

// The same scene's JPEG 4:2:0 frames read as 4:2:0, the last edge round on chroma restored
// around the object (EdgeRefineOptions::chroma_restoration): the tracker runs the restoration
// end to end and keeps the shaded rim's bias as low.
TEST(EdgeStageTest, RestoredChromaKeepsTheShadedRimBiasDown) {
  const std::vector<std::string> overrides = {"motion.num_frames=7", "render.threads=2",
                                              "object.specular=0"};
  MultiViewTrackerOptions restored;
  restored.frame.edge.chroma_restoration.enabled = true;
  const std::vector<double> edge = TrackedBiasNorms("configs/synth/shaded_rim.yaml", overrides,
                                                    restored, nullptr, ChromaSampling::Jpeg420());
  for (size_t c = 0; c < edge.size(); ++c) {
    SCOPED_TRACE(c);
    std::printf("camera %zu: mean signed error %.3f mm\n", c, edge[c]);
    EXPECT_LT(edge[c], kEdgeBiasBelowMm);
  }
}

// The saturated-rim scene (configs/synth/saturated_rim.yaml: the red channel of the lit
// surfaces beyond full scale, clipped after the blur), measured where the clipping acts: the
// edge lines at the true pose, whose contour is the true one, so each line's μ is its own error
// (as tests/bench/edge_bias_probe does). Measured over these 7 frames, 200 lines per view: mean
// μ −0.110 / −0.042 px (cam0 / cam1) with the clipped channel, +0.005 / −0.022 px without it.
// (An earlier form of this test compared the norm of the tracked pose's mean signed error
// over 6 frames, with the clipped channel and without: 0.0315 → 0.0196 mm. Tracked longer, the
// difference fades into what any other change of the solver moves it by: 0.028 → 0.026 mm over
// 12 frames with RBOT's background memory of the colour model, 0.027 → 0.022 mm over 6 and
// 0.015 → 0.015 mm over 19 with the default, color.local_background_memory = image. It did
// not isolate the clipping.)
TEST(EdgeStageTest, SaturatedRimsAreMeasuredOnTheUnclippedChannels) {
  const SynthesizedScene scene("configs/synth/saturated_rim.yaml",
                               {"motion.num_frames=7", "render.threads=2"});
  const Sequence& sequence = scene.sequence;
  const std::vector<Eigen::Isometry3d>& truth = scene.truth;
  const RayCaster caster(*scene.mesh);
  const Eigen::Isometry3d template_from_objcentre = scene.mesh->objcentre_from_template().inverse();

  EdgeLineOptions handling;
  handling.num_lines = 200;
  handling.line_spacing_px = 0.01;   // num_lines decides
  handling.crease_contours = false;  // the saturated rims are the silhouette's
  EdgeLineOptions clipping_ignored = handling;
  clipping_ignored.clip_level = 2.0;
  // Mean μ (px) of every line of view c over the sequence.
  auto mean_offset = [&](const EdgeLineOptions& options, int c) {
    double sum = 0.0;
    int count = 0;
    for (int frame = 0; frame < sequence.num_frames; ++frame) {
      const cv::Mat3b image = cv::imread(sequence.image_paths[c][frame]);
      const RigCamera& view = sequence.rig[c];
      const Silhouette silhouette =
          RenderSilhouette(caster, view.camera, view.cam_from_rig * truth[frame]);
      const StatusOr<CorrespondenceLines> lines =
          BuildEdgeLines(caster, view.camera, view.cam_from_rig,
                         truth[frame] * template_from_objcentre, image, silhouette, options);
      EXPECT_TRUE(lines.ok());
      if (!lines.ok()) continue;
      for (const CorrespondenceLine& line : lines->lines) {
        sum += line.mean_px;
        ++count;
      }
    }
    EXPECT_GT(count, 100 * sequence.num_frames);
    return sum / std::max(count, 1);
  };
  for (int c = 0; c < sequence.rig.size(); ++c) {
    SCOPED_TRACE(c);
    const double ignored = mean_offset(clipping_ignored, c);
    const double handled = mean_offset(handling, c);
    EXPECT_LT(ignored, -0.03);
    EXPECT_LT(std::abs(handled), 0.03);
    EXPECT_LT(std::abs(handled), 0.75 * std::abs(ignored));
  }
}

// With edge.occlusion_contours the edge lines also run across the occlusion contours inside the
// silhouette (one gear tooth in front of the next), with edge.crease_contours across the mesh's
// creases (the edges of the teeth, which `bcot synth` shades sharp): on `bcot synth` images of
// the pinion at the true pose both find the image step where the mesh puts it, as the
// silhouette's lines do (occlusion: 2,084 lines, median +0.044 px, IQR 0.40 px; creases:
// 2,826 lines, +0.010 px inside, 0.31 px; the silhouette's 3,669: −0.043, 0.47).
TEST(EdgeStageTest, InnerContourLinesFindTheStepAtTheTruePose) {
  const SynthesizedScene scene("configs/synth/shaded_rim.yaml",
                               {"object.mesh=" + test::SourcePath("data/meshes/pinion.off"),
                                "motion.num_frames=3", "render.threads=2"});
  const RayCaster caster(*scene.mesh);
  const Eigen::Isometry3d template_from_objcentre = scene.mesh->objcentre_from_template().inverse();
  EdgeLineOptions outer_only;
  outer_only.response.kind = ImageResponse::Kind::kSrgb;
  outer_only.crease_contours = false;
  EdgeLineOptions with_occlusion = outer_only;
  with_occlusion.occlusion_contours = true;
  EdgeLineOptions with_creases = outer_only;
  with_creases.crease_contours = true;
  std::vector<double> outer_offsets, occlusion_offsets, crease_offsets;
  for (int c = 0; c < scene.sequence.rig.size(); ++c) {
    const RigCamera& view = scene.sequence.rig[c];
    for (int frame = 0; frame < scene.sequence.num_frames; ++frame) {
      const cv::Mat3b image = cv::imread(scene.sequence.image_paths[c][frame]);
      const Silhouette silhouette =
          RenderSilhouette(caster, view.camera, view.cam_from_rig * scene.truth[frame]);
      const Eigen::Isometry3d rig_from_objcentre = scene.truth[frame] * template_from_objcentre;
      const auto lines = [&](const EdgeLineOptions& options) {
        StatusOr<CorrespondenceLines> built = BuildEdgeLines(
            caster, view.camera, view.cam_from_rig, rig_from_objcentre, image, silhouette, options);
        BCOT_CHECK(built.ok());
        return std::move(built).value();
      };
      const CorrespondenceLines outer = lines(outer_only);
      // The silhouette's lines come first and are the same; the rest are the inner contour's.
      for (const auto& [options, offsets] : {std::pair(with_occlusion, &occlusion_offsets),
                                             std::pair(with_creases, &crease_offsets)}) {
        const CorrespondenceLines both = lines(options);
        ASSERT_GE(both.lines.size(), outer.lines.size());
        for (size_t i = 0; i < both.lines.size(); ++i) {
          if (i < outer.lines.size()) {
            EXPECT_EQ(both.lines[i].mean_px, outer.lines[i].mean_px);
          } else {
            offsets->push_back(both.lines[i].mean_px);
          }
        }
      }
      for (const CorrespondenceLine& line : outer.lines) outer_offsets.push_back(line.mean_px);
    }
  }
  // The pinion's teeth hide each other along about half as much contour as its silhouette.
  ASSERT_GT(occlusion_offsets.size(), outer_offsets.size() / 4);
  ASSERT_GT(crease_offsets.size(), outer_offsets.size() / 4);
  // Median and interquartile range of the offsets (px).
  auto quartiles = [](std::vector<double> offsets) {
    std::sort(offsets.begin(), offsets.end());
    const size_t n = offsets.size();
    return std::make_pair(offsets[n / 2], offsets[3 * n / 4] - offsets[n / 4]);
  };
  const auto [outer_median, outer_iqr] = quartiles(outer_offsets);
  for (const auto& [name, offsets] :
       {std::pair("occlusion", &occlusion_offsets), std::pair("crease", &crease_offsets)}) {
    const auto [median, iqr] = quartiles(*offsets);
    fprintf(stderr, "%s: %zu lines, median %+.3f, IQR %.3f (outer %zu, %+.3f, %.3f)\n", name,
            offsets->size(), median, iqr, outer_offsets.size(), outer_median, outer_iqr);
    EXPECT_LT(std::abs(median), 0.1) << name;
    EXPECT_LT(iqr, 1.25 * outer_iqr) << name;
  }
}

// Glossy and metal rims under real light often carry no step at the geometric edge: the
// outermost sliver reflects what lies behind the object, and the image edge is found up to 2 px
// inside on some lines while the others are right (docs/notes/issue12_rim_profiles.md: the
// measured μ is bimodal). Here the outer 1.5 px of the upper rim take the colour found 3 px
// outside the contour on alternate 8 px stretches: half of the upper lines are then measured
// ~1.5 px inside. One residual block per line lets a robust loss discount them; the Cauchy loss
// (the default) does so better than Huber, which only bounds their influence.
void EraseUpperRimStretches(const RayCaster& caster, const Camera& camera,
                            const Eigen::Isometry3d& cam_from_object, double depth_px,
                            cv::Mat3b* image) {
  const Silhouette silhouette = RenderSilhouette(caster, camera, cam_from_object, ContourOptions{});
  const cv::Mat3b original = image->clone();
  const cv::Rect bounds(0, 0, image->cols, image->rows);
  for (const ContourPoint& point : silhouette.contour) {
    if (point.normal.y() > -0.5) continue;
    if (static_cast<int>(std::floor(point.pixel.x() / 8.0)) % 2 != 0) continue;
    const Eigen::Vector2d outside = point.pixel + 3.0 * point.normal;
    const cv::Point source(static_cast<int>(std::lround(outside.x())),
                           static_cast<int>(std::lround(outside.y())));
    if (!bounds.contains(source)) continue;
    for (double s = -depth_px; s <= 0.25; s += 0.25) {
      const Eigen::Vector2d at = point.pixel + s * point.normal;
      const cv::Point target(static_cast<int>(std::lround(at.x())),
                             static_cast<int>(std::lround(at.y())));
      if (bounds.contains(target)) (*image)(target) = original(source);
    }
  }
}

// The edit above, `depth_px` deep, as an image edit of TrackedBiasNorms.
ImageEdit EraseAlternateUpperRimStretches(double depth_px) {
  return [depth_px](const RayCaster& caster, const Camera& camera,
                    const Eigen::Isometry3d& cam_from_object, cv::Mat3b* image) {
    EraseUpperRimStretches(caster, camera, cam_from_object, depth_px, image);
  };
}

TEST(EdgeStageTest, RobustLossDiscountsRimsWithoutAStepAtTheEdge) {
  const std::vector<std::string> overrides = {"motion.num_frames=7", "render.threads=2"};
  // Two rounds of the loss under test and no Tukey round (the next test's), which would
  // discount these lines after either loss.
  MultiViewTrackerOptions cauchy;
  cauchy.frame.edge.rounds = 2;
  cauchy.frame.edge.redescending_rounds = 0;
  MultiViewTrackerOptions huber = cauchy;
  huber.frame.edge.robust_loss = EdgeRobustLoss::kHuber;
  const std::vector<double> clean =
      TrackedBiasNorms("configs/synth/shaded_rim.yaml", overrides, cauchy);
  const std::vector<double> bounded = TrackedBiasNorms("configs/synth/shaded_rim.yaml", overrides,
                                                       huber, EraseAlternateUpperRimStretches(1.5));
  const std::vector<double> discounted = TrackedBiasNorms(
      "configs/synth/shaded_rim.yaml", overrides, cauchy, EraseAlternateUpperRimStretches(1.5));
  // Measured per camera: clean 0.066 mm; erased rims 0.178 mm with Huber, 0.068 mm with Cauchy.
  for (size_t c = 0; c < clean.size(); ++c) {
    SCOPED_TRACE(c);
    EXPECT_GT(bounded[c], 0.12);
    EXPECT_LT(discounted[c], 0.09);
    EXPECT_LT(discounted[c], 0.5 * bounded[c]);
    EXPECT_LT(discounted[c], clean[c] + 0.02);
  }
}

// The same rims erased only 0.75 px deep: half of the upper lines are then measured ~0.75 px
// inside, near Cauchy's threshold (3σ, σ >= 0.1 px), where its weight still pulls. A last
// round with Tukey's loss (edge.redescending_rounds), started where the Cauchy rounds ended,
// gives them none.
TEST(EdgeStageTest, RedescendingRoundDiscountsLinesMeasuredSlightlyInside) {
  const std::vector<std::string> overrides = {"motion.num_frames=7", "render.threads=2"};
  const ImageEdit shallow = EraseAlternateUpperRimStretches(0.75);
  // The same number of edge rounds: two with Cauchy's loss, or one and then one with Tukey's
  // (the default).
  MultiViewTrackerOptions cauchy_only;
  cauchy_only.frame.edge.rounds = 2;
  cauchy_only.frame.edge.redescending_rounds = 0;
  const MultiViewTrackerOptions redescending;
  ASSERT_EQ(redescending.frame.edge.rounds + redescending.frame.edge.redescending_rounds, 2);
  const std::vector<double> pulled =
      TrackedBiasNorms("configs/synth/shaded_rim.yaml", overrides, cauchy_only, shallow);
  const std::vector<double> discounted =
      TrackedBiasNorms("configs/synth/shaded_rim.yaml", overrides, redescending, shallow);
  // Measured per camera: 0.113 mm with two Cauchy rounds, 0.039 mm with one and a Tukey round.
  for (size_t c = 0; c < pulled.size(); ++c) {
    SCOPED_TRACE(c);
    EXPECT_GT(pulled[c], 0.09);
    EXPECT_LT(discounted[c], 0.07);
    EXPECT_LT(discounted[c], 0.6 * pulled[c]);
  }
}

}  // namespace
}  // namespace bcot
