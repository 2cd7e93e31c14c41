#include "bcot/core/se3.h"

#include <gtest/gtest.h>

#include <random>

#include "test_util.h"

namespace bcot {
namespace {

using test::kPi;

// Rodrigues on a 4×4 with a truncated power series, the reference the closed forms must match.
Eigen::Matrix4d SeriesExp(const Eigen::Matrix4d& a) {
  Eigen::Matrix4d result = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d term = Eigen::Matrix4d::Identity();
  for (int k = 1; k < 40; ++k) {
    term = term * a / k;
    result += term;
  }
  return result;
}

class Se3AngleTest : public ::testing::TestWithParam<double> {};

TEST_P(Se3AngleTest, ExpMatchesPowerSeriesAndLogInvertsIt) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    Vector6d twist;
    twist.head<3>() = 50.0 * test::RandomUnitVector(rng);
    twist.tail<3>() = GetParam() * test::RandomUnitVector(rng);
    const Eigen::Isometry3d transform = ExpSE3(twist);
    EXPECT_LT((transform.matrix() - SeriesExp(HatSE3(twist))).cwiseAbs().maxCoeff(), 1e-9);
    const Vector6d recovered = LogSE3(transform);
    EXPECT_LT((recovered - twist).norm(), 1e-9 * std::max(1.0, twist.norm()))
        << "angle " << GetParam();
  }
}

// Identity, 1e-9 rad, 1e-6 (the series switch), moderate angles and up to just below π.
INSTANTIATE_TEST_SUITE_P(Angles, Se3AngleTest,
                         ::testing::Values(0.0, 1e-9, 1e-7, 1e-6, 2e-6, 1e-3, 0.5, 2.0, 3.0,
                                           kPi - 1e-4, kPi - 1e-7));

TEST(So3Test, LogNearPiKeepsAxisAndAngle) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d axis = test::RandomUnitVector(rng);
    for (double epsilon : {0.0, 1e-12, 1e-8, 1e-5}) {
      const Eigen::Vector3d phi = (kPi - epsilon) * axis;
      const Eigen::Vector3d recovered = LogSO3(ExpSO3(phi));
      // At exactly π, axis and −axis describe the same rotation.
      const double error = std::min((recovered - phi).norm(), (recovered + phi).norm());
      EXPECT_LT(error, 1e-7) << "epsilon " << epsilon;
      EXPECT_NEAR(recovered.norm(), kPi - epsilon, 1e-7);
    }
  }
}

TEST(So3Test, ExpIsARotation) {
  std::mt19937 rng(5);
  for (double angle : {0.0, 1e-9, 0.3, 3.1}) {
    const Eigen::Matrix3d r = ExpSO3(angle * test::RandomUnitVector(rng));
    std::string why;
    EXPECT_TRUE(IsRotationMatrix(r, 1e-12, &why)) << why;
  }
}

TEST(So3Test, HatVeeAndCrossProduct) {
  const Eigen::Vector3d v(1.0, -2.0, 3.5);
  const Eigen::Vector3d w(-0.5, 4.0, 2.0);
  EXPECT_LT((Hat(v) * w - v.cross(w)).norm(), 1e-15);
  EXPECT_EQ(Vee(Hat(v)), v);
}

// d/dε Log(Exp(φ + ε)·Exp(φ)ᵀ) = J_l(φ): the defining property of the left Jacobian,
// checked by central differences.
TEST(So3Test, LeftJacobianMatchesNumericDerivative) {
  std::mt19937 rng(11);
  for (double angle : {0.0, 1e-9, 1e-3, 1.0, 2.5, 3.0}) {
    const Eigen::Vector3d phi = angle * test::RandomUnitVector(rng);
    const Eigen::Matrix3d r_transpose = ExpSO3(phi).transpose();
    Eigen::Matrix3d numeric;
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * h;
      numeric.col(k) = (LogSO3(Eigen::Matrix3d(ExpSO3(phi + e) * r_transpose)) -
                        LogSO3(Eigen::Matrix3d(ExpSO3(phi - e) * r_transpose))) /
                       (2.0 * h);
    }
    EXPECT_LT((LeftJacobianSO3(phi) - numeric).cwiseAbs().maxCoeff(), 1e-7) << angle;
    EXPECT_LT((InverseLeftJacobianSO3(phi) * LeftJacobianSO3(phi) - Eigen::Matrix3d::Identity())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12)
        << angle;
  }
}

TEST(Se3Test, AdjointConjugatesTwists) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 10; ++trial) {
    Vector6d a, b;
    a << 30.0 * test::RandomUnitVector(rng), 1.3 * test::RandomUnitVector(rng);
    b << 0.2 * test::RandomUnitVector(rng), 0.05 * test::RandomUnitVector(rng);
    const Eigen::Isometry3d t = ExpSE3(a);
    const Eigen::Isometry3d lhs = t * ExpSE3(b) * t.inverse();
    const Eigen::Isometry3d rhs = ExpSE3(AdjointSE3(t) * b);
    EXPECT_LT((lhs.matrix() - rhs.matrix()).cwiseAbs().maxCoeff(), 1e-10);
  }
}

