// Cost of the edge stage's blurred-step fit, FitEdgeProfile, and of a whole line across an edge
// in an image, FitEdgeAcross, with and without the correction for JPEG's subsampled chroma
// (scripts/bench_edge_fit.sh runs this and tabulates it). The edge stage and the quality check fit
// one profile per contour line, some 4,000 per binocular frame, so this fit is a large share of
// `bcot annotate`'s time (docs/notes/issue19_speed.md).
//
// Profiles: 2,000 seeded draws of the edge stage's window (33 samples, 0.25 px apart, ±4 px) in
// three kinds, a third each: a clean blurred step (contrast 0.1–0.6, blur 0.4–1.2 px, noise
// σ 0.005), the same with a shading ramp inside and a different slope outside (the shaded rims
// of issue 12), and noise without a step (no contrast: most fits fail, as on clutter). Reported:
// µs per fit, the fraction of fits found, and the mean |μ − truth| of the found step fits.
//
// Lines: 1,000 lines across straight edges between two colours that differ mostly in hue (blue
// and orange, blur σ 0.7 px, sRGB), at 8 angles (5°…85°) and sub-pixel positions, encoded as
// JPEG 4:2:0 (quality 95) and decoded by libjpeg; each line fitted as full-resolution colour
// (FitEdgeAcross_Uncorrected) and with the codec's shift taken off (FitEdgeAcross_Jpeg420).
// Reported: µs per line, the fraction found, and the mean signed and mean |μ − truth|.
#include <benchmark/benchmark.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <vector>

#include "bcot/optim/edge_lines.h"

namespace bcot {
namespace {

constexpr int kProfiles = 2000;

struct Profile {
  std::vector<double> values;
  double mean_px = 0.0;  // true centre of the step; NaN for noise
};

std::vector<Profile> MakeProfiles(const EdgeLineOptions& options) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.005);
  const int half = static_cast<int>(std::floor(options.window_px / options.step_px + 1e-9));
  std::vector<Profile> profiles(kProfiles);
  for (int i = 0; i < kProfiles; ++i) {
    Profile& profile = profiles[i];
    const int kind = i % 3;
    const double mu = -1.0 + 2.0 * uniform(rng);
    const double width = 0.4 + 0.8 * uniform(rng);
    const double contrast = 0.1 + 0.5 * uniform(rng);
    const double outside = 0.1 + 0.3 * uniform(rng);
    const double inside_slope = kind == 1 ? -0.05 * uniform(rng) : 0.0;
    const double outside_slope = kind == 1 ? 0.02 * (uniform(rng) - 0.5) : 0.0;
    profile.mean_px = kind == 2 ? std::nan("") : mu;
    for (int k = -half; k <= half; ++k) {
      const double s = k * options.step_px;
      double value = outside + outside_slope * s + noise(rng);
      if (kind != 2) {
        // Inside (s < μ) the object: contrast above the background, shaded towards the rim.
        const double inside = 0.5 * std::erfc((s - mu) / (width * std::sqrt(2.0)));
        value += inside * (contrast + inside_slope * (s - mu));
      }
      profile.values.push_back(value);
    }
  }
  return profiles;
}

void BM_FitEdgeProfile(benchmark::State& state) {
  const EdgeLineOptions options;
  const std::vector<Profile> profiles = MakeProfiles(options);
  const int half = static_cast<int>(std::floor(options.window_px / options.step_px + 1e-9));
  int found = 0, measured = 0;
  double abs_error = 0.0;
  for (auto _ : state) {
    found = measured = 0;
    abs_error = 0.0;
    for (const Profile& profile : profiles) {
      EdgeFit fit;
      const bool ok = FitEdgeProfile(profile.values, -half * options.step_px, options, &fit);
      benchmark::DoNotOptimize(fit);
      if (!ok) continue;
      ++found;
      if (std::isfinite(profile.mean_px)) {
        ++measured;
        abs_error += std::abs(fit.mean_px - profile.mean_px);
      }
    }
  }
  state.SetItemsProcessed(state.iterations() * kProfiles);
  state.counters["found_fraction"] = static_cast<double>(found) / kProfiles;
  state.counters["mean_abs_error_px"] = measured > 0 ? abs_error / measured : std::nan("");
}
BENCHMARK(BM_FitEdgeProfile)->Unit(benchmark::kMillisecond);

