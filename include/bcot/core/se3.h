// SO(3) and SE(3) helpers on Eigen types.
//
// Conventions (DESIGN.md, "Update in O_o"):
//   - a twist is δ = (ρ, φ) ∈ R⁶, translation part first, rotation part (axis·angle) last;
//   - Exp(δ) = [[Exp(φ), J_l(φ)·ρ], [0, 1]] with J_l the left Jacobian of SO(3);
//   - poses are Eigen::Isometry3d named `target_from_source`, translations in mm.
// Every function is exact at the identity, uses Taylor series for angles below 1e-3 rad and
// stays accurate near π (the logarithm goes through a quaternion, not acos of the trace).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace bcot {

// π, for the conversions between degrees and radians used throughout.
inline constexpr double kPi = 3.14159265358979323846;

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Skew-symmetric matrix v^ with v^·w = v × w.
Eigen::Matrix3d Hat(const Eigen::Vector3d& v);
// Inverse of Hat (reads the off-diagonal entries; assumes a skew-symmetric input).
Eigen::Vector3d Vee(const Eigen::Matrix3d& m);
// 4×4 matrix of a twist, [[φ^, ρ], [0, 0]].
Eigen::Matrix4d HatSE3(const Vector6d& twist);

// Rotation exponential (Rodrigues) and logarithm; Log returns φ with |φ| ≤ π.
Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi);
Eigen::Vector3d LogSO3(const Eigen::Matrix3d& rotation);
Eigen::Vector3d LogSO3(const Eigen::Quaterniond& rotation);

// Left Jacobian of SO(3), J_l(φ) = Σ (φ^)^k / (k+1)!, and its inverse.
Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& phi);
Eigen::Matrix3d InverseLeftJacobianSO3(const Eigen::Vector3d& phi);

Eigen::Isometry3d ExpSE3(const Vector6d& twist);
// Left Jacobian of SE(3) for twists (ρ, φ): Exp(ξ + ε) ≈ Exp(J_l(ξ)·ε)·Exp(ξ), i.e.
// J_l(ξ) = Σ (ad_ξ)^k / (k+1)! = [[J_l(φ), Q(ρ, φ)], [0, J_l(φ)]], and its inverse
// [[J⁻¹, −J⁻¹·Q·J⁻¹], [0, J⁻¹]] (J = J_l(φ) of SO(3)). The right Jacobian is J_r(ξ) = J_l(−ξ).
// Q is summed from the series of ad_ξ (entire in ξ, no cancellation: machine precision for
// |φ| ≤ π); the inverse needs |φ| < 2π.
Matrix6d LeftJacobianSE3(const Vector6d& twist);
Matrix6d InverseLeftJacobianSE3(const Vector6d& twist);
Vector6d LogSE3(const Eigen::Isometry3d& transform);

// Adjoint of T = (R, t) acting on (ρ, φ) twists: Ad_T = [[R, t^R], [0, R]], so that
// T·Exp(δ)·T⁻¹ = Exp(Ad_T·δ).
Matrix6d AdjointSE3(const Eigen::Isometry3d& transform);

// Geodesic interpolation a·Exp(s·Log(a⁻¹·b)) for s in [0, 1] (any real s extrapolates).
Eigen::Isometry3d InterpolateSE3(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s);
// Rotation-only geodesic interpolation (slerp).
Eigen::Matrix3d InterpolateSO3(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double s);

// Angle of the relative rotation between a and b in degrees, in [0, 180].
double RotationDistanceDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

// world_from_cam of a camera at `position` looking at the origin (x right, y down, z forward),
// with world z up in its image (no roll); y up when it looks along z.
Eigen::Isometry3d LookAtOrigin(const Eigen::Vector3d& position);

// True when R is orthonormal with det +1 within `tolerance` (max abs entry of RᵀR − I).
// On failure writes a short reason (e.g. "RᵀR deviates from I by 3.2e-02") to `why`.
bool IsRotationMatrix(const Eigen::Matrix3d& rotation, double tolerance, std::string* why);

// Re-orthonormalises a nearly orthonormal matrix (closest rotation via SVD).
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& matrix);

}  // namespace bcot
