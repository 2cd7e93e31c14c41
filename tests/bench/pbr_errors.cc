// Per-camera pose errors of an annotation against a sequence's ground truth, for
// scripts/bench_pbr.sh (issue 12).
//
// For each camera of the rig, poses cam_from_object = cam_from_rig · rig_from_object (the
// annotation's rig_from_object.txt and the sequence's gt/rig_from_object.txt) are compared at
// the object's bounding-box centre c (mesh as the annotator loads it): e = T·c − G·c in that
// camera's axes (mm), rotation error = angle(R·R_gtᵀ) (deg). One tab-separated line per camera:
//   camera frames rot_mean rot_max abs_x abs_y abs_z bias_x bias_y bias_z std_x std_y std_z
//   worst_t lost
// (bias = mean signed error, std = its standard deviation, worst_t = max ‖e‖, lost = frames
// with > 5° or > 50 mm). --blocks N adds lines `camera#b` for consecutive blocks of N frames.
// --rotation adds per camera the rotation error as a vector, φ = log(R·R_gtᵀ) in that camera's
// axes (deg), whether it is a bias or jitter:
//   camera:rotation bias_x bias_y bias_z std_x std_y std_z mean_step
// (bias = mean φ, std its standard deviation per axis, mean_step = mean ‖φ_t − φ_{t−1}‖: about
// √2 times the spread of φ when the errors of consecutive frames are independent, near 0 for
// an error that drifts slowly).
// For a body of revolution (render/symmetry_detection.h) the images cannot show the angle about
// its axis, so each annotated pose is first turned about the axis to the angle nearest the
// ground truth's (RotationalSymmetry::HoldAngle): the rotation error is then the axis's own
// error and the turn about it is left out (a note on stderr says so; --no-symmetry keeps the
// plain error).
//   build/tests/bench/pbr_errors SEQ ANNOTATION_DIR [--blocks 10] [--rotation] [--no-symmetry]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/render/symmetry_detection.h"

namespace {

void PrintStats(const std::string& name, const std::vector<double>& rot,
                const std::vector<Eigen::Vector3d>& err) {
  const int n = static_cast<int>(rot.size());
  if (n == 0) return;
  double rot_sum = 0, rot_max = 0, worst = 0;
  int lost = 0;
  Eigen::Vector3d abs_sum = Eigen::Vector3d::Zero(), sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    rot_sum += rot[i];
    rot_max = std::max(rot_max, rot[i]);
    worst = std::max(worst, err[i].norm());
    abs_sum += err[i].cwiseAbs();
    sum += err[i];
    if (rot[i] > 5.0 || err[i].norm() > 50.0) ++lost;
  }
  const Eigen::Vector3d mean = sum / n;
  Eigen::Vector3d var = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) var += (err[i] - mean).cwiseAbs2();
  const Eigen::Vector3d sd =
      n > 1 ? Eigen::Vector3d((var / (n - 1)).cwiseSqrt()) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d abs_mean = abs_sum / n;
  std::printf("%s\n",
              fmt::format("{}\t{}\t{:.4f}\t{:.4f}\t{:.4f}\t{:.4f}\t{:.4f}\t{:+.4f}\t{:+.4f}\t"
                          "{:+.4f}\t{:.4f}\t{:.4f}\t{:.4f}\t{:.4f}\t{}",
                          name, n, rot_sum / n, rot_max, abs_mean.x(), abs_mean.y(), abs_mean.z(),
                          mean.x(), mean.y(), mean.z(), sd.x(), sd.y(), sd.z(), worst, lost)
                  .c_str());
}

