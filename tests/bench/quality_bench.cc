// Honesty check of the quality report (issue 4), run by scripts/bench_quality.sh; not a test.
//
// For a synthetic sequence with ground truth (`bcot synth` writes gt/rig_from_object.txt),
// every frame and view gets two numbers:
//   measured  the report's reprojection error (MeasureQuality: contour of the pose vs the
//             boundary found in the image along the normals), p90 and median, px;
//   true      the same statistics of the true projected contour error: for each contour
//             sample of the pose, the distance (px) to the ground-truth pose's contour
//             (RayCaster, dense samples, point-to-polyline), no image involved.
// Poses: the annotation (--poses FILE, e.g. out/.../rig_from_object.txt) and/or ground truth
// perturbed per frame by a seeded random rigid motion whose size is uniform in
// [0, --max-deg] and [0, --max-mm] (so errors span 0 to a few px). Prints one row per frame and
// view and the Pearson correlation of measured vs true (p90 and median) over all rows.
//
// Usage: quality_bench --sequence DIR [--poses FILE] [--perturbed] [--max-deg 1.5]
//          [--max-mm 4] [--seed 1] [--offset-px 3 ...] [--rotate-px 2 ...] [--config FILE]
//          [--frames N]
// --offset-px: also ground truth as is and shifted so the object moves that far in cam0's image
// (the accept / reject check); --rotate-px: ground truth rotated about cam0's optical axis
// through the object centre so that its farthest contour point moves that far; --frames: only
// the first N frames.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/quality/boundary_search.h"
#include "bcot/quality/quality_files.h"
#include "bcot/quality/rigid_motion_fit.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "ground_truth_sequence.h"

namespace bcot {
namespace {

double DistanceToPolyline(const Eigen::Vector2d& p, const std::vector<ContourPoint>& contour) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < contour.size(); ++i) {
    const ContourPoint& a = contour[i];
    best = std::min(best, (p - a.pixel).norm());
    const size_t j = i + 1;
    if (j < contour.size() && contour[j].contour_id == a.contour_id) {
      const Eigen::Vector2d ab = contour[j].pixel - a.pixel;
      const double s =
          std::clamp((p - a.pixel).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
      best = std::min(best, (p - a.pixel - s * ab).norm());
    }
  }
  return best;
}

double Pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

struct Rows {
  std::vector<double> measured_p90, true_p90, measured_median, true_median;
  int unverifiable = 0;
  void Append(const Rows& other) {
    measured_p90.insert(measured_p90.end(), other.measured_p90.begin(), other.measured_p90.end());
    true_p90.insert(true_p90.end(), other.true_p90.begin(), other.true_p90.end());
    measured_median.insert(measured_median.end(), other.measured_median.begin(),
                           other.measured_median.end());
    true_median.insert(true_median.end(), other.true_median.begin(), other.true_median.end());
    unverifiable += other.unverifiable;
  }
};

void PrintCorrelation(const std::string& label, const Rows& rows) {
  if (rows.true_p90.size() < 3) return;
  double mean_abs_difference = 0.0, within = 0.0, ratio = 0.0;
  int ratio_rows = 0;
  const double n = static_cast<double>(rows.true_p90.size());
  for (size_t i = 0; i < rows.true_p90.size(); ++i) {
    const double difference = rows.measured_p90[i] - rows.true_p90[i];
    mean_abs_difference += std::abs(difference) / n;
    within += (std::abs(difference) <= 0.5 ? 1.0 : 0.0) / n;
    if (rows.true_p90[i] >= 0.5) {  // the ratio means nothing near zero
      ratio += rows.measured_p90[i] / rows.true_p90[i];
      ++ratio_rows;
    }
  }
  ratio = ratio_rows > 0 ? ratio / ratio_rows : std::numeric_limits<double>::quiet_NaN();
  std::printf(
      "%-10s rows %zu (+%d cannot tell)  pearson(p90) %.3f  pearson(median) %.3f  "
      "mean |meas-true| p90 %.3f px  within 0.5 px %.1f%%  mean meas/true p90 (true >= 0.5 px) "
      "%.2f\n",
      label.c_str(), rows.true_p90.size(), rows.unverifiable,
      Pearson(rows.measured_p90, rows.true_p90), Pearson(rows.measured_median, rows.true_median),
      mean_abs_difference, 100.0 * within, ratio);
}

// `sequence` and `gt` hold the same frames; `rig_from_object` has at least as many poses.
// `caster` holds the sequence's mesh.
int Run(const Sequence& sequence, const RayCaster& caster, const std::vector<Eigen::Isometry3d>& gt,
        const std::string& label, std::vector<Eigen::Isometry3d> rig_from_object,
        const QualityOptions& options, Rows* rows) {
  Rows mine;
  rig_from_object.resize(gt.size());
  const StatusOr<QualityReport> report =
      MeasureQuality(sequence, caster, rig_from_object, {}, options, ImageResponse());
  if (!report.ok()) {
    std::fprintf(stderr, "quality_bench: %s\n", report.status().message().c_str());
    return 1;
  }
  ContourOptions dense;
  dense.sample_spacing_px = 0.5;
  ContourOptions sparse;
  sparse.sample_spacing_px = options.sample_spacing_px;
  for (int f = 0; f < sequence.num_frames; ++f) {
    for (int v = 0; v < sequence.rig.size(); ++v) {
      const RigCamera& camera = sequence.rig[v];
      const std::vector<ContourPoint> truth =
          caster.ExtractContour(camera.camera, camera.cam_from_rig * gt[f], dense);
      const std::vector<ContourPoint> posed =
          caster.ExtractContour(camera.camera, camera.cam_from_rig * rig_from_object[f], sparse);
      std::vector<double> distances;
      for (const ContourPoint& point : posed) {
        distances.push_back(DistanceToPolyline(point.pixel, truth));
      }
      const ViewFrameQuality& q = report->frames[f][v];
      const double true_p90 = AbsPercentile(distances, 0.9);
      const double true_median = AbsPercentile(distances, 0.5);
      std::printf("%-10s %5d %-6s %10.3f %10.3f %10.3f %10.3f %8.3f %7d/%d%s\n", label.c_str(), f,
                  camera.camera.name.c_str(), q.p90_px, true_p90, q.median_px, true_median,
                  q.statistic_sigma_px, q.found, q.points, q.verifiable ? "" : " cannot-tell");
      if (!q.verifiable) {
        ++mine.unverifiable;
      } else if (std::isfinite(q.p90_px) && std::isfinite(true_p90)) {
        mine.measured_p90.push_back(q.p90_px);
        mine.true_p90.push_back(true_p90);
        mine.measured_median.push_back(q.median_px);
        mine.true_median.push_back(true_median);
      }
    }
  }
  std::printf("%-10s verdict: %s", label.c_str(), report->accepted ? "accepted" : "rejected");
  for (const std::string& reason : report->reasons) std::printf(" [%s]", reason.c_str());
  std::printf("\n");
  PrintCorrelation(label, mine);
  rows->Append(mine);
  return 0;
}

}  // namespace
}  // namespace bcot

