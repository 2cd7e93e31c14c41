#include "bcot/core/rotation_grid.h"

#include <algorithm>
#include <cmath>

#include "bcot/core/se3.h"
#include "bcot/core/status.h"

namespace bcot {

std::vector<Eigen::Quaterniond> SuperFibonacciRotations(int count) {
  BCOT_CHECK(count >= 1);
  // ψ is the real root of ψ⁴ = ψ + 4; together with √2 it gives the two incommensurable
  // angular frequencies of the spiral.
  constexpr double kPhi = 1.41421356237309504880;
  constexpr double kPsi = 1.53375116875520428812;
  std::vector<Eigen::Quaterniond> rotations;
  rotations.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double s = i + 0.5;
    const double r = std::sqrt(s / count);
    const double big_r = std::sqrt(1.0 - s / count);
    const double alpha = 2.0 * kPi * s / kPhi;
    const double beta = 2.0 * kPi * s / kPsi;
    Eigen::Quaterniond q(big_r * std::cos(beta), r * std::sin(alpha), r * std::cos(alpha),
                         big_r * std::sin(beta));
    q.normalize();
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();
    rotations.push_back(q);
  }
  return rotations;
}

double QuaternionAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  // atan2 of the relative rotation's half-angle sine and cosine: exact near 0 and 180°, where
  // acos of the dot product loses half the digits.
  const Eigen::Quaterniond relative = a.conjugate() * b;
  return 2.0 * std::atan2(relative.vec().norm(), std::abs(relative.w())) * 180.0 / kPi;
}

}  // namespace bcot
