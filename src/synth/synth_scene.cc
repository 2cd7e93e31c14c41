#include "bcot/synth/synth_scene.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "bcot/core/se3.h"

namespace bcot {
namespace {

constexpr double kDegToRad = kPi / 180.0;

uint64_t SplitMix64(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Random numbers (xoshiro256** seeded by splitmix64).

SynthRng::SynthRng(uint64_t seed) {
  uint64_t s = seed;
  for (uint64_t& word : state_) word = SplitMix64(&s);
}

uint64_t SynthRng::Next() {
  const uint64_t result = Rotl(state_[1] * 5, 7) * 9;
  const uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = Rotl(state_[3], 45);
  return result;
}

double SynthRng::Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
double SynthRng::Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
int SynthRng::UniformInt(int lo, int hi) {
  const uint64_t span = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo + 1);
  return lo + static_cast<int>(Next() % span);
}
double SynthRng::Normal() {
  const double u1 = 1.0 - Uniform();  // (0, 1]
  const double u2 = Uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}
Eigen::Vector3d SynthRng::UnitVector() {
  const double z = Uniform(-1.0, 1.0);
  const double phi = Uniform(0.0, 2.0 * kPi);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}
Eigen::Matrix3d SynthRng::Rotation() {
  // Uniform quaternion (Shoemake).
  const double u1 = Uniform(), u2 = Uniform(), u3 = Uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const Eigen::Quaterniond q(b * std::cos(2 * kPi * u3), a * std::sin(2 * kPi * u2),
                             a * std::cos(2 * kPi * u2), b * std::sin(2 * kPi * u3));
  return q.normalized().toRotationMatrix();
}

uint64_t MixSeed(uint64_t seed, uint64_t stream) {
  uint64_t s = seed * 0x9E3779B97F4A7C15ull + stream;
  SplitMix64(&s);
  return SplitMix64(&s);
}

double HashUniform(uint64_t key) {
  uint64_t s = key;
  return static_cast<double>(SplitMix64(&s) >> 11) * 0x1.0p-53;
}

double HashNormal(uint64_t key) {
  // Irwin-Hall: the sum of four 16-bit uniforms, standardised (tails bounded at ±3.46σ; no
  // transcendental functions, which matters at millions of noise samples per image).
  uint64_t s = key;
  const uint64_t bits = SplitMix64(&s);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += static_cast<double>((bits >> (16 * i)) & 0xFFFF) + 0.5;
  constexpr double kMean = 4.0 * 32768.0;
  constexpr double kInvSigma = 1.0 / (65536.0 * 0.57735026918962576);  // 1 / (65536·√(4/12))
  return (sum - kMean) * kInvSigma;
}

// ---------------------------------------------------------------------------------------------
// Camera layout.

std::vector<SynthCamera> MakeSynthCameras(const SynthOptions::Cameras& options) {
  const double e = options.elevation_deg * kDegToRad;
  const Eigen::Vector3d d0(0.0, -std::cos(e), std::sin(e));  // target → C-0
  const Eigen::Isometry3d world_from_cam0 = LookAtOrigin(options.distance_mm * d0);
  const Eigen::Vector3d x0 = world_from_cam0.linear().col(0);
  const Eigen::Vector3d up_normal = -world_from_cam0.linear().col(1);  // arc plane normal, up

  const double fx = 0.5 * options.width / std::tan(0.5 * options.hfov_deg * kDegToRad);
  auto make = [&](const Eigen::Vector3d& direction, const std::string& kind, double angle_deg,
                  int index) {
    SynthCamera camera;
    camera.camera =
        Camera(options.name_prefix + std::to_string(index), options.width, options.height, fx, fx,
               0.5 * (options.width - 1), 0.5 * (options.height - 1));
    camera.camera.distortion = options.distortion;
    camera.cam_from_world = LookAtOrigin(options.distance_mm * direction).inverse();
    camera.kind = kind;
    camera.included_angle_deg = angle_deg;
    return camera;
  };

  std::vector<SynthCamera> cameras;
  cameras.push_back(make(d0, "base", 0.0, 0));
  for (double angle_deg : options.arc_angles_deg) {
    const double a = angle_deg * kDegToRad;
    cameras.push_back(make(std::cos(a) * d0 + std::sin(a) * x0, "arc", angle_deg,
                           static_cast<int>(cameras.size())));
  }
  for (double angle_deg : options.cone_angles_deg) {
    const double a = angle_deg * kDegToRad;
    const double cos_a = std::cos(a);
    const Eigen::Vector3d d_arc = cos_a * d0 + std::sin(a) * x0;
    const double p = cos_a / (1.0 + cos_a);
    const double q = std::sqrt(std::max(0.0, 1.0 - 2.0 * cos_a * cos_a / (1.0 + cos_a)));
    const Eigen::Vector3d c = (p * (d0 + d_arc) + q * up_normal).normalized();
    cameras.push_back(make(c, "cone", angle_deg, static_cast<int>(cameras.size())));
  }
  return cameras;
}

Rig MakeSynthRig(const std::vector<SynthCamera>& cameras) {
  Rig rig;
  const Eigen::Isometry3d world_from_rig = cameras.at(0).cam_from_world.inverse();
  for (const SynthCamera& camera : cameras) {
    RigCamera rig_camera;
    rig_camera.camera = camera.camera;
    rig_camera.cam_from_rig = camera.cam_from_world * world_from_rig;
    rig.Add(rig_camera);
  }
  return rig;
}

double IncludedAngleDeg(const Eigen::Isometry3d& cam_a_from_world,
                        const Eigen::Isometry3d& cam_b_from_world) {
  const Eigen::Vector3d axis_a = cam_a_from_world.linear().row(2).transpose();
  const Eigen::Vector3d axis_b = cam_b_from_world.linear().row(2).transpose();
  return std::atan2(axis_a.cross(axis_b).norm(), axis_a.dot(axis_b)) / kDegToRad;
}

double BoundingRadiusMm(const Mesh& mesh) {
  const Eigen::Vector3d centre = mesh.bbox_center();
  double radius = 0.0;
  for (const Eigen::Vector3f& v : mesh.vertices()) {
    radius = std::max(radius, (v.cast<double>() - centre).norm());
  }
  return radius;
}

StatusOr<double> AutoWorkspaceRadiusMm(const std::vector<SynthCamera>& cameras, double distance_mm,
                                       double object_radius_mm, double margin_px) {
  // Half-angle of the cone inscribed in the image (minus margin) about each optical axis.
  double half_angle = kPi;
  for (const SynthCamera& synth_camera : cameras) {
    const Camera& camera = synth_camera.camera;
    const double x0 = margin_px, x1 = camera.width - 1 - margin_px;
    const double y0 = margin_px, y1 = camera.height - 1 - margin_px;
    if (x1 <= x0 || y1 <= y0) return Status::InvalidConfig("motion.frustum_margin_px too large");
    constexpr int kSteps = 64;
    for (int i = 0; i <= kSteps; ++i) {
      const double s = static_cast<double>(i) / kSteps;
      for (const Eigen::Vector2d& pixel :
           {Eigen::Vector2d(x0 + s * (x1 - x0), y0), Eigen::Vector2d(x0 + s * (x1 - x0), y1),
            Eigen::Vector2d(x0, y0 + s * (y1 - y0)), Eigen::Vector2d(x1, y0 + s * (y1 - y0))}) {
        const Eigen::Vector3d ray = camera.PixelToRay(pixel).normalized();
        half_angle = std::min(half_angle, std::acos(std::clamp(ray.z(), -1.0, 1.0)));
      }
    }
  }
  // A sphere of radius R centred at distance ≤ r from the look-at point stays inside the cone
  // when asin(r / D) + asin(R / (D − r)) ≤ half_angle.
  auto fits = [&](double r) {
    if (r + object_radius_mm >= distance_mm) return false;
    return std::asin(r / distance_mm) + std::asin(object_radius_mm / (distance_mm - r)) <=
           half_angle;
  };
  if (!fits(0.0)) {
    return Status::InvalidConfig(fmt::format(
        "the object (bounding radius {:.1f} mm) does not fit in the views at "
        "cameras.distance_mm = {}: increase the distance or hfov_deg, or reduce object.size_mm",
        object_radius_mm, distance_mm));
  }
  double lo = 0.0, hi = distance_mm - object_radius_mm;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

// ---------------------------------------------------------------------------------------------
// Trajectories.

SpeedProfile::SpeedProfile(double mean_speed, double variation, int num_frames, SynthRng* rng)
    : mean_speed_(mean_speed), variation_(variation) {
  constexpr int kTerms = 3;
  double weight_sum = 0.0;
  for (int k = 0; k < kTerms; ++k) {
    weights_.push_back(rng->Uniform(0.5, 1.0));
    weight_sum += weights_.back();
    omegas_.push_back(2.0 * kPi / rng->Uniform(12.0, 60.0));  // periods of 12–60 frames
    phases_.push_back(rng->Uniform(0.0, 2.0 * kPi));
  }
  for (double& weight : weights_) weight /= weight_sum;
  if (num_frames > 1) {
    const double raw = Raw(num_frames - 1) - Raw(0.0);
    scale_ = (num_frames - 1) / raw;
  }
}

double SpeedProfile::Raw(double t) const {
  double s = t;
  for (size_t k = 0; k < weights_.size(); ++k) {
    s += variation_ * weights_[k] * (std::cos(phases_[k]) - std::cos(omegas_[k] * t + phases_[k])) /
         omegas_[k];
  }
  return s;
}

double SpeedProfile::ArcLength(double t) const {
  return mean_speed_ * scale_ * (Raw(t) - Raw(0.0));
}

RotationPath::RotationPath(double max_length_rad, SynthRng* rng) {
  bias_ = 0.8 * rng->UnitVector();
  for (int k = 0; k < 3; ++k) {
    amplitudes_.push_back(rng->Uniform(0.3, 0.7) * rng->UnitVector());
    omegas_.push_back(rng->Uniform(0.4, 1.5));  // direction turns over ~1 rad of rotation
    phases_.push_back(rng->Uniform(0.0, 2.0 * kPi));
  }
  max_length_rad = std::max(max_length_rad, 1e-3);
  step_ = std::max(2e-3, max_length_rad / 200000.0);
  const int steps = static_cast<int>(std::ceil(max_length_rad / step_)) + 1;
  table_.reserve(steps + 1);
  table_.push_back(Eigen::Matrix3d::Identity());
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) * step_;  // midpoint rule
    table_.push_back(NearestRotation(table_.back() * ExpSO3(Direction(u) * step_)));
  }
}

Eigen::Vector3d RotationPath::Direction(double u) const {
  Eigen::Vector3d w = bias_;
  for (size_t k = 0; k < amplitudes_.size(); ++k) {
    w += amplitudes_[k] * std::sin(omegas_[k] * u + phases_[k]);
  }
  const double norm = w.norm();
  return norm > 1e-9 ? Eigen::Vector3d(w / norm) : Eigen::Vector3d::UnitZ();
}

Eigen::Matrix3d RotationPath::At(double u) const {
  if (table_.empty()) return Eigen::Matrix3d::Identity();
  u = std::clamp(u, 0.0, step_ * (table_.size() - 1));
  const int index = std::min(static_cast<int>(u / step_), static_cast<int>(table_.size()) - 2);
  if (index < 0) return table_.front();
  const double rest = u - index * step_;
  return table_[index] * ExpSO3(Direction((index + 0.5) * step_) * rest);
}

ClosedCurve::ClosedCurve(double radius, const Eigen::Vector3d& axis_weights, bool rotation_metric,
                         SynthRng* rng) {
  constexpr int kHarmonics = 3;
  constexpr int kSamples = 4096;
  constexpr int kCandidates = 16;
  // Draw a few candidate curves (a fixed number, so the stream stays aligned) and keep the
  // one whose tightest bend is the widest relative to its size: a sum of harmonics can have
  // near-cusps, which would be jerks in the motion.
  double best_score = -1.0;
  std::vector<Eigen::Vector3d> candidate(kSamples + 1);
  for (int attempt = 0; attempt < kCandidates; ++attempt) {
    Eigen::Vector3d a[kHarmonics], b[kHarmonics];
    for (int k = 0; k < kHarmonics; ++k) {
      for (int axis = 0; axis < 3; ++axis) {
        a[k][axis] = rng->Normal() / ((k + 1) * (k + 1));
        b[k][axis] = rng->Normal() / ((k + 1) * (k + 1));
      }
    }
    double max_norm = 0.0;
    for (int i = 0; i <= kSamples; ++i) {
      const double theta = 2.0 * kPi * i / kSamples;
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int k = 0; k < kHarmonics; ++k) {
        p += a[k] * std::cos((k + 1) * theta) + b[k] * std::sin((k + 1) * theta);
      }
      candidate[i] = p.cwiseProduct(axis_weights);
      max_norm = std::max(max_norm, candidate[i].norm());
    }
    // Smallest radius of curvature (from consecutive sample triples) over the largest |p|.
    double min_bend = std::numeric_limits<double>::infinity();
    for (int i = 1; i < kSamples; ++i) {
      const Eigen::Vector3d u = candidate[i] - candidate[i - 1];
      const Eigen::Vector3d v = candidate[i + 1] - candidate[i];
      const double turn = u.cross(v).norm();  // |u||v| sin(angle)
      const double chord = (candidate[i + 1] - candidate[i - 1]).norm();
      if (turn > 0.0) min_bend = std::min(min_bend, u.norm() * v.norm() * chord / (2.0 * turn));
    }
    const double score = max_norm > 0.0 ? min_bend / max_norm : 0.0;
    if (score > best_score) {
      best_score = score;
      points_ = candidate;
    }
  }
  start_ = rng->Uniform();
  double max_norm = 0.0;
  for (const Eigen::Vector3d& p : points_) max_norm = std::max(max_norm, p.norm());
  const double scale = max_norm > 0.0 ? radius / max_norm : 0.0;
  arc_.assign(kSamples + 1, 0.0);
  for (int i = 0; i <= kSamples; ++i) {
    points_[i] *= scale;
    if (i > 0) {
      const double step =
          rotation_metric
              ? RotationDistanceDeg(ExpSO3(points_[i - 1]), ExpSO3(points_[i])) * kDegToRad
              : (points_[i] - points_[i - 1]).norm();
      arc_[i] = arc_[i - 1] + step;
    }
  }
  length_ = arc_.back();
  start_ *= length_;
}

