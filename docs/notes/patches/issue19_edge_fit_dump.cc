// Fits 20,000 seeded edge profiles with the FitEdgeProfile of the library it is linked against
// and prints one line per profile: index, true centre (px), found (0/1), fitted μ, σ_μ and w.
// The profiles are of bench_edge_fit's kinds: blurred steps with and without shading ramps, a
// third with a sliver at the edge, noise σ 0.005 and 0.02.
//
// Used to compare two fits of the same profiles (docs/notes/issue19_speed.md, "The edge profile
// fit by variable projection"): build it against the release build of main, and again after
// `git apply docs/notes/patches/issue19_edge_fit_variable_projection.patch` and a rebuild, then
// `/usr/bin/python3 docs/notes/patches/issue19_edge_fit_compare.py OLD NEW`. From the repository
// root, after `cmake --build build --target bcot_optim`:
//   c++ -O2 -std=c++17 -I include -isystem /usr/include/eigen3 -isystem /usr/include/opencv4 \
//     docs/notes/patches/issue19_edge_fit_dump.cc -Wl,--start-group build/libbcot_optim.a \
//     build/libbcot_render.a build/libbcot_core.a -Wl,--end-group -lopencv_core \
//     -lopencv_imgproc -lopencv_imgcodecs -lfmt -lembree3 -ltbb -lassimp -lyaml-cpp -lceres \
//     -lglog -o /tmp/edge_fit_dump && /tmp/edge_fit_dump > FITS
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bcot/optim/edge_lines.h"

int main() {
  constexpr int kProfiles = 20000;
  constexpr int kHalf = 16;  // 33 samples 0.25 px apart, ±4 px: the edge stage's window
  const bcot::EdgeLineOptions options;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int i = 0; i < kProfiles; ++i) {
    std::normal_distribution<double> noise(0.0, i % 2 ? 0.005 : 0.02);
    const int kind = i % 3;
    const double mu = -1.0 + 2.0 * uniform(rng);
    const double width = 0.4 + 0.8 * uniform(rng);
    const double contrast = 0.1 + 0.5 * uniform(rng);
    const double outside = 0.1 + 0.3 * uniform(rng);
    const double inside_slope = kind == 1 ? -0.05 * uniform(rng) : 0.0;
    const double outside_slope = kind == 1 ? 0.02 * (uniform(rng) - 0.5) : 0.0;
    const double rim = kind == 2 ? 0.3 * (uniform(rng) - 0.5) : 0.0;  // a sliver at the edge
    std::vector<double> values;
    for (int k = -kHalf; k <= kHalf; ++k) {
      const double s = k * 0.25;
      const double inside = 0.5 * std::erfc((s - mu) / (width * std::sqrt(2.0)));
      values.push_back(outside + outside_slope * s + noise(rng) +
                       inside * (contrast + inside_slope * (s - mu)) +
                       rim * std::exp(-0.5 * std::pow((s - mu + 0.3) / width, 2)));
    }
    bcot::EdgeFit fit;
    const bool found = bcot::FitEdgeProfile(values, -kHalf * 0.25, options, &fit);
    std::printf("%d %.17g %d %.17g %.17g %.17g\n", i, mu, found ? 1 : 0, fit.mean_px,
                fit.sigma_px, fit.width_px);
  }
}