int main(int argc, char** argv) {
  CLI::App app{"Measured reprojection error vs true projected contour error"};
  std::string sequence_dir, poses_path, config_path;
  bool perturbed = false;
  double max_deg = 1.5, max_mm = 4.0;
  int seed = 1;
  std::vector<double> offsets_px, rotations_px;
  int max_frames = 0;
  app.add_option("--sequence", sequence_dir, "Synthetic sequence (with gt/)")->required();
  app.add_option("--poses", poses_path, "Annotated rig_from_object.txt");
  app.add_flag("--perturbed", perturbed, "Also: ground truth perturbed per frame");
  app.add_option("--max-deg", max_deg, "Largest perturbation rotation (deg)");
  app.add_option("--max-mm", max_mm, "Largest perturbation translation (mm)");
  app.add_option("--seed", seed, "Perturbation seed");
  app.add_option("--offset-px", offsets_px,
                 "Also: ground truth as is and shifted so the object moves this far in cam0's "
                 "image (repeatable)");
  app.add_option("--rotate-px", rotations_px,
                 "Also: ground truth rotated about cam0's axis so its farthest contour point "
                 "moves this far (repeatable)");
  app.add_option("--frames", max_frames, "Only the first N frames (0 = all)");
  app.add_option("--config", config_path, "Annotate config (its quality: section is used)");
  std::vector<std::string> overrides;
  app.add_option("--set", overrides, "Config override key=value (repeatable)");
  CLI11_PARSE(app, argc, argv);
  using namespace bcot;
  const StatusOr<AnnotateOptions> options = ReadAnnotateOptions(config_path, overrides);
  if (!options.ok()) {
    std::fprintf(stderr, "quality_bench: %s\n", options.status().message().c_str());
    return 2;
  }
  StatusOr<bench::GroundTruthSequence> loaded = bench::LoadGroundTruthSequence(sequence_dir);
  if (!loaded.ok()) {
    std::fprintf(stderr, "quality_bench: %s\n", loaded.status().message().c_str());
    return 1;
  }
  Sequence* sequence = &loaded->sequence;
  std::vector<Eigen::Isometry3d>* gt = &loaded->truth;
  const Mesh* mesh = &loaded->mesh;
  if (max_frames > 0 && max_frames < sequence->num_frames) {
    sequence->num_frames = max_frames;
    for (std::vector<std::string>& paths : sequence->image_paths) paths.resize(max_frames);
    if (!sequence->timestamps_ns.empty()) sequence->timestamps_ns.resize(max_frames);
  }
  gt->resize(sequence->num_frames);
  const RayCaster caster(*mesh);
  std::printf("%-10s %5s %-6s %10s %10s %10s %10s %8s %9s\n", "poses", "frame", "view", "meas_p90",
              "true_p90", "meas_med", "true_med", "sigma", "found");
  Rows rows;
  auto run = [&](const std::string& label, const std::vector<Eigen::Isometry3d>& poses) {
    return Run(*sequence, caster, *gt, label, poses, options->quality, &rows);
  };
  if (!poses_path.empty()) {
    const StatusOr<std::vector<Eigen::Isometry3d>> poses = ReadPoseFile(poses_path);
    if (!poses.ok()) {
      std::fprintf(stderr, "quality_bench: %s\n", poses.status().message().c_str());
      return 1;
    }
    if (poses->size() < gt->size()) {
      std::fprintf(stderr, "quality_bench: %s: %zu poses for %zu frames\n", poses_path.c_str(),
                   poses->size(), gt->size());
      return 1;
    }
    if (run("annotated", *poses) != 0) return 1;
  }
  if (perturbed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<Eigen::Isometry3d> poses = *gt;
    for (Eigen::Isometry3d& rig_from_object : poses) {
      const Eigen::Vector3d axis =
          Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const Eigen::Vector3d direction =
          Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const double size = unit(rng);
      Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
      delta.linear() = Eigen::AngleAxisd(size * max_deg * M_PI / 180.0, axis).toRotationMatrix();
      delta.translation() = size * max_mm * direction;
      // Rotate about the object's origin, translate in the rig frame.
      rig_from_object = Eigen::Translation3d(delta.translation()) * rig_from_object *
                        Eigen::Isometry3d(delta.linear());
    }
    if (run("perturbed", poses) != 0) return 1;
  }
  const RigCamera& cam0 = sequence->rig[0];
  if (!offsets_px.empty()) offsets_px.insert(offsets_px.begin(), 0.0);
  for (const double shift : offsets_px) {
    std::vector<Eigen::Isometry3d> poses = *gt;
    for (Eigen::Isometry3d& rig_from_object : poses) {
      const double depth = (cam0.cam_from_rig * rig_from_object).translation().z();
      rig_from_object.pretranslate(cam0.cam_from_rig.linear().transpose() *
                                   Eigen::Vector3d(shift * depth / cam0.camera.fx, 0, 0));
    }
    if (run(fmt::format("gt+{}px", shift), poses) != 0) return 1;
  }
  for (const double move : rotations_px) {
    std::vector<Eigen::Isometry3d> poses = *gt;
    for (Eigen::Isometry3d& rig_from_object : poses) {
      // Farthest contour point from the projected object centre in cam0 (px).
      const Eigen::Isometry3d cam_from_object = cam0.cam_from_rig * rig_from_object;
      const Eigen::Vector3d centre_in_cam = cam_from_object * mesh->bbox_center();
      const Eigen::Vector2d centre = cam0.camera.Project(centre_in_cam);
      double radius = 0.0;
      for (const ContourPoint& point : caster.ExtractContour(cam0.camera, cam_from_object)) {
        radius = std::max(radius, (point.pixel - centre).norm());
      }
      if (radius <= 0.0) continue;
      // Rotation about cam0's optical axis through the object centre, in rig coordinates.
      const Eigen::Vector3d axis =
          cam0.cam_from_rig.linear().transpose() * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d pivot = rig_from_object * mesh->bbox_center();
      const Eigen::Isometry3d rotate = Eigen::Translation3d(pivot) *
                                       Eigen::AngleAxisd(move / radius, axis) *
                                       Eigen::Translation3d(-pivot);
      rig_from_object = rotate * rig_from_object;
    }
    if (run(fmt::format("gt~rot{}px", move), poses) != 0) return 1;
  }
  PrintCorrelation("all", rows);
  return 0;
}
