// Scene geometry of `bcot synth`: the camera layout of the paper's synthetic study (§5.1,
// supplement §B) and smooth random trajectories.
//
// World frame W: origin at the target point (centre of the object's workspace), z up, mm.
// Every camera looks at the target from `distance_mm`; the rig frame is C-0's camera frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/rig.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"
#include "bcot/synth/synth_options.h"

namespace bcot {

// Deterministic random numbers: a 64-bit generator with its own distributions (so results do
// not depend on the standard library's distribution implementations). Not thread-safe; pass
// one per consumer.
class SynthRng {
 public:
  explicit SynthRng(uint64_t seed);
  uint64_t Next();
  double Uniform();                      // [0, 1)
  double Uniform(double lo, double hi);  // [lo, hi)
  int UniformInt(int lo, int hi);        // [lo, hi]
  double Normal();                       // N(0, 1), Box-Muller
  Eigen::Vector3d UnitVector();          // uniform on the sphere
  Eigen::Matrix3d Rotation();            // uniform on SO(3)

 private:
  uint64_t state_[4];
};

// Stateless mixing (splitmix64) of a seed with a stream id: independent streams per purpose.
uint64_t MixSeed(uint64_t seed, uint64_t stream);
// Uniform [0, 1) and approximately N(0, 1) (Irwin-Hall of four uniforms) from a hashed key:
// per-pixel noise independent of thread order.
double HashUniform(uint64_t key);
double HashNormal(uint64_t key);

// One camera of the layout at frame 0.
struct SynthCamera {
  Camera camera;
  Eigen::Isometry3d cam_from_world = Eigen::Isometry3d::Identity();
  std::string kind;                 // "base" (C-0), "arc" or "cone"
  double included_angle_deg = 0.0;  // requested included angle to C-0 (0 for C-0)
};

// C-0, then one arc camera per options.arc_angles_deg, then one cone camera per
// options.cone_angles_deg. Arc camera at α: direction d(α) = cos α·d₀ + sin α·x₀ (d₀ = target →
// C-0, x₀ = C-0's x axis), in the plane through C-0 and the target. Cone camera at α:
// c = p·(d₀ + d(α)) + q·n with p = cos α / (1 + cos α), q = √(1 − 2cos²α / (1 + cos α)) and n the
// arc plane's upward normal, so ∠(c, d₀) = ∠(c, d(α)) = α. Cameras look at the target with
// world z up (no roll).
std::vector<SynthCamera> MakeSynthCameras(const SynthOptions::Cameras& options);

// cam_from_rig = cam_from_world · world_from_cam0 for every camera.
Rig MakeSynthRig(const std::vector<SynthCamera>& cameras);

// Angle between the optical axes of two cameras (deg).
double IncludedAngleDeg(const Eigen::Isometry3d& cam_a_from_world,
                        const Eigen::Isometry3d& cam_b_from_world);

// Radius of the smallest sphere about the bounding-box centre holding every vertex (mm).
double BoundingRadiusMm(const Mesh& mesh);

// Largest radius r of the ball about each camera's look-at point such that a sphere of
// `object_radius_mm` centred anywhere in it projects inside the image with `margin_px`, for
// every camera (distortion included). Error when even r = 0 does not fit.
StatusOr<double> AutoWorkspaceRadiusMm(const std::vector<SynthCamera>& cameras, double distance_mm,
                                       double object_radius_mm, double margin_px);

// Arc length s(t) of a smoothly modulated speed: ds/dt = v̄·c·(1 + a·Σ wₖ sin(ωₖt + φₖ)), with c
// chosen so that s(N−1) − s(0) = v̄·(N−1) exactly (mean speed v̄ over the frames).
class SpeedProfile {
 public:
  SpeedProfile() = default;
  SpeedProfile(double mean_speed, double variation, int num_frames, SynthRng* rng);
  double ArcLength(double t) const;

