#include "bcot/optim/motion_prior_cost.h"

#include <ceres/gradient_checker.h>
#include <ceres/numeric_diff_options.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "test_util.h"

namespace bcot {
namespace {

using test::kPi;

Eigen::Isometry3d Pose(const Eigen::Vector3d& rotation_vector, const Eigen::Vector3d& t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = ExpSO3(rotation_vector);
  pose.translation() = t;
  return pose;
}

Vector6d TestWeights() {
  Vector6d weights;
  weights << 1.0 / 0.2, 1.0 / 0.3, 1.0 / 0.5, 300.0, 500.0, 700.0;  // 1/mm, 1/rad
  return weights;
}

struct Triple {
  std::string name;
  Eigen::Isometry3d a, b, c;
};

// Seeded triples of rig_from_objcentre: identity, typical frame steps, absolute rotations near
// π, and large relative rotations between consecutive frames (up to 2.5 rad).
std::vector<Triple> Triples() {
  std::mt19937 rng(29);
  std::vector<Triple> triples;
  triples.push_back({"identity", Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(),
                     Eigen::Isometry3d::Identity()});
  struct Spec {
    const char* name;
    double absolute_rad;
    double step_rad;
    double step_mm;
  };
  for (const Spec& spec : {Spec{"small steps", 0.7, 0.03, 2.0},
                           Spec{"near-pi absolute rotation", kPi - 1e-3, 0.05, 3.0},
                           Spec{"large relative rotations", 2.0, 1.2, 40.0},
                           Spec{"very large relative rotations", 3.0, 2.5, 80.0}}) {
    for (int seed = 0; seed < 3; ++seed) {
      const Eigen::Isometry3d a =
          Pose(spec.absolute_rad * test::RandomUnitVector(rng),
               Eigen::Vector3d(30, -20, 500) + 50 * test::RandomUnitVector(rng));
      const Eigen::Isometry3d b = a * Pose(spec.step_rad * test::RandomUnitVector(rng),
                                           spec.step_mm * test::RandomUnitVector(rng));
      const Eigen::Isometry3d c = b * Pose(spec.step_rad * test::RandomUnitVector(rng),
                                           spec.step_mm * test::RandomUnitVector(rng));
      triples.push_back({std::string(spec.name) + " " + std::to_string(seed), a, b, c});
    }
  }
  return triples;
}

// ceres::GradientChecker through the Se3Manifold of every block: numeric differentiation
// along X ⊕ δ against the analytic SE(3) Jacobians of the header, at one set of poses.
void ExpectGradientCheckerAccepts(const ceres::CostFunction& cost, const std::string& name,
                                  const std::vector<Eigen::Isometry3d>& poses) {
  Se3Manifold manifold;
  std::vector<const ceres::Manifold*> manifolds(poses.size(), &manifold);
  ceres::NumericDiffOptions numeric_options;
  // Ridders' default first step is 1% of each ambient coordinate: 0.01 of a quaternion
  // coefficient (~1°) or 5 mm of a 500 mm translation; the extrapolation from there leaves
  // ~1e-4 relative error on the rotation columns. 1e-4 keeps the steps in the linear regime.
  numeric_options.ridders_relative_initial_step_size = 1e-4;
  ceres::GradientChecker checker(&cost, &manifolds, numeric_options);
  std::vector<PoseParameters> blocks;
  for (const Eigen::Isometry3d& pose : poses) blocks.push_back(ToPoseParameters(pose));
  std::vector<const double*> parameters;
  for (const PoseParameters& block : blocks) parameters.push_back(block.data());
  ceres::GradientChecker::ProbeResults results;
  // Ceres' relative error is per entry: 1e-5 as in region_cost_test.cc, since entries of
  // ~1e-5 (next to entries of ~300) carry ~1e-11 of numeric round-off.
  EXPECT_TRUE(checker.Probe(parameters.data(), 1e-5, &results))
      << name << ": max relative error " << results.maximum_relative_error << "\n"
      << results.error_log.substr(0, 4000);
  std::printf("[ %s ] max relative Jacobian error %.2e\n", name.c_str(),
              results.maximum_relative_error);
}

// kDecoupled is zero when the centre moves on a straight line at constant speed in the rig
// while the object spins at constant body angular velocity, and equals W times the change of
// both velocities otherwise.
TEST(ConstantVelocityCostTest, DecoupledIsZeroOnStraightCentreAndConstantSpin) {
  const ConstantVelocityCost cost(TestWeights(), MotionPriorForm::kDecoupled);
  std::mt19937 rng(37);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Vector3d omega = 0.1 * test::RandomUnitVector(rng);
    const Eigen::Vector3d velocity = 5.0 * test::RandomUnitVector(rng);
    const Eigen::Isometry3d a =
        Pose(2.5 * test::RandomUnitVector(rng), 400.0 * test::RandomUnitVector(rng));
    const Eigen::Isometry3d b =
        Pose(LogSO3(Eigen::Matrix3d(a.linear() * ExpSO3(omega))), a.translation() + velocity);
    Eigen::Isometry3d c =
        Pose(LogSO3(Eigen::Matrix3d(b.linear() * ExpSO3(omega))), b.translation() + velocity);
    PoseParameters pa = ToPoseParameters(a), pb = ToPoseParameters(b), pc = ToPoseParameters(c);
    const double* parameters[] = {pa.data(), pb.data(), pc.data()};
    Vector6d residual;
    ASSERT_TRUE(cost.Evaluate(parameters, residual.data(), nullptr));
    EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-9) << trial;
    // The SE(3) form is not zero on this motion (the straight path bends in the body frame).
    EXPECT_GT(VelocityChange(a, b, c, MotionPriorForm::kSe3).head<3>().norm(), 1e-3) << trial;

