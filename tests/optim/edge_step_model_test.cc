#include "bcot/optim/edge_step_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace bcot {
namespace {

// The edge stage's fit window: 21 samples 0.25 px apart around μ0, a noisy blurred step.
struct Window {
  Eigen::ArrayXd offsets;
  Eigen::ArrayXd values;
  double mu0 = 0.0;
};

Window MakeWindow(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  Window window;
  window.mu0 = 0.25;
  window.offsets = window.mu0 + 0.25 * Eigen::ArrayXd::LinSpaced(21, -10, 10);
  window.values.resize(21);
  for (int i = 0; i < 21; ++i) {
    const double s = window.offsets[i];
    window.values[i] = 0.2 + 0.4 * 0.5 * std::erfc((s - 0.3) / (0.8 * std::sqrt(2.0))) + noise(rng);
  }
  return window;
}

// Parameter sets (a, g, b, μ, w, k): a falling step, a rising one with a kink, a narrow blur
// that puts samples far in both tails, a wide one.
std::vector<EdgeStepParams> ParameterSets() {
  std::vector<EdgeStepParams> sets(4);
  sets[0] << 0.6, 0.0, -0.4, 0.3, 0.8, 0.0;
  sets[1] << 0.1, 0.05, 0.3, -0.7, 0.6, -0.2;
  sets[2] << 0.5, -0.02, -0.25, 1.1, 0.12, 0.4;
  sets[3] << 0.3, 0.01, -0.5, 0.0, 2.4, 0.1;
  return sets;
}

// The model with the exact normal CDF (std::erfc), residual of sample i.
double ExactResidual(const Window& window, const EdgeStepParams& x, int i) {
  const double s = window.offsets[i], z = (s - x[3]) / x[4];
  const double cdf = 0.5 * std::erfc(-z / std::sqrt(2.0));
  const double pdf = std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI);
  return x[0] + x[1] * (s - window.mu0) + x[2] * cdf + x[5] * x[4] * (z * cdf + pdf) -
         window.values[i];
}

// The analytic Jacobian is the exact model's (its Φ' is the exact density φ), with Φ itself
// approximated (|ΔΦ| <= 7.5e-8) where a column contains it. The approximation's own slope differs
// from φ by up to ~1e-3 relative near z = 0 (its two branches meet there with a kink), so the
// Jacobian is checked against central differences of the exact model, to the approximation's
// error (a wrong or missing term is off by 1e-3 or more);
// ResidualsAreTheModelMinusTheSamples checks that the residuals approximate that model.
TEST(EdgeStepModelTest, JacobianMatchesCentralDifferences) {
  const Window window = MakeWindow(3);
  EdgeStepModel model(window.offsets, window.mu0, window.values);
  for (const EdgeStepParams& x : ParameterSets()) {
    Eigen::VectorXd residuals;
    Eigen::MatrixXd jacobian;
    model.ResidualsAndJacobian(x, &residuals, &jacobian);
    ASSERT_EQ(jacobian.rows(), 21);
    ASSERT_EQ(jacobian.cols(), kEdgeStepParams);
    for (int p = 0; p < kEdgeStepParams; ++p) {
      const double h = 1e-6 * std::max(1.0, std::abs(x[p]));
      EdgeStepParams plus = x, minus = x;
      plus[p] += h;
      minus[p] -= h;
      for (int i = 0; i < 21; ++i) {
        const double numeric =
            (ExactResidual(window, plus, i) - ExactResidual(window, minus, i)) / (2.0 * h);
        EXPECT_NEAR(jacobian(i, p), numeric, 3e-7)
            << "parameter " << p << ", sample " << i << ", x = " << x.transpose();
      }
    }
  }
}

TEST(EdgeStepModelTest, NormalEquationsAreThoseOfTheJacobian) {
  const Window window = MakeWindow(5);
  EdgeStepModel model(window.offsets, window.mu0, window.values);
  for (const EdgeStepParams& x : ParameterSets()) {
    Eigen::VectorXd residuals;
    Eigen::MatrixXd jacobian;
    model.ResidualsAndJacobian(x, &residuals, &jacobian);
    EdgeStepMatrix jtj;
    EdgeStepParams jtr;
    const double rss = model.Evaluate(x, &jtj, &jtr);
    EXPECT_NEAR(rss, residuals.squaredNorm(), 1e-12 * std::max(1.0, rss));
    EXPECT_NEAR(model.Evaluate(x, nullptr, nullptr), rss, 1e-15);
    const Eigen::MatrixXd expected_jtj = jacobian.transpose() * jacobian;
    const Eigen::VectorXd expected_jtr = jacobian.transpose() * residuals;
    EXPECT_LT((jtj - expected_jtj).cwiseAbs().maxCoeff(),
              1e-10 * expected_jtj.cwiseAbs().maxCoeff());
    EXPECT_LT((jtr - expected_jtr).cwiseAbs().maxCoeff(),
              1e-10 * std::max(1e-3, expected_jtr.cwiseAbs().maxCoeff()));
    EXPECT_TRUE(jtj.isApprox(jtj.transpose()));
  }
}

TEST(EdgeStepModelTest, ResidualsAreTheModelMinusTheSamples) {
  const Window window = MakeWindow(7);
  EdgeStepModel model(window.offsets, window.mu0, window.values);
  for (const EdgeStepParams& x : ParameterSets()) {
    Eigen::VectorXd residuals;
    Eigen::MatrixXd jacobian;
    model.ResidualsAndJacobian(x, &residuals, &jacobian);
    for (int i = 0; i < 21; ++i) {
      // The approximation of Φ: |ΔΦ| <= 7.5e-8, times |b| + |k·w·z| (< 1 here).
      EXPECT_NEAR(residuals[i], ExactResidual(window, x, i), 1e-7) << "sample " << i;
    }
  }
}

}  // namespace
}  // namespace bcot
