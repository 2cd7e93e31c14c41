// The edge fit under noise that differs across the edge (docs/notes/issue12_noise.md).
//
// A one-dimensional image: pixels of unit width across a Gaussian-blurred step (inside level
// 0.3 + contrast, outside 0.3, blur σ `--blur` px, edge at a uniformly random sub-pixel phase),
// each pixel the mean over its width, plus Gaussian noise whose standard deviation blends from
// σ_in (inside) to σ_out (outside) across the edge. The line is sampled as the edge stage samples
// an image (every edge.step_px over ±edge.window_px, linear interpolation between pixels) and
// fitted by FitEdgeProfile with the annotation config's defaults. Printed per (contrast, σ_out,
// σ_in): the fraction of lines found and the signed error of the found centres (mean, median, 10
// and 90 % quantiles; negative = inside, towards the σ_in side).
//
// Usage: build/tests/bench/edge_noise_bias [--contrast 0.3,0.1] [--sigma-out 0.01,0.03]
//            [--sigma-in 0.01,0.02,0.03,0.05,0.08] [--blur 0.7] [--trials 20000] [--seed 1]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "bcot/optim/edge_lines.h"

namespace {

double NormalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

constexpr int kHalfPixels = 8;   // pixels −8 … 8 around the line's centre
constexpr int kSubsamples = 16;  // integration points per pixel

// Where the edge stage's samples fall between the pixels (offsets k·step_px within window_px):
// sample k interpolates pixels first[k] and first[k] + 1 with weight `fraction[k]` on the second.
struct SampleLayout {
  double first_offset_px = 0.0;
  std::vector<int> first;
  std::vector<double> fraction;

  explicit SampleLayout(const bcot::EdgeLineOptions& options) {
    const int half = static_cast<int>(std::floor(options.window_px / options.step_px + 1e-9));
    first_offset_px = -half * options.step_px;
    for (int k = -half; k <= half; ++k) {
      const double s = k * options.step_px + kHalfPixels;
      const int i0 = std::min(2 * kHalfPixels - 1, static_cast<int>(std::floor(s)));
      first.push_back(i0);
      fraction.push_back(s - i0);
    }
  }
};

struct Summary {
  double found_fraction = 0.0;
  double mean = 0.0, median = 0.0, p10 = 0.0, p90 = 0.0;
};

Summary Simulate(double contrast, double sigma_out, double sigma_in, double blur_px, int trials,
                 std::mt19937* rng) {
  const bcot::EdgeLineOptions options;
  const SampleLayout layout(options);
  std::uniform_real_distribution<double> phase(-0.5, 0.5);
  std::normal_distribution<double> unit_normal(0.0, 1.0);
  std::vector<double> errors;
  std::vector<double> pixels(2 * kHalfPixels + 1), values(layout.first.size());
  for (int trial = 0; trial < trials; ++trial) {
    const double edge = phase(*rng);
    for (int i = 0; i < static_cast<int>(pixels.size()); ++i) {
      const double x = i - kHalfPixels;
      double mean = 0.0;
      for (int j = 0; j < kSubsamples; ++j) {
        const double xs = x - 0.5 + (j + 0.5) / kSubsamples;
        mean += 0.3 + contrast * (1.0 - NormalCdf((xs - edge) / blur_px));
      }
      mean /= kSubsamples;
      // The noise follows the pixel's share of the inside (blurred like the image).
      const double inside = 1.0 - NormalCdf((x - edge) / blur_px);
      const double sd =
          std::sqrt(inside * sigma_in * sigma_in + (1.0 - inside) * sigma_out * sigma_out);
      pixels[i] = mean + sd * unit_normal(*rng);
    }
    for (size_t k = 0; k < values.size(); ++k) {
      const int i0 = layout.first[k];
      const double f = layout.fraction[k];
      values[k] = (1.0 - f) * pixels[i0] + f * pixels[i0 + 1];
    }
    bcot::EdgeFit fit;
    if (bcot::FitEdgeProfile(values, layout.first_offset_px, options, &fit)) {
      errors.push_back(fit.mean_px - edge);
    }
  }
  Summary summary;
  summary.found_fraction = static_cast<double>(errors.size()) / trials;
  if (errors.empty()) return summary;
  for (const double e : errors) summary.mean += e;
  summary.mean /= static_cast<double>(errors.size());
  std::sort(errors.begin(), errors.end());
  const auto quantile = [&](double q) {
    return errors[static_cast<size_t>(q * static_cast<double>(errors.size() - 1))];
  };
  summary.median = quantile(0.5);
  summary.p10 = quantile(0.1);
  summary.p90 = quantile(0.9);
  return summary;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Edge-fit bias under noise that differs across the edge"};
  std::vector<double> contrasts{0.3, 0.1}, sigmas_out{0.01, 0.03},
      sigmas_in{0.01, 0.02, 0.03, 0.05, 0.08};
  double blur_px = 0.7;
  int trials = 20000;
  unsigned seed = 1;
  app.add_option("--contrast", contrasts, "Step heights (linear)")->delimiter(',');
  app.add_option("--sigma-out", sigmas_out, "Pixel noise outside (linear)")->delimiter(',');
  app.add_option("--sigma-in", sigmas_in, "Pixel noise inside (linear)")->delimiter(',');
  app.add_option("--blur", blur_px, "Blur σ of the step (px)")->check(CLI::PositiveNumber);
  app.add_option("--trials", trials, "Lines per row")->check(CLI::Range(1, 10000000));
  app.add_option("--seed", seed, "Random seed");
  CLI11_PARSE(app, argc, argv);

  std::mt19937 rng(seed);
  fmt::print("| contrast | σ out | σ in | found | mean error (px) | median | 10 % | 90 % |\n");
  fmt::print("|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const double contrast : contrasts) {
    for (const double sigma_out : sigmas_out) {
      for (const double sigma_in : sigmas_in) {
        const Summary s = Simulate(contrast, sigma_out, sigma_in, blur_px, trials, &rng);
        fmt::print(
            "| {:.2f} | {:.3f} | {:.3f} | {:.3f} | {:+.4f} | {:+.4f} | {:+.3f} | {:+.3f} |\n",
            contrast, sigma_out, sigma_in, s.found_fraction, s.mean, s.median, s.p10, s.p90);
      }
    }
  }
  return 0;
}