Eigen::Vector3d ClosedCurve::At(double s) const {
  if (points_.empty()) return Eigen::Vector3d::Zero();
  if (length_ <= 0.0) return points_.front();
  double wrapped = std::fmod(start_ + s, length_);
  if (wrapped < 0.0) wrapped += length_;
  const auto upper = std::upper_bound(arc_.begin(), arc_.end(), wrapped);
  const int i1 =
      std::clamp(static_cast<int>(upper - arc_.begin()), 1, static_cast<int>(arc_.size()) - 1);
  const int i0 = i1 - 1;
  const double span = arc_[i1] - arc_[i0];
  const double w = span > 0.0 ? (wrapped - arc_[i0]) / span : 0.0;
  return (1.0 - w) * points_[i0] + w * points_[i1];
}

StatusOr<SynthMotion> SynthMotion::Create(const SynthOptions& options,
                                          const std::vector<SynthCamera>& cameras,
                                          const Mesh& object_mesh) {
  const SynthOptions::Motion& m = options.motion;
  SynthMotion motion;
  motion.mode_ = m.mode;
  motion.world_from_rig0_ = cameras.at(0).cam_from_world.inverse();
  for (const SynthCamera& camera : cameras) {
    motion.cam_from_rig_.push_back(camera.cam_from_world * motion.world_from_rig0_);
  }
  motion.objcentre_from_template_ = object_mesh.objcentre_from_template();
  motion.object_radius_mm_ = BoundingRadiusMm(object_mesh);
  if (m.workspace_radius_mm > 0.0) {
    motion.workspace_radius_mm_ = m.workspace_radius_mm;
  } else {
    BCOT_ASSIGN_OR_RETURN(motion.workspace_radius_mm_,
                          AutoWorkspaceRadiusMm(cameras, options.cameras.distance_mm,
                                                motion.object_radius_mm_, m.frustum_margin_px));
  }

  SynthRng rng(MixSeed(options.seed, 101));
  motion.object_rotation0_ = rng.Rotation();
  const double deg = kDegToRad;
  const int n = m.num_frames;
  const double r = motion.workspace_radius_mm_;
  const Eigen::Vector3d isotropic(1.0, 1.0, 1.0);
  // Every path is built (in a fixed order) whatever the mode, so streams stay aligned.
  const bool rig = m.mode == "rig";
  const double object_scale = rig ? m.object_motion_scale : 1.0;
  const double object_rotation_speed = m.rotation_deg_per_frame * deg * object_scale;
  const double object_translation_speed =
      m.mode == "rotate" ? 0.0 : m.translation_mm_per_frame * object_scale;
  motion.object_rotation_speed_ = SpeedProfile(object_rotation_speed, m.speed_variation, n, &rng);
  motion.object_translation_speed_ =
      SpeedProfile(object_translation_speed, m.speed_variation, n, &rng);
  motion.rig_rotation_speed_ =
      SpeedProfile(rig ? m.rotation_deg_per_frame * deg : 0.0, m.speed_variation, n, &rng);
  motion.rig_translation_speed_ =
      SpeedProfile(rig ? m.translation_mm_per_frame : 0.0, m.speed_variation, n, &rng);
  // Room for motion-blur sub-frames half a frame beyond either end.
  const double max_rotation = motion.object_rotation_speed_.ArcLength(n + 1.0) + 1.0;
  motion.object_rotation_ = RotationPath(max_rotation, &rng);
  motion.object_translation_ = ClosedCurve(rig ? 0.3 * r : r, isotropic, false, &rng);
  motion.rig_rotation_ =
      ClosedCurve(m.rig_max_rotation_deg * deg, Eigen::Vector3d(0.33, 0.33, 1), true, &rng);
  motion.rig_translation_ = ClosedCurve(0.7 * r, isotropic, false, &rng);
  return motion;
}

