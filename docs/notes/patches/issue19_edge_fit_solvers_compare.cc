// Compares FitEdgeProfile (after docs/notes/patches/issue19_edge_fit_variable_projection.patch:
// Levenberg-Marquardt on (mu, w) with the linear parameters projected out) with the six-parameter
// Levenberg-Marquardt fit it replaces (copied below as old_fit::FitEdgeProfile), on 20,000 seeded
// profiles of bench_edge_fit's kinds (blurred steps with and without shading ramps, a third with
// a sliver at the edge; noise sigma 0.005 and 0.02). Build and run from the repository root, on a
// release build with the patch applied (docs/notes/issue19_speed.md, "Variable projection"):
//   c++ -O2 -std=c++17 -I include -isystem /usr/include/eigen3 -isystem /usr/include/opencv4 \
//     docs/notes/patches/issue19_edge_fit_solvers_compare.cc -Wl,--start-group \
//     build/libbcot_optim.a build/libbcot_render.a build/libbcot_core.a -Wl,--end-group \
//     -lopencv_core -lopencv_imgproc -lopencv_imgcodecs -lfmt -lembree3 -ltbb -lassimp \
//     -lyaml-cpp -lceres -lglog -o /tmp/edge_fit_solvers && /tmp/edge_fit_solvers
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/edge_step_model.h"
namespace old_fit {
using namespace bcot;
constexpr double kInvSqrt2 = 0.70710678118654752440;
double NormalCdf(double z) { return 0.5 * std::erfc(-z * kInvSqrt2); }
bool FitEdgeProfile(const std::vector<double>& values, double first_offset_px,
                    const EdgeLineOptions& options, EdgeFit* fit, int max_iterations) {
  const int n = static_cast<int>(values.size());
  if (n < 7) return false;
  const double h = options.step_px;
  // Start: the steepest descent (the profile falls from inside to outside) within search_px.
  int best = -1;
  double steepest = 0.0;
  for (int k = 1; k + 1 < n; ++k) {
    const double s = first_offset_px + k * h;
    if (std::abs(s) > options.search_px) continue;
    const double slope = (values[k + 1] - values[k - 1]) / (2.0 * h);
    if (best < 0 || slope < steepest) {
      best = k;
      steepest = slope;
    }
  }
  if (best < 0 || !(steepest < 0.0)) return false;
  const double mu0 = first_offset_px + best * h;
  // The fit window: the samples within fit_half_px of μ0 (a contiguous run, offsets increase).
  int first = n, last = -1;
  for (int k = 0; k < n; ++k) {
    if (std::abs(first_offset_px + k * h - mu0) <= options.fit_half_px + 1e-9) {
      first = std::min(first, k);
      last = k;
    }
  }
  const int m = last - first + 1;
  if (m < 8) return false;
  const Eigen::ArrayXd offsets = first_offset_px + h * Eigen::ArrayXd::LinSpaced(m, first, last);
  EdgeStepModel model(offsets, mu0, Eigen::Map<const Eigen::ArrayXd>(values.data() + first, m));

  // Initial (a, g, b) by linear least squares at μ = μ0, w = 0.7, k = 0.
  EdgeStepParams x;
  x << 0.0, 0.0, 0.0, mu0, 0.7, 0.0;
  {
    Eigen::MatrixXd a(m, 3);
    a.col(0).setOnes();
    a.col(1) = (offsets - mu0).matrix();
    for (int i = 0; i < m; ++i) a(i, 2) = NormalCdf((offsets[i] - x[3]) / x[4]);
    const Eigen::Vector3d linear =
        a.colPivHouseholderQr().solve(Eigen::Map<const Eigen::VectorXd>(values.data() + first, m));
    x.head<3>() = linear;
  }
  EdgeStepMatrix jtj, jtj_new;
  EdgeStepParams jtr, jtr_new;
  double rss = model.Evaluate(x, &jtj, &jtr);
  double lambda = 1e-3;
  bool converged = false;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    EdgeStepMatrix damped = jtj;
    damped.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
    // λ > 0 makes the damped matrix positive definite; LDLT is the fallback for round-off.
    const Eigen::LLT<EdgeStepMatrix> cholesky(damped);
    const EdgeStepParams delta = cholesky.info() == Eigen::Success
                                     ? EdgeStepParams(-cholesky.solve(jtr))
                                     : EdgeStepParams(-damped.ldlt().solve(jtr));
    EdgeStepParams candidate = x + delta;
    if (!candidate.allFinite()) return false;
    candidate[4] = std::max(candidate[4], 0.05);
    // The normal equations cost little beside Φ and φ, which they share: evaluated with the
    // residuals, they are ready when the step is accepted.
    const double rss_new = model.Evaluate(candidate, &jtj_new, &jtr_new);
    if (rss_new <= rss) {
      x = candidate;
      rss = rss_new;
      jtj = jtj_new;
      jtr = jtr_new;
      lambda = std::max(lambda * 0.3, 1e-9);
      if (std::abs(delta[3]) < 1e-4 && std::abs(delta[4]) < 1e-4) {
        converged = true;
        break;
      }
    } else {
      lambda *= 10.0;
      if (lambda > 1e8) {
        converged = true;  // no further decrease possible: at a minimum within precision
        break;
      }
    }
  }
  if (!converged) return false;
  Eigen::FullPivLU<EdgeStepMatrix> lu(jtj);
  if (!lu.isInvertible()) return false;
  const double noise_variance = rss / std::max(1, m - kEdgeStepParams);
  const double variance = noise_variance * lu.inverse()(3, 3);
  fit->mean_px = x[3];
  fit->width_px = x[4];
  fit->step = x[2];
  fit->sigma_px = std::sqrt(std::max(0.0, variance));
  if (!std::isfinite(fit->sigma_px)) return false;
  if (std::abs(fit->mean_px) > options.search_px) return false;
  if (fit->width_px < options.min_width_px || fit->width_px > options.max_width_px) return false;
  // b < 0: the profile falls from inside (d̂ side) to outside.
  if (!(-fit->step >= options.min_snr * std::sqrt(noise_variance))) return false;
  return true;
}


}
int main() {
  bcot::EdgeLineOptions options;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int half = 16;
  int both = 0, only_old = 0, only_new = 0, far = 0; int nb[4]={0,0,0,0}, nn[4]={0,0,0,0}, no[4]={0,0,0,0}; const double th[4]={0.3,0.5,1.0,2.0}; double max_d = 0, sum_d = 0, max_sig = 0, max_w=0, err_both=0, err_new=0, err_old=0, sig_both=0, sig_new=0;
  for (int i = 0; i < 20000; ++i) {
    std::normal_distribution<double> noise(0.0, i % 2 ? 0.005 : 0.02);
    const int kind = i % 3;
    const double mu = -1.0 + 2.0 * uniform(rng), width = 0.4 + 0.8 * uniform(rng);
    const double contrast = 0.1 + 0.5 * uniform(rng), outside = 0.1 + 0.3 * uniform(rng);
    const double inside_slope = kind == 1 ? -0.05 * uniform(rng) : 0.0;
    const double outside_slope = kind == 1 ? 0.02 * (uniform(rng) - 0.5) : 0.0;
    const double rim = kind == 2 ? 0.3 * (uniform(rng) - 0.5) : 0.0;  // a sliver at the edge
    std::vector<double> values;
    for (int k = -half; k <= half; ++k) {
      const double s = k * 0.25;
      double v = outside + outside_slope * s + noise(rng);
      const double inside = 0.5 * std::erfc((s - mu) / (width * std::sqrt(2.0)));
      v += inside * (contrast + inside_slope * (s - mu));
      v += rim * std::exp(-0.5 * std::pow((s - mu + 0.3) / width, 2));
      values.push_back(v);
    }
    bcot::EdgeFit a, b;
    const bool ok_old = old_fit::FitEdgeProfile(values, -4.0, options, &a, 30);
    const bool ok_new = bcot::FitEdgeProfile(values, -4.0, options, &b, 30);
    if (ok_old && ok_new) {
      ++both; const double d = std::abs(a.mean_px - b.mean_px); sum_d += d; max_d = std::max(max_d, d);
      if (d > 1e-3) ++far;
      max_sig = std::max(max_sig, std::abs(a.sigma_px - b.sigma_px) / a.sigma_px);
      max_w = std::max(max_w, std::abs(a.width_px - b.width_px)); err_both += std::abs(b.mean_px - mu); for(int q=0;q<4;++q) nb[q]+= b.sigma_px>th[q]; sig_both += b.sigma_px;
    } else if (ok_old) { ++only_old; err_old += std::abs(a.mean_px - mu); for(int q=0;q<4;++q) no[q]+= a.sigma_px>th[q]; } else if (ok_new) { ++only_new; err_new += std::abs(b.mean_px - mu); for(int q=0;q<4;++q) nn[q]+= b.sigma_px>th[q]; sig_new += b.sigma_px; }
  }
  std::printf("mean |err| both %.4f only_new %.4f only_old %.4f; mean sigma both %.4f only_new %.4f\n", err_both/both, err_new/only_new, err_old/std::max(1,only_old), sig_both/both, sig_new/only_new);
  for(int q=0;q<4;++q) std::printf("sigma>%.1f: both %d only_new %d only_old %d\n", th[q], nb[q], nn[q], no[q]);
  std::printf("both %d only_old %d only_new %d |dmu| mean %.2e max %.2e (>1e-3: %d) max rel dsigma %.2e max dw %.2e\n",
              both, only_old, only_new, sum_d / both, max_d, far, max_sig, max_w);
}
