// Cost of the edge stage's blurred-step fit, FitEdgeProfile (scripts/bench_edge_fit.sh runs this
// and tabulates it). The edge stage and the quality check fit one profile per contour line, some
// 4,000 per binocular frame, so this fit is a large share of `bcot annotate`'s time
// (docs/notes/issue19_speed.md).
//
// Profiles: 2,000 seeded draws of the edge stage's window (33 samples, 0.25 px apart, ±4 px) in
// three kinds, a third each: a clean blurred step (contrast 0.1–0.6, blur 0.4–1.2 px, noise
// σ 0.005), the same with a shading ramp inside and a different slope outside (the shaded rims
// of issue 12), and noise without a step (no contrast: most fits fail, as on clutter). Reported:
// µs per fit, the fraction of fits found, and the mean |μ − truth| of the found step fits.
#include <benchmark/benchmark.h>

#include <cmath>
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

}  // namespace
}  // namespace bcot

BENCHMARK_MAIN();
