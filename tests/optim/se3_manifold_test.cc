#include "bcot/optim/se3_manifold.h"

#include <ceres/ceres.h>
#include <ceres/gradient_checker.h>
#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include <random>

#include "bcot/core/se3.h"

namespace bcot {
namespace {

using namespace ceres;  // NOLINT: the invariant matchers expect ceres names unqualified

Vector6d RandomTwist(std::mt19937& rng, double rotation_scale, double translation_scale) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Vector6d twist;
  for (int k = 0; k < 3; ++k) twist[k] = translation_scale * uniform(rng);
  for (int k = 3; k < 6; ++k) twist[k] = rotation_scale * uniform(rng);
  return twist;
}

TEST(Se3ManifoldTest, InvariantsHold) {
  std::mt19937 rng(23);
  Se3Manifold manifold;
  for (int trial = 0; trial < 20; ++trial) {
    const PoseParameters x = ToPoseParameters(ExpSE3(RandomTwist(rng, 2.0, 300.0)));
    const Vector6d delta = RandomTwist(rng, 0.5, 20.0);
    // y is reached from x by a tangent step shorter than π so the quaternion sign is kept.
    PoseParameters y;
    manifold.Plus(x.data(), RandomTwist(rng, 1.0, 50.0).data(), y.data());
    const Eigen::VectorXd xd = x, yd = y, dd = delta;
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, xd, dd, yd, 1e-9);
  }
}

TEST(Se3ManifoldTest, PlusIsRightMultiplicationByExp) {
  std::mt19937 rng(29);
  Se3Manifold manifold;
  for (double angle : {0.0, 1e-9, 0.3, kPi - 1e-3}) {
    const Eigen::Isometry3d t = ExpSE3(RandomTwist(rng, 1.5, 200.0));
    Vector6d delta = RandomTwist(rng, 1.0, 10.0);
    delta.tail<3>() = angle * delta.tail<3>().normalized();
    const PoseParameters x = ToPoseParameters(t);
    PoseParameters result;
    ASSERT_TRUE(manifold.Plus(x.data(), delta.data(), result.data()));
    const Eigen::Isometry3d expected = t * ExpSE3(delta);
    EXPECT_LT(
        (FromPoseParameters(result.data()).matrix() - expected.matrix()).cwiseAbs().maxCoeff(),
        1e-10)
        << angle;
  }
}

// A residual written as an explicit function of the pose: the pixel of a model point
// X_o seen by a camera, r = π(K·cam_from_rig·rig_from_objcentre·X_o) − observed. Its Lie
// Jacobian is ∂π/∂X_c · R_c·[I | −X_o^] (DESIGN.md S.19), handed to Ceres through
// AmbientFromLieJacobian. The gradient checker compares it with numeric differentiation
// through the manifold, which proves the ambient/tangent bookkeeping.
class PointProjectionCost final : public SizedCostFunction<2, 7> {
 public:
  PointProjectionCost(const Eigen::Isometry3d& cam_from_rig, const Eigen::Vector3d& point)
      : cam_from_rig_(cam_from_rig), point_(point) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Isometry3d cam_from_obj = cam_from_rig_ * FromPoseParameters(parameters[0]);
    const Eigen::Vector3d p = cam_from_obj * point_;
    const double fx = 900.0, fy = 880.0;
    residuals[0] = fx * p.x() / p.z() + 320.0;
    residuals[1] = fy * p.y() / p.z() + 240.0;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Matrix<double, 2, 3> d_pixel;
      d_pixel << fx / p.z(), 0.0, -fx * p.x() / (p.z() * p.z()),  //
          0.0, fy / p.z(), -fy * p.y() / (p.z() * p.z());
      Eigen::Matrix<double, 3, 6> d_point;
      d_point << cam_from_obj.linear(), -cam_from_obj.linear() * Hat(point_);
      AmbientFromLieJacobian(d_pixel * d_point, parameters[0], jacobians[0]);
    }
    return true;
  }

 private:
  Eigen::Isometry3d cam_from_rig_;
  Eigen::Vector3d point_;
};

