// Accuracy and jitter of the temporal smoothing window on synthetic sequences with ground
// truth (gt/rig_from_object.txt), run by scripts/bench_window.sh; not a test.
//
// Every sequence is annotated once with the given config and the window switched on:
// SequenceAnnotation holds the per-frame poses (before the window) and the final ones, so both
// rows come from the same per-frame solves. Metrics: core/trajectory_metrics.h, at the mesh's
// bounding-box centre, in the rig frame (cam0: z is depth). A sequence given as DIR:K has a
// velocity step at frame K; the mean error over frames K−1..K+1 is then printed too.
//
// Usage: window_bench --config configs/annotate.yaml --sequence DIR[:K] [--sequence ...]
//          [--set section.key=value]...
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/core/trajectory_metrics.h"
#include "bcot/pipeline/annotate_options.h"
#include "bcot/pipeline/annotator.h"
#include "bcot/render/mesh.h"

namespace bcot {
namespace {

struct Row {
  TrajectoryErrors all;
  double step_rotation_deg = -1.0;  // < 0: no step
  double step_translation_mm = -1.0;
};

Row Measure(const std::vector<Eigen::Isometry3d>& poses,
            const std::vector<Eigen::Isometry3d>& truth, const Eigen::Vector3d& centre, int step) {
  Row row;
  const int n = static_cast<int>(truth.size());
  row.all = CompareTrajectories(poses, truth, centre, 0, n);
  if (step > 0 && step + 2 <= n) {
    row.step_rotation_deg = 0.0;
    row.step_translation_mm = 0.0;
    for (int t = step - 1; t <= step + 1; ++t) {
      row.step_rotation_deg += RotationDistanceDeg(poses[t].linear(), truth[t].linear()) / 3.0;
      row.step_translation_mm += (poses[t] * centre - truth[t] * centre).norm() / 3.0;
    }
  }
  return row;
}

std::string Format(const std::string& name, const std::string& poses, const Row& r) {
  const std::string step =
      r.step_rotation_deg < 0.0
          ? "–"
          : fmt::format("{:.3f} / {:.3f}", r.step_rotation_deg, r.step_translation_mm);
  return fmt::format("| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.4f} | {:.4f} | {} |", name,
                     poses, r.all.rotation_deg, r.all.translation_mm.x(), r.all.translation_mm.y(),
                     r.all.translation_mm.z(), r.all.jitter_rotation_deg,
                     r.all.jitter_translation_mm, step);
}

int Run(int argc, char** argv) {
  CLI::App app("Temporal window benchmark (accuracy and jitter vs ground truth)");
  std::string config;
  std::vector<std::string> sequences;
  std::vector<std::string> overrides;
  app.add_option("--config", config, "annotate config")->required();
  app.add_option("--sequence", sequences, "sequence dir, DIR:K for a velocity step at K")
      ->required();
  app.add_option("--set", overrides, "section.key=value overrides");
  CLI11_PARSE(app, argc, argv);
  StatusOr<AnnotateOptions> options = ReadAnnotateOptions(config, overrides);
  if (!options.ok()) {
    std::fprintf(stderr, "%s\n", options.status().message().c_str());
    return 2;
  }
  options->window.enabled = true;
  std::printf(
      "| sequence | poses | rotation (deg) | x (mm) | y (mm) | z (mm) | "
      "jitter rot (deg/frame²) | jitter trans (mm/frame²) | step frames deg / mm |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& spec : sequences) {
    const size_t colon = spec.rfind(':');
    const std::string dir = colon == std::string::npos ? spec : spec.substr(0, colon);
    const int step = colon == std::string::npos ? -1 : std::stoi(spec.substr(colon + 1));
    StatusOr<Sequence> sequence = LoadSequence(dir);
    StatusOr<std::vector<Eigen::Isometry3d>> truth = ReadPoseFile(dir + "/gt/rig_from_object.txt");
    if (!sequence.ok() || !truth.ok()) {
      std::fprintf(stderr, "%s: %s\n", dir.c_str(),
                   (!sequence.ok() ? sequence.status() : truth.status()).message().c_str());
      return 1;
    }
    StatusOr<Mesh> mesh = Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
    if (!mesh.ok()) return 1;
    const Eigen::Vector3d centre = mesh->objcentre_from_template().inverse().translation();
    const auto start = std::chrono::steady_clock::now();
    StatusOr<SequenceAnnotation> annotation = AnnotateSequence(*sequence, *options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!annotation.ok()) {
      std::fprintf(stderr, "%s: %s\n", dir.c_str(), annotation.status().message().c_str());
      return 1;
    }
    if (truth->size() != annotation->rig_from_object.size()) {
      std::fprintf(stderr, "%s: %zu truth poses for %zu frames\n", dir.c_str(), truth->size(),
                   annotation->rig_from_object.size());
      return 1;
    }
    const std::filesystem::path path(dir);
    const std::string name =
        path.parent_path().filename().string() + "/" + path.filename().string();
    std::printf("%s\n", Format(name, "per-frame",
                               Measure(annotation->per_frame_rig_from_object, *truth, centre, step))
                            .c_str());
    std::printf(
        "%s\n",
        Format(name, "window", Measure(annotation->rig_from_object, *truth, centre, step)).c_str());
    std::fprintf(stderr, "%s: %zu frames, %d failed, %.1f s (per-frame solves + window)\n",
                 dir.c_str(), annotation->frames.size(), annotation->failed_frames, seconds);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace bcot

int main(int argc, char** argv) { return bcot::Run(argc, argv); }