Eigen::Isometry3d SynthMotion::WorldFromRig(double t) const {
  if (mode_ != "rig") return world_from_rig0_;
  Eigen::Isometry3d pan = Eigen::Isometry3d::Identity();
  pan.linear() = ExpSO3(rig_rotation_.At(rig_rotation_speed_.ArcLength(t)));
  pan.translation() = rig_translation_.At(rig_translation_speed_.ArcLength(t));
  return pan * world_from_rig0_;
}

Eigen::Isometry3d SynthMotion::WorldFromObject(double t) const {
  Eigen::Isometry3d world_from_objcentre = Eigen::Isometry3d::Identity();
  world_from_objcentre.linear() =
      object_rotation0_ * object_rotation_.At(object_rotation_speed_.ArcLength(t));
  if (mode_ != "rotate") {
    world_from_objcentre.translation() =
        object_translation_.At(object_translation_speed_.ArcLength(t));
  }
  return world_from_objcentre * objcentre_from_template_;
}

Eigen::Isometry3d SynthMotion::CamFromWorld(int index, double t) const {
  return cam_from_rig_.at(index) * WorldFromRig(t).inverse();
}

Eigen::Isometry3d SynthMotion::RigFromObject(double t) const {
  return WorldFromRig(t).inverse() * WorldFromObject(t);
}