    const Eigen::Vector3d kick_mm(0.5, -0.2, 0.1);
    const Eigen::Vector3d kick_rad(0.002, 0.0, -0.001);
    c = Pose(LogSO3(Eigen::Matrix3d(b.linear() * ExpSO3(omega + kick_rad))),
             b.translation() + velocity + kick_mm);
    pc = ToPoseParameters(c);
    ASSERT_TRUE(cost.Evaluate(parameters, residual.data(), nullptr));
    Vector6d expected;
    expected << -kick_mm, -kick_rad;
    expected = TestWeights().cwiseProduct(expected);
    EXPECT_LT((residual - expected).cwiseAbs().maxCoeff(), 1e-7) << trial;
  }
}

// r = W·(ξ₁ − ξ₂) is zero on a constant-velocity screw motion (any velocity, any start pose)
// and equals W times the change of body twist otherwise.
TEST(ConstantVelocityCostTest, ZeroOnConstantVelocityAndWeightedVelocityChangeOtherwise) {
  const ConstantVelocityCost cost(TestWeights());
  std::mt19937 rng(31);
  for (int trial = 0; trial < 5; ++trial) {
    Vector6d velocity;
    velocity << 5.0 * test::RandomUnitVector(rng), 0.1 * test::RandomUnitVector(rng);
    const Eigen::Isometry3d a =
        Pose(2.5 * test::RandomUnitVector(rng), 400.0 * test::RandomUnitVector(rng));
    const Eigen::Isometry3d b = a * ExpSE3(velocity);
    const Eigen::Isometry3d c = b * ExpSE3(velocity);
    PoseParameters pa = ToPoseParameters(a), pb = ToPoseParameters(b), pc = ToPoseParameters(c);
    const double* parameters[] = {pa.data(), pb.data(), pc.data()};
    Vector6d residual;
    ASSERT_TRUE(cost.Evaluate(parameters, residual.data(), nullptr));
    EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-9) << trial;

    Vector6d kick;
    kick << 0.5, -0.2, 0.1, 0.002, 0.0, -0.001;
    const Eigen::Isometry3d c_kicked = b * ExpSE3(velocity + kick);
    pc = ToPoseParameters(c_kicked);
    ASSERT_TRUE(cost.Evaluate(parameters, residual.data(), nullptr));
    const Vector6d expected = -TestWeights().cwiseProduct(kick);
    EXPECT_LT((residual - expected).cwiseAbs().maxCoeff(), 1e-8) << trial;
    EXPECT_LT((VelocityChange(a, b, c_kicked) + kick).cwiseAbs().maxCoeff(), 1e-10) << trial;
  }
}

// Seeded quadruples for ConstantAccelerationCost: the triples of Triples() extended by one
// more step of the same size.
struct Quad {
  std::string name;
  Eigen::Isometry3d a, b, c, d;
};

std::vector<Quad> Quads() {
  std::mt19937 rng(41);
  std::vector<Quad> quads;
  for (const Triple& triple : Triples()) {
    const double step_rad =
        LogSO3(Eigen::Matrix3d(triple.b.linear().transpose() * triple.c.linear())).norm();
    const double step_mm = (triple.c.translation() - triple.b.translation()).norm();
    const Eigen::Isometry3d d = triple.c * Pose(step_rad * test::RandomUnitVector(rng),
                                                step_mm * test::RandomUnitVector(rng));
    quads.push_back({triple.name, triple.a, triple.b, triple.c, d});
  }
  return quads;
}

// Both priors, both forms: every block of every seeded triple / quadruple.
class MotionPriorCostFormTest : public ::testing::TestWithParam<MotionPriorForm> {};

