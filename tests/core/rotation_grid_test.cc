#include "bcot/core/rotation_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "test_util.h"

namespace bcot {
namespace {

Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

TEST(RotationGridTest, CountAndUnitQuaternionsWithNonNegativeW) {
  for (int count : {1, 7, 5000}) {
    const std::vector<Eigen::Quaterniond> grid = SuperFibonacciRotations(count);
    ASSERT_EQ(static_cast<int>(grid.size()), count);
    for (const Eigen::Quaterniond& q : grid) {
      EXPECT_NEAR(q.norm(), 1.0, 1e-12);
      EXPECT_GE(q.w(), 0.0);
    }
  }
}

TEST(RotationGridTest, QuaternionAngleTreatsSignsAsOneRotation) {
  const Eigen::Quaterniond a(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  Eigen::Quaterniond minus_a = a;
  minus_a.coeffs() = -a.coeffs();
  EXPECT_NEAR(QuaternionAngleDeg(a, minus_a), 0.0, 1e-12);
  EXPECT_NEAR(QuaternionAngleDeg(a, a), 0.0, 1e-12);
  const Eigen::Quaterniond b(Eigen::AngleAxisd(0.3 + 0.5, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(QuaternionAngleDeg(a, b), 0.5 * 180.0 / kPi, 1e-9);
  const Eigen::Quaterniond tiny(Eigen::AngleAxisd(0.3 + 1e-7, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(QuaternionAngleDeg(a, tiny), 1e-7 * 180.0 / kPi, 1e-12);
  const Eigen::Quaterniond half_turn(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(QuaternionAngleDeg(Eigen::Quaterniond::Identity(), half_turn), 180.0, 1e-9);
}

// Near-uniformity of the 5,000-rotation grid bcot init searches: no two rotations closer than
// 7°, every rotation's nearest neighbour within 14°, and every one of 2,000 random rotations
// within 13° of a grid rotation (the covering radius the refinement must capture; 5,000 balls
// cannot cover SO(3) below 8.9°).
TEST(RotationGridTest, FiveThousandRotationsAreNearUniform) {
  const std::vector<Eigen::Quaterniond> grid = SuperFibonacciRotations(5000);
  double min_nn = std::numeric_limits<double>::infinity();
  double max_nn = 0.0;
  for (int i = 0; i < static_cast<int>(grid.size()); ++i) {
    double best_dot = 0.0;
    for (int j = 0; j < static_cast<int>(grid.size()); ++j) {
      if (j != i) best_dot = std::max(best_dot, std::abs(grid[i].coeffs().dot(grid[j].coeffs())));
    }
    const double angle = 2.0 * std::acos(std::min(1.0, best_dot)) * 180.0 / kPi;
    min_nn = std::min(min_nn, angle);
    max_nn = std::max(max_nn, angle);
  }
  EXPECT_GT(min_nn, 7.0);
  EXPECT_LT(max_nn, 14.0);
  std::printf("nearest-neighbour angles %.2f..%.2f deg\n", min_nn, max_nn);

  std::mt19937 rng(11);
  double covering = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Quaterniond q = RandomRotation(rng);
    double best_dot = 0.0;
    for (const Eigen::Quaterniond& g : grid) {
      best_dot = std::max(best_dot, std::abs(g.coeffs().dot(q.coeffs())));
    }
    covering = std::max(covering, 2.0 * std::acos(std::min(1.0, best_dot)) * 180.0 / kPi);
  }
  EXPECT_LT(covering, 13.0);
  std::printf("covering radius (2,000 random rotations) %.2f deg\n", covering);
  EXPECT_GT(covering, 0.5 * max_nn);  // a real measurement, not a vacuous bound
}

}  // namespace
}  // namespace bcot