Status CheckObjectInViews(const SynthMotion& motion, const std::vector<SynthCamera>& cameras,
                          const Mesh& object_mesh, int num_frames, double margin_px) {
  const auto& vertices = object_mesh.vertices();
  const size_t stride = std::max<size_t>(1, vertices.size() / 4000);
  for (int frame = 0; frame < num_frames; ++frame) {
    for (size_t c = 0; c < cameras.size(); ++c) {
      const Camera& camera = cameras[c].camera;
      const Eigen::Isometry3d cam_from_object =
          motion.CamFromWorld(static_cast<int>(c), frame) * motion.WorldFromObject(frame);
      for (size_t i = 0; i < vertices.size(); i += stride) {
        const Eigen::Vector3d p = cam_from_object * vertices[i].cast<double>();
        const Eigen::Vector2d pixel = p.z() > 1e-6 ? camera.Project(p) : Eigen::Vector2d(-1e9, 0);
        if (pixel.x() < margin_px - 0.5 || pixel.y() < margin_px - 0.5 ||
            pixel.x() > camera.width - 0.5 - margin_px ||
            pixel.y() > camera.height - 0.5 - margin_px) {
          return Status::InvalidConfig(fmt::format(
              "the object leaves view {} at frame {} (vertex at pixel ({:.1f}, {:.1f})): reduce "
              "motion.workspace_radius_mm or increase cameras.distance_mm",
              camera.name, frame, pixel.x(), pixel.y()));
        }
      }
    }
  }
  return Status::Ok();
}