TEST_P(MotionPriorCostFormTest, GradientCheckerAcceptsEveryBlock) {
  const ConstantVelocityCost velocity(TestWeights(), GetParam());
  for (const Triple& triple : Triples()) {
    ExpectGradientCheckerAccepts(velocity, "velocity " + triple.name,
                                 {triple.a, triple.b, triple.c});
  }
  const ConstantAccelerationCost acceleration(TestWeights(), GetParam());
  for (const Quad& quad : Quads()) {
    ExpectGradientCheckerAccepts(acceleration, "acceleration " + quad.name,
                                 {quad.a, quad.b, quad.c, quad.d});
  }
}

INSTANTIATE_TEST_SUITE_P(Forms, MotionPriorCostFormTest,
                         ::testing::Values(MotionPriorForm::kSe3, MotionPriorForm::kDecoupled));

// The residual of a 6-residual prior at `poses` (no Jacobians).
Vector6d Residual(const ceres::CostFunction& cost, const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<PoseParameters> blocks;
  for (const Eigen::Isometry3d& pose : poses) blocks.push_back(ToPoseParameters(pose));
  std::vector<const double*> parameters;
  for (const PoseParameters& block : blocks) parameters.push_back(block.data());
  Vector6d residual;
  EXPECT_TRUE(cost.Evaluate(parameters.data(), residual.data(), nullptr));
  return residual;
}

// kDecoupled is zero when the centre moves with constant acceleration in the rig and the body
// angular velocity changes by the same rotation vector every frame; a kick of the last step
// shows up as W times the kick. The velocity prior is not zero on that motion.
TEST(ConstantAccelerationCostTest, DecoupledIsZeroOnConstantAcceleration) {
  const ConstantAccelerationCost cost(TestWeights(), MotionPriorForm::kDecoupled);
  std::mt19937 rng(43);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Vector3d omega = 0.05 * test::RandomUnitVector(rng),
                          alpha = 0.01 * test::RandomUnitVector(rng);
    const Eigen::Vector3d velocity = 3.0 * test::RandomUnitVector(rng),
                          acceleration = 0.8 * test::RandomUnitVector(rng);
    std::vector<Eigen::Isometry3d> poses = {
        Pose(2.5 * test::RandomUnitVector(rng), 400.0 * test::RandomUnitVector(rng))};
    const auto step = [&](int k, const Eigen::Vector3d& kick_mm, const Eigen::Vector3d& kick_rad) {
      const Eigen::Isometry3d& x = poses.back();
      poses.push_back(
          Pose(LogSO3(Eigen::Matrix3d(x.linear() * ExpSO3(omega + k * alpha + kick_rad))),
               x.translation() + velocity + k * acceleration + kick_mm));
    };
    for (int k = 0; k < 3; ++k) step(k, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    EXPECT_LT(Residual(cost, poses).cwiseAbs().maxCoeff(), 1e-9) << trial;
    EXPECT_GT(VelocityChange(poses[0], poses[1], poses[2], MotionPriorForm::kDecoupled).norm(), 0.1)
        << trial;

    const Eigen::Vector3d kick_mm(0.5, -0.2, 0.1), kick_rad(0.002, 0.0, -0.001);
    poses.pop_back();
    step(2, kick_mm, kick_rad);
    const Vector6d residual = Residual(cost, poses);
    Vector6d expected;
    expected << kick_mm, kick_rad;
    expected = TestWeights().cwiseProduct(expected);
    EXPECT_LT((residual - expected).cwiseAbs().maxCoeff(), 1e-7) << trial;
    EXPECT_LT(
        (AccelerationChange(poses[0], poses[1], poses[2], poses[3], MotionPriorForm::kDecoupled) -
         TestWeights().cwiseInverse().cwiseProduct(residual))
            .cwiseAbs()
            .maxCoeff(),
        1e-12)
        << trial;
  }
}

// kSe3 is zero when the body twist per frame changes by the same twist every frame.
TEST(ConstantAccelerationCostTest, Se3IsZeroOnConstantTwistChange) {
  const ConstantAccelerationCost cost(TestWeights());
  std::mt19937 rng(47);
  for (int trial = 0; trial < 5; ++trial) {
    Vector6d twist, change;
    twist << 5.0 * test::RandomUnitVector(rng), 0.1 * test::RandomUnitVector(rng);
    change << 0.5 * test::RandomUnitVector(rng), 0.01 * test::RandomUnitVector(rng);
    std::vector<Eigen::Isometry3d> poses = {
        Pose(2.5 * test::RandomUnitVector(rng), 400.0 * test::RandomUnitVector(rng))};
    for (int k = 0; k < 3; ++k) poses.push_back(poses.back() * ExpSE3(twist + k * change));
    EXPECT_LT(Residual(cost, poses).cwiseAbs().maxCoeff(), 1e-9) << trial;
  }
}

}  // namespace
}  // namespace bcot