TEST(Se3ManifoldTest, GradientCheckerAcceptsLieJacobians) {
  std::mt19937 rng(31);
  Se3Manifold manifold;
  std::vector<const Manifold*> manifolds = {&manifold};
  NumericDiffOptions numeric_options;
  for (double angle : {0.0, 0.7, kPi - 1e-2}) {
    Eigen::Isometry3d rig_from_obj = ExpSE3(RandomTwist(rng, 1.0, 30.0));
    rig_from_obj.linear() = ExpSO3(angle * Eigen::Vector3d(0.3, -0.8, 0.5).normalized());
    rig_from_obj.translation() += Eigen::Vector3d(0.0, 0.0, 600.0);
    Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
    cam_from_rig.linear() = ExpSO3(Eigen::Vector3d(0.0, 0.1, 0.0));
    const PointProjectionCost cost(cam_from_rig, Eigen::Vector3d(40.0, -25.0, 18.0));
    GradientChecker checker(&cost, &manifolds, numeric_options);
    PoseParameters x = ToPoseParameters(rig_from_obj);
    const double* parameters[] = {x.data()};
    GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results)) << results.error_log;
  }
}

RotationalSymmetry TiltedAxis() {
  return {Eigen::Vector3d(0.2, 0.9, -0.4).normalized(), Eigen::Vector3d(15.0, -8.0, 22.0)};
}

TEST(AxisLockedSe3ManifoldTest, InvariantsHold) {
  std::mt19937 rng(37);
  const AxisLockedSe3Manifold manifold(TiltedAxis());
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto random_delta = [&](double scale) {
    Eigen::VectorXd delta(5);
    for (int k = 0; k < 5; ++k) delta[k] = scale * uniform(rng);
    return delta;
  };
  for (int trial = 0; trial < 20; ++trial) {
    const PoseParameters x = ToPoseParameters(ExpSE3(RandomTwist(rng, 2.0, 300.0)));
    PoseParameters y;
    manifold.Plus(x.data(), random_delta(0.8).data(), y.data());
    const Eigen::VectorXd xd = x, yd = y, dd = random_delta(0.4);
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, xd, dd, yd, 1e-9);
  }
}

TEST(AxisLockedSe3ManifoldTest, StepsNeverTurnAboutTheAxisAndReachEveryOtherDirection) {
  const RotationalSymmetry symmetry = TiltedAxis();
  const AxisLockedSe3Manifold manifold(symmetry);
  std::mt19937 rng(41);
  const PoseParameters x = ToPoseParameters(ExpSE3(RandomTwist(rng, 2.0, 300.0)));
  Eigen::Matrix<double, 7, 5, Eigen::RowMajor> plus_jacobian;
  manifold.PlusJacobian(x.data(), plus_jacobian.data());
  // In the full tangent no step has a rotation about the axis ...
  const Eigen::Matrix<double, 6, 5> steps = TangentFromAmbientJacobian(x.data()) * plus_jacobian;
  EXPECT_LT((symmetry.axis.transpose() * steps.bottomRows<3>()).norm(), 1e-12);
  // ... and the steps with the symmetry's twist span every direction.
  Matrix6d with_twist;
  with_twist << steps, symmetry.Twist();
  const Eigen::FullPivLU<Matrix6d> lu(with_twist);
  EXPECT_EQ(lu.rank(), 6);
  // Finite steps too: the pose's rotation never gains a turn about the axis.
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::Matrix<double, 5, 1> delta = Eigen::Matrix<double, 5, 1>::Random();
    delta.head<3>() *= 20.0;
    PoseParameters y;
    manifold.Plus(x.data(), delta.data(), y.data());
    const Eigen::Vector3d turn = LogSO3(FromPoseParameters(x.data()).linear().transpose() *
                                        FromPoseParameters(y.data()).linear());
    EXPECT_LT(std::abs(turn.dot(symmetry.axis)), 1e-12);
  }
}

TEST(AxisLockedSe3ManifoldTest, GradientCheckerAcceptsLieJacobians) {
  std::mt19937 rng(43);
  const AxisLockedSe3Manifold manifold(TiltedAxis());
  std::vector<const Manifold*> manifolds = {&manifold};
  NumericDiffOptions numeric_options;
  Eigen::Isometry3d rig_from_obj = ExpSE3(RandomTwist(rng, 1.0, 30.0));
  rig_from_obj.translation() += Eigen::Vector3d(0.0, 0.0, 600.0);
  const PointProjectionCost cost(Eigen::Isometry3d::Identity(), Eigen::Vector3d(40.0, -25.0, 18.0));
  GradientChecker checker(&cost, &manifolds, numeric_options);
  PoseParameters x = ToPoseParameters(rig_from_obj);
  const double* parameters[] = {x.data()};
  GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results)) << results.error_log;
}

TEST(NewPoseManifoldTest, LocksTheAxisOnlyForASymmetricObject) {
  EXPECT_EQ(NewPoseManifold(std::nullopt)->TangentSize(), 6);
  EXPECT_EQ(NewPoseManifold(TiltedAxis())->TangentSize(), 5);
}

}  // namespace
}  // namespace bcot