// ---------------------------------------------------------------------------------------------
// Built-in shapes.

Mesh MakeTrefoilKnotMesh(double size_mm) {
  constexpr int kSegments = 240;  // along the knot
  constexpr int kSides = 18;      // around the tube
  const double tube = 0.42;       // tube radius in curve units
  auto curve = [](double t) {
    return Eigen::Vector3d(std::sin(t) + 2.0 * std::sin(2.0 * t),
                           std::cos(t) - 2.0 * std::cos(2.0 * t), -0.8 * std::sin(3.0 * t));
  };
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  for (int i = 0; i < kSegments; ++i) {
    const double t = 2.0 * kPi * i / kSegments;
    const double h = 1e-4;
    const Eigen::Vector3d p = curve(t);
    const Eigen::Vector3d tangent = (curve(t + h) - curve(t - h)).normalized();
    const Eigen::Vector3d accel = curve(t + h) - 2.0 * p + curve(t - h);
    Eigen::Vector3d normal = (accel - accel.dot(tangent) * tangent).normalized();
    const Eigen::Vector3d binormal = tangent.cross(normal);
    for (int j = 0; j < kSides; ++j) {
      const double a = 2.0 * kPi * j / kSides;
      vertices.push_back(
          (p + tube * (std::cos(a) * normal + std::sin(a) * binormal)).cast<float>());
    }
  }
  for (int i = 0; i < kSegments; ++i) {
    const int i1 = (i + 1) % kSegments;
    for (int j = 0; j < kSides; ++j) {
      const int j1 = (j + 1) % kSides;
      const int a = i * kSides + j, b = i1 * kSides + j, c = i1 * kSides + j1, d = i * kSides + j1;
      triangles.emplace_back(a, b, c);
      triangles.emplace_back(a, c, d);
    }
  }
  Mesh unit = Mesh::FromArrays(std::move(vertices), std::move(triangles));
  Eigen::Isometry3d centre = Eigen::Isometry3d::Identity();
  centre.translation() = -unit.bbox_center();
  const Mesh centred = unit.Transformed(centre);
  return centred.Transformed(Eigen::Isometry3d::Identity(), size_mm / centred.diameter());
}