 private:
  double mean_speed_ = 0.0;
  double variation_ = 0.0;
  double scale_ = 1.0;
  std::vector<double> weights_, omegas_, phases_;
  double Raw(double t) const;
};

// An unbounded rotation path parameterised by its rotation arc length u (rad): the body-frame
// angular velocity direction turns smoothly (random sinusoids around a bias axis).
class RotationPath {
 public:
  RotationPath() = default;
  RotationPath(double max_length_rad, SynthRng* rng);
  Eigen::Matrix3d At(double u) const;  // u clamped to [0, max_length]

 private:
  Eigen::Vector3d Direction(double u) const;
  double step_ = 1.0;
  std::vector<Eigen::Matrix3d> table_;
  Eigen::Vector3d bias_ = Eigen::Vector3d::UnitZ();
  std::vector<Eigen::Vector3d> amplitudes_;
  std::vector<double> omegas_, phases_;
};

// A smooth random closed curve in R³ (sum of three harmonics) scaled so that its largest
// |point| equals `radius` (anisotropic weights per axis before scaling), parameterised by arc
// length and looped. With `rotation_metric` the arc length is the geodesic distance of
// ExpSO3(point) (the curve is an axis-angle path).
class ClosedCurve {
 public:
  ClosedCurve() = default;
  ClosedCurve(double radius, const Eigen::Vector3d& axis_weights, bool rotation_metric,
              SynthRng* rng);
  Eigen::Vector3d At(double s) const;  // s ≥ 0 is wrapped; starts at a random point
  double length() const { return length_; }

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<double> arc_;
  double length_ = 0.0;
  double start_ = 0.0;
};

// Object and rig motion over (fractional) frame times; frame f's ground truth is at t = f.
//   free:   the object's bbox centre follows a closed curve in the workspace ball, it rotates
//           about that centre; the rig is fixed at its layout pose.
//   rotate: as free without translation (centre at the target).
//   rig:    world_from_rig(t) = T(o(t))·Exp(φ(t))·world_from_rig(0): the rig pans about a
//           moving look-at point o(t) (ball of 0.7 r) by a bounded rotation; the object moves
//           in a ball of 0.3 r at object_motion_scale of the speeds.
class SynthMotion {
 public:
  static StatusOr<SynthMotion> Create(const SynthOptions& options,
                                      const std::vector<SynthCamera>& cameras,
                                      const Mesh& object_mesh);

  Eigen::Isometry3d WorldFromRig(double t) const;
  // Object template frame O_t (the mesh frame) in the world.
  Eigen::Isometry3d WorldFromObject(double t) const;
  // cam_from_world of camera `index` at time t (rig moves in rig mode).
  Eigen::Isometry3d CamFromWorld(int index, double t) const;
  Eigen::Isometry3d RigFromObject(double t) const;

  double workspace_radius_mm() const { return workspace_radius_mm_; }
  double object_radius_mm() const { return object_radius_mm_; }

 private:
  std::string mode_;
  std::vector<Eigen::Isometry3d> cam_from_rig_;
  Eigen::Isometry3d world_from_rig0_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d objcentre_from_template_ = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d object_rotation0_ = Eigen::Matrix3d::Identity();
  double workspace_radius_mm_ = 0.0;
  double object_radius_mm_ = 0.0;
  SpeedProfile object_rotation_speed_, object_translation_speed_;
  SpeedProfile rig_rotation_speed_, rig_translation_speed_;
  RotationPath object_rotation_;
  ClosedCurve object_translation_;
  ClosedCurve rig_rotation_, rig_translation_;
};

// OK when every vertex of `object_mesh` projects inside every camera's image, `margin_px`
// from the border, at every frame; else kInvalidConfig naming the camera and frame.
Status CheckObjectInViews(const SynthMotion& motion, const std::vector<SynthCamera>& cameras,
                          const Mesh& object_mesh, int num_frames, double margin_px);

// Built-in shapes (mm, centred at the origin, longest bbox side = size_mm).
Mesh MakeTrefoilKnotMesh(double size_mm);  // the default object: a closed knotted tube
Mesh MakeBoxMesh(const Eigen::Vector3d& size_mm);
Mesh MakeCylinderMesh(double radius_mm, double height_mm, int segments);
Mesh MakeEllipsoidMesh(const Eigen::Vector3d& radii_mm, int rings, int segments);

}  // namespace bcot