// The rotation errors φ (deg, one per frame): mean, standard deviation per axis, mean step.
void PrintRotationVectors(const std::string& name, const std::vector<Eigen::Vector3d>& phi) {
  const int n = static_cast<int>(phi.size());
  if (n < 2) return;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : phi) mean += v;
  mean /= n;
  Eigen::Vector3d var = Eigen::Vector3d::Zero();
  double step = 0.0;
  for (int i = 0; i < n; ++i) {
    var += (phi[i] - mean).cwiseAbs2();
    if (i > 0) step += (phi[i] - phi[i - 1]).norm();
  }
  const Eigen::Vector3d sd = (var / (n - 1)).cwiseSqrt();
  std::printf(
      "%s\n",
      fmt::format("{}:rotation\t{:+.4f}\t{:+.4f}\t{:+.4f}\t{:.4f}\t{:.4f}\t{:.4f}\t{:.4f}", name,
                  mean.x(), mean.y(), mean.z(), sd.x(), sd.y(), sd.z(), step / (n - 1))
          .c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Per-camera pose errors (bias and spread per axis) at the bounding-box centre"};
  std::string seq_dir, ann_dir;
  int blocks = 0;
  app.add_option("sequence", seq_dir)->required();
  app.add_option("annotation", ann_dir)->required();
  app.add_option("--blocks", blocks, "also per block of N consecutive frames");
  bool rotation_vectors = false, no_symmetry = false;
  app.add_flag("--rotation", rotation_vectors, "also the rotation error's bias and jitter");
  app.add_flag("--no-symmetry", no_symmetry,
               "count the turn about a body of revolution's axis as an error too");
  CLI11_PARSE(app, argc, argv);

  auto seq = bcot::LoadSequence(seq_dir, /*require_init_pose=*/false);
  if (!seq.ok()) {
    std::fprintf(stderr, "%s\n", seq.status().message().c_str());
    return 2;
  }
  auto mesh = bcot::Mesh::Load(seq->object.mesh_path, seq->object.unit_to_mm);
  auto truth = bcot::ReadPoseFile(seq_dir + "/gt/rig_from_object.txt");
  auto est = bcot::ReadPoseFile(ann_dir + "/rig_from_object.txt");
  for (const bcot::Status& s : {mesh.status(), truth.status(), est.status()}) {
    if (!s.ok()) {
      std::fprintf(stderr, "%s\n", s.message().c_str());
      return 2;
    }
  }
  if (truth->size() != est->size()) {
    std::fprintf(stderr, "%zu ground-truth poses, %zu annotated\n", truth->size(), est->size());
    return 2;
  }
  if (!no_symmetry) {
    const bcot::RayCaster caster(*mesh);
    const auto symmetry = bcot::DetectRotationalSymmetry(caster, bcot::SymmetryDetectionOptions());
    if (!symmetry.ok()) {
      std::fprintf(stderr, "%s\n", symmetry.status().message().c_str());
      return 2;
    }
    if (symmetry->has_value()) {
      // How far each pose set turns about the axis from one frame to the next (O_t).
      const Eigen::Vector3d axis = (*symmetry)->axis;
      const auto turns = [&](const std::vector<Eigen::Isometry3d>& poses) {
        double sum = 0.0, largest = 0.0;
        for (size_t i = 1; i < poses.size(); ++i) {
          const double turn =
              std::abs(
                  bcot::LogSO3(poses[i - 1].linear().transpose() * poses[i].linear()).dot(axis)) *
              180.0 / M_PI;
          sum += turn;
          largest = std::max(largest, turn);
        }
        return std::make_pair(sum / std::max<size_t>(1, poses.size() - 1), largest);
      };
      const auto [annotated_mean, annotated_max] = turns(*est);
      const auto [true_mean, true_max] = turns(*truth);
      std::fprintf(stderr,
                   "pbr_errors: the object is a body of revolution: rotation errors leave out "
                   "the turn about its axis (--no-symmetry keeps it); that turn from one frame "
                   "to the next: annotation %.4f° mean, %.4f° max; ground truth %.4f° mean, "
                   "%.4f° max\n",
                   annotated_mean, annotated_max, true_mean, true_max);
      for (size_t i = 0; i < truth->size(); ++i) {
        (*est)[i] = (*symmetry)->HoldAngle(est->at(i), truth->at(i));
      }
    }
  }
  const Eigen::Vector3d centre = mesh->bbox_center();
  for (int view = 0; view < seq->rig.size(); ++view) {
    const auto& rc = seq->rig[view];
    std::vector<double> rot;
    std::vector<Eigen::Vector3d> err, phi;
    for (size_t i = 0; i < truth->size(); ++i) {
      const Eigen::Isometry3d g = rc.cam_from_rig * truth->at(i);
      const Eigen::Isometry3d t = rc.cam_from_rig * est->at(i);
      const Eigen::AngleAxisd d(t.linear() * g.linear().transpose());
      rot.push_back(std::abs(d.angle()) * 180.0 / M_PI);
      phi.push_back(d.angle() * d.axis() * 180.0 / M_PI);
      err.push_back(t * centre - g * centre);
    }
    PrintStats(rc.camera.name, rot, err);
    if (rotation_vectors) PrintRotationVectors(rc.camera.name, phi);
    for (int b = 0; blocks > 0 && b * blocks < static_cast<int>(rot.size()); ++b) {
      const int lo = b * blocks, hi = std::min<int>(rot.size(), lo + blocks);
      PrintStats(fmt::format("{}#{}", rc.camera.name, b),
                 std::vector<double>(rot.begin() + lo, rot.begin() + hi),
                 std::vector<Eigen::Vector3d>(err.begin() + lo, err.begin() + hi));
    }
  }
  return 0;
}