Mesh MakeBoxMesh(const Eigen::Vector3d& size_mm) {
  std::vector<Eigen::Vector3f> vertices;
  for (int i = 0; i < 8; ++i) {
    vertices.emplace_back(static_cast<float>(((i & 1) ? 0.5 : -0.5) * size_mm.x()),
                          static_cast<float>(((i & 2) ? 0.5 : -0.5) * size_mm.y()),
                          static_cast<float>(((i & 4) ? 0.5 : -0.5) * size_mm.z()));
  }
  const std::vector<Eigen::Vector3i> triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                                  {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                                  {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return Mesh::FromArrays(std::move(vertices), triangles);
}

Mesh MakeCylinderMesh(double radius_mm, double height_mm, int segments) {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * kPi * i / segments;
    const float x = static_cast<float>(radius_mm * std::cos(a));
    const float y = static_cast<float>(radius_mm * std::sin(a));
    vertices.emplace_back(x, y, static_cast<float>(-0.5 * height_mm));
    vertices.emplace_back(x, y, static_cast<float>(0.5 * height_mm));
  }
  const int bottom = static_cast<int>(vertices.size());
  vertices.emplace_back(0.0f, 0.0f, static_cast<float>(-0.5 * height_mm));
  vertices.emplace_back(0.0f, 0.0f, static_cast<float>(0.5 * height_mm));
  for (int i = 0; i < segments; ++i) {
    const int i1 = (i + 1) % segments;
    triangles.emplace_back(2 * i, 2 * i1, 2 * i1 + 1);
    triangles.emplace_back(2 * i, 2 * i1 + 1, 2 * i + 1);
    triangles.emplace_back(bottom, 2 * i1, 2 * i);
    triangles.emplace_back(bottom + 1, 2 * i + 1, 2 * i1 + 1);
  }
  return Mesh::FromArrays(std::move(vertices), std::move(triangles));
}

Mesh MakeEllipsoidMesh(const Eigen::Vector3d& radii_mm, int rings, int segments) {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  vertices.emplace_back(0.0f, 0.0f, static_cast<float>(-radii_mm.z()));
  for (int r = 1; r < rings; ++r) {
    const double polar = kPi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * kPi * s / segments;
      vertices.emplace_back(static_cast<float>(radii_mm.x() * std::sin(polar) * std::cos(a)),
                            static_cast<float>(radii_mm.y() * std::sin(polar) * std::sin(a)),
                            static_cast<float>(-radii_mm.z() * std::cos(polar)));
    }
  }
  const int top = static_cast<int>(vertices.size());
  vertices.emplace_back(0.0f, 0.0f, static_cast<float>(radii_mm.z()));
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    triangles.emplace_back(0, ring(1, s + 1), ring(1, s));
    triangles.emplace_back(top, ring(rings - 1, s), ring(rings - 1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      triangles.emplace_back(ring(r, s), ring(r, s + 1), ring(r + 1, s + 1));
      triangles.emplace_back(ring(r, s), ring(r + 1, s + 1), ring(r + 1, s));
    }
  }
  return Mesh::FromArrays(std::move(vertices), std::move(triangles));
}

}  // namespace bcot