// J_l of SE(3) is the derivative of Exp: Log(Exp(ξ + ε)·Exp(ξ)⁻¹) ≈ J_l(ξ)·ε, checked by
// central differences at small, medium and near-π angles; the inverse inverts it.
TEST(Se3Test, LeftJacobianMatchesNumericDerivativeAndInverts) {
  std::mt19937 rng(19);
  for (double angle : {0.0, 1e-4, 0.3, 1.5, 3.0}) {
    Vector6d xi;
    xi << 40.0 * test::RandomUnitVector(rng), angle * test::RandomUnitVector(rng);
    const Matrix6d analytic = LeftJacobianSE3(xi);
    Matrix6d numeric;
    const double h = 1e-6;
    const Eigen::Isometry3d exp_inverse = ExpSE3(xi).inverse();
    for (int k = 0; k < 6; ++k) {
      const Vector6d e = Vector6d::Unit(k) * h;
      numeric.col(k) =
          (LogSE3(ExpSE3(xi + e) * exp_inverse) - LogSE3(ExpSE3(xi - e) * exp_inverse)) / (2.0 * h);
    }
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6) << angle;
    EXPECT_LT((InverseLeftJacobianSE3(xi) * analytic - Matrix6d::Identity()).cwiseAbs().maxCoeff(),
              1e-12)
        << angle;
  }
}

// The right-perturbation derivative the region cost functions rely on (DESIGN.md S.19):
// ∂(T·Exp(δ)·X)/∂δ at δ = 0 is R·[I | −X^].
TEST(Se3Test, PointDerivativeMatchesNumeric) {
  std::mt19937 rng(17);
  Vector6d a;
  a << 100.0 * test::RandomUnitVector(rng), 2.0 * test::RandomUnitVector(rng);
  const Eigen::Isometry3d t = ExpSE3(a);
  const Eigen::Vector3d x(12.0, -40.0, 7.5);
  Eigen::Matrix<double, 3, 6> analytic;
  analytic << t.linear(), -t.linear() * Hat(x);
  Eigen::Matrix<double, 3, 6> numeric;
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    const Vector6d e = Vector6d::Unit(k) * h;
    numeric.col(k) = ((t * ExpSE3(e)) * x - (t * ExpSE3(-e)) * x) / (2.0 * h);
  }
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Se3Test, InterpolationEndpointsAndMidpoint) {
  std::mt19937 rng(19);
  Vector6d a, b;
  a << 20.0 * test::RandomUnitVector(rng), 0.7 * test::RandomUnitVector(rng);
  b << 60.0 * test::RandomUnitVector(rng), 2.9 * test::RandomUnitVector(rng);
  const Eigen::Isometry3d ta = ExpSE3(a);
  const Eigen::Isometry3d tb = ExpSE3(b);
  EXPECT_LT((InterpolateSE3(ta, tb, 0.0).matrix() - ta.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((InterpolateSE3(ta, tb, 1.0).matrix() - tb.matrix()).cwiseAbs().maxCoeff(), 1e-9);
  // The midpoint is equidistant in rotation from both ends.
  const Eigen::Isometry3d mid = InterpolateSE3(ta, tb, 0.5);
  EXPECT_NEAR(RotationDistanceDeg(ta.linear(), mid.linear()),
              RotationDistanceDeg(mid.linear(), tb.linear()), 1e-9);
  const Eigen::Matrix3d r_mid = InterpolateSO3(ta.linear(), tb.linear(), 0.5);
  EXPECT_LT((r_mid - mid.linear()).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(So3Test, RotationValidation) {
  std::string why;
  Eigen::Matrix3d scaled = 1.01 * Eigen::Matrix3d::Identity();
  EXPECT_FALSE(IsRotationMatrix(scaled, 1e-4, &why));
  EXPECT_NE(why.find("orthonormal"), std::string::npos) << why;
  Eigen::Matrix3d reflection = Eigen::Matrix3d::Identity();
  reflection(2, 2) = -1.0;
  EXPECT_FALSE(IsRotationMatrix(reflection, 1e-4, &why));
  EXPECT_NE(why.find("determinant"), std::string::npos) << why;
  Eigen::Matrix3d nan_matrix = Eigen::Matrix3d::Identity();
  nan_matrix(0, 1) = std::nan("");
  EXPECT_FALSE(IsRotationMatrix(nan_matrix, 1e-4, &why));
  const Eigen::Matrix3d noisy =
      ExpSO3(Eigen::Vector3d(0.3, -0.2, 1.0)) + 1e-5 * Eigen::Matrix3d::Ones();
  EXPECT_TRUE(IsRotationMatrix(NearestRotation(noisy), 1e-12, &why)) << why;
}

}  // namespace
}  // namespace bcot