// One JPEG-decoded image of a straight edge and the lines across it (their centres on the true
// edge, so μ's truth is 0).
struct EdgeLineCase {
  cv::Mat3b image;
  std::vector<Eigen::Vector2d> centres;
  Eigen::Vector2d normal;
};

std::vector<EdgeLineCase> MakeEdgeLineCases() {
  const Eigen::Vector3d inside(0.55, 0.12, 0.03), outside(0.03, 0.18, 0.6);  // BGR, linear
  std::vector<EdgeLineCase> cases;
  for (int a = 0; a < 8; ++a) {
    const double angle = (5.0 + a * 80.0 / 7.0) * M_PI / 180.0;
    EdgeLineCase c;
    c.normal = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d point(60.0 + 0.37 * a, 60.0 + 0.21 * a);
    cv::Mat3b image(120, 120);
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        const double distance = c.normal.dot(Eigen::Vector2d(x, y) - point);
        const double f = 0.5 * std::erfc(-distance / (0.7 * std::sqrt(2.0)));
        for (int ch = 0; ch < 3; ++ch) {
          const double linear = inside[ch] + (outside[ch] - inside[ch]) * f;
          const double code =
              linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
          image(y, x)[ch] = static_cast<unsigned char>(std::lround(255.0 * code));
        }
      }
    }
    std::vector<unsigned char> bytes;
    cv::imencode(".jpg", image, bytes, {cv::IMWRITE_JPEG_QUALITY, 95});  // 4:2:0
    c.image = cv::imdecode(bytes, cv::IMREAD_COLOR);
    const Eigen::Vector2d tangent(-c.normal.y(), c.normal.x());
    for (int i = 0; i < 125; ++i) c.centres.push_back(point + (i - 62) * 0.4 * tangent);
    cases.push_back(std::move(c));
  }
  return cases;
}

void FitEdgeLines(benchmark::State& state, const ChromaSampling& sampling) {
  const EdgeLineOptions options;
  const LinearTable table(options.response);
  const std::vector<EdgeLineCase> cases = MakeEdgeLineCases();
  int lines = 0, found = 0;
  double signed_error = 0.0, abs_error = 0.0;
  for (auto _ : state) {
    lines = found = 0;
    signed_error = abs_error = 0.0;
    for (const EdgeLineCase& c : cases) {
      for (const Eigen::Vector2d& centre : c.centres) {
        EdgeFit fit;
        ++lines;
        if (FitEdgeAcross(c.image, table, centre, c.normal, options, &fit, sampling) !=
            EdgeAcross::kFound) {
          continue;
        }
        ++found;
        signed_error += fit.mean_px;
        abs_error += std::abs(fit.mean_px);
      }
    }
  }
  state.SetItemsProcessed(state.iterations() * lines);
  state.counters["found_fraction"] = static_cast<double>(found) / lines;
  state.counters["mean_error_px"] = found > 0 ? signed_error / found : std::nan("");
  state.counters["mean_abs_error_px"] = found > 0 ? abs_error / found : std::nan("");
}

void BM_FitEdgeAcross_Uncorrected(benchmark::State& state) {
  FitEdgeLines(state, ChromaSampling::Full());
}
BENCHMARK(BM_FitEdgeAcross_Uncorrected)->Unit(benchmark::kMillisecond);

void BM_FitEdgeAcross_Jpeg420(benchmark::State& state) {
  FitEdgeLines(state, ChromaSampling::Jpeg420());
}
BENCHMARK(BM_FitEdgeAcross_Jpeg420)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace bcot

BENCHMARK_MAIN();
