// Accuracy and jitter of the temporal smoothing window on synthetic sequences with ground
// truth (gt/rig_from_object.txt), run by scripts/bench_window.sh; not a test.
//
// Every sequence is annotated once with the given config and the window switched on:
// SequenceAnnotation holds the per-frame poses (before the window) and the final ones, so both
// rows come from the same per-frame solves. Metrics: core/trajectory_metrics.h, at the mesh's
// bounding-box centre, in the rig frame (cam0: z is depth). A sequence given as DIR:K has a
// velocity step at frame K; the mean error over frames K−1..K+1 is then printed too.
// Each --variant LABEL:key=value[,key=value...] (window.* keys without the section, e.g.
// `q:robust_translation_mm=0`) adds a row from a further window with those options, run on the same
// per-frame solves (AnnotateFrameObserver), so settings compare without re-solving; the prior σ
// each of its windows ran with (raised by window.adaptive_prior) goes to stderr. A variant that
// changes nothing (e.g. `same:adaptive_prior=true`) shows them for the config's own window.
//
// Usage: window_bench --config configs/annotate.yaml --sequence DIR[:K] [--sequence ...]
//          [--set section.key=value]... [--variant LABEL:key=value,...]...
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/annotator.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/core/trajectory_metrics.h"
#include "bcot/optim/window_problem.h"
#include "bcot/render/mesh.h"
#include "ground_truth_sequence.h"

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

// Per rig axis: mean over t of |a_t − a_gt,t| of the point's acceleration (mm/frame²).
Eigen::Vector3d AxisJitterMm(const std::vector<Eigen::Isometry3d>& poses,
                             const std::vector<Eigen::Isometry3d>& truth,
                             const Eigen::Vector3d& centre) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const int n = static_cast<int>(truth.size());
  for (int t = 1; t + 1 < n; ++t) {
    const auto acceleration = [&](const std::vector<Eigen::Isometry3d>& p) {
      return Eigen::Vector3d(p[t + 1] * centre - 2.0 * (p[t] * centre) + p[t - 1] * centre);
    };
    sum += (acceleration(poses) - acceleration(truth)).cwiseAbs();
  }
  return n > 2 ? Eigen::Vector3d(sum / (n - 2)) : sum;
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

struct Variant {
  std::string label;
  WindowProblemOptions window;
};

// LABEL:key=value,key=value → the config's window options with window.key=value overrides.
StatusOr<Variant> ParseVariant(const std::string& config, std::vector<std::string> overrides,
                               const std::string& spec) {
  const size_t colon = spec.find(':');
  Variant variant;
  variant.label = spec.substr(0, colon);
  if (colon != std::string::npos) {
    std::string rest = spec.substr(colon + 1);
    size_t begin = 0;
    while (begin < rest.size()) {
      size_t comma = rest.find(',', begin);
      // A comma inside [..] belongs to a list value.
      const size_t bracket = rest.find('[', begin);
      if (bracket != std::string::npos && bracket < comma)
        comma = rest.find(',', rest.find(']', bracket));
      if (comma == std::string::npos) comma = rest.size();
      overrides.push_back("window." + rest.substr(begin, comma - begin));
      begin = comma + 1;
    }
  }
  StatusOr<AnnotateOptions> options = ReadAnnotateOptions(config, overrides);
  if (!options.ok()) return options.status();
  variant.window = options->window;
  variant.window.enabled = true;
  return variant;
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
  std::vector<std::string> variant_specs;
  app.add_option("--variant", variant_specs,
                 "LABEL:key=value,... further window settings on the same per-frame solves");
  CLI11_PARSE(app, argc, argv);
  std::vector<Variant> variants;
  for (const std::string& spec : variant_specs) {
    StatusOr<Variant> variant = ParseVariant(config, overrides, spec);
    if (!variant.ok()) {
      std::fprintf(stderr, "%s\n", variant.status().message().c_str());
      return 2;
    }
    variants.push_back(*variant);
  }
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
    StatusOr<bench::GroundTruthSequence> loaded = bench::LoadGroundTruthSequence(dir);
    if (!loaded.ok()) {
      std::fprintf(stderr, "%s: %s\n", dir.c_str(), loaded.status().message().c_str());
      return 1;
    }
    const Sequence* sequence = &loaded->sequence;
    const std::vector<Eigen::Isometry3d>* truth = &loaded->truth;
    const Mesh* mesh = &loaded->mesh;
    const Eigen::Vector3d centre = mesh->objcentre_from_template().inverse().translation();
    std::vector<WindowSmoother> smoothers;
    smoothers.reserve(variants.size());
    for (const Variant& variant : variants) smoothers.emplace_back(variant.window);
    const auto start = std::chrono::steady_clock::now();
    StatusOr<SequenceAnnotation> annotation =
        AnnotateSequence(*sequence, *options, {},
                         [&smoothers](int, const Eigen::Isometry3d& rig_from_objcentre,
                                      const std::vector<ViewLinearisation>& linearisations) {
                           for (WindowSmoother& smoother : smoothers)
                             smoother.Push(rig_from_objcentre, linearisations);
                         });
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
    // One table row per pose set; its per-axis translation jitter on stderr (diagnostics).
    const auto print = [&](const std::string& label, const std::vector<Eigen::Isometry3d>& poses) {
      std::printf("%s\n", Format(name, label, Measure(poses, *truth, centre, step)).c_str());
      const Eigen::Vector3d axis_jitter = AxisJitterMm(poses, *truth, centre);
      // How far the window moved the poses from the per-frame solves (the templates it
      // re-uses are linearised there).
      double shift_mm = 0.0, max_shift_mm = 0.0;
      for (size_t t = 0; t < poses.size(); ++t) {
        const double d =
            (poses[t] * centre - annotation->per_frame_rig_from_object[t] * centre).norm();
        shift_mm += d / static_cast<double>(poses.size());
        max_shift_mm = std::max(max_shift_mm, d);
      }
      std::fprintf(stderr,
                   "%s %s: translation jitter per rig axis x %.4f y %.4f z %.4f mm; centre moved "
                   "by the window mean %.4f max %.4f mm\n",
                   name.c_str(), label.c_str(), axis_jitter.x(), axis_jitter.y(), axis_jitter.z(),
                   shift_mm, max_shift_mm);
      if (step > 2 && step + 2 < static_cast<int>(truth->size())) {
        // Jitter of each constant-speed stretch on its own (the slow one, then the fast one).
        const TrajectoryErrors slow = CompareTrajectories(poses, *truth, centre, 0, step);
        const TrajectoryErrors fast =
            CompareTrajectories(poses, *truth, centre, step, static_cast<int>(truth->size()));
        std::fprintf(stderr,
                     "%s %s: jitter before the step rot %.4f trans %.4f, after rot %.4f trans "
                     "%.4f\n",
                     name.c_str(), label.c_str(), slow.jitter_rotation_deg,
                     slow.jitter_translation_mm, fast.jitter_rotation_deg,
                     fast.jitter_translation_mm);
      }
    };
    print("per-frame", annotation->per_frame_rig_from_object);
    if (step > 3 && step + 3 < static_cast<int>(truth->size())) {
      // What a smoother can remove in each stretch: the true change of the centre's acceleration
      // (rms per axis of the truth's third differences, mm/frame³) against the part of the
      // per-frame solves' third differences that is noise (√20 · rms per-axis error, white noise).
      const auto stretch = [&](int first, int end) {
        const auto point = [&](const std::vector<Eigen::Isometry3d>& p, int k) {
          return Eigen::Vector3d(p[k] * centre);
        };
        // Per-frame error about its mean over the stretch (the slowly varying bias is not
        // frame-to-frame noise).
        std::vector<Eigen::Vector3d> errors;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (int t = first; t < end; ++t) {
          errors.push_back(point(annotation->per_frame_rig_from_object, t) - point(*truth, t));
          mean += errors.back() / (end - first);
        }
        double noise = 0.0, jerk = 0.0;
        int jerks = 0;
        for (const Eigen::Vector3d& error : errors) {
          noise += (error - mean).squaredNorm() / 3.0 / errors.size();
        }
        for (int t = first + 1; t + 2 < end; ++t) {
          jerk += (point(*truth, t + 2) - 3.0 * point(*truth, t + 1) + 3.0 * point(*truth, t) -
                   point(*truth, t - 1))
                      .squaredNorm() /
                  3.0;
          ++jerks;
        }
        return std::pair{std::sqrt(jerk / std::max(jerks, 1)), std::sqrt(20.0 * noise)};
      };
      const auto [slow_jerk, slow_noise] = stretch(0, step);
      const auto [fast_jerk, fast_noise] = stretch(step, static_cast<int>(truth->size()));
      std::fprintf(stderr,
                   "%s: change of acceleration rms, truth vs per-frame noise (mm/frame³): before "
                   "the step %.4f vs %.4f, after %.4f vs %.4f\n",
                   name.c_str(), slow_jerk, slow_noise, fast_jerk, fast_noise);
    }
    print("window", annotation->rig_from_object);
    const Eigen::Isometry3d objcentre_from_template = mesh->objcentre_from_template();
    for (size_t k = 0; k < variants.size(); ++k) {
      smoothers[k].Finish();
      std::vector<Eigen::Isometry3d> poses;
      for (const Eigen::Isometry3d& pose : smoothers[k].rig_from_objcentre()) {
        poses.push_back(pose * objcentre_from_template);
      }
      print(variants[k].label, poses);
      // The prior σ each of the variant's windows ran with (raised by window.adaptive_prior).
      std::string sigmas;
      for (const WindowSummary& window : smoothers[k].windows()) {
        sigmas += fmt::format(" [{}, {}) {:.3f} mm {:.3f}°", window.first, window.end,
                              window.translation_sigma_mm, window.rotation_sigma_deg);
      }
      std::fprintf(stderr, "%s %s: prior σ per window:%s\n", name.c_str(),
                   variants[k].label.c_str(), sigmas.c_str());
    }
    std::fprintf(stderr, "%s: %zu frames, %d failed, %.1f s (per-frame solves + window)\n",
                 dir.c_str(), annotation->frames.size(), annotation->failed_frames, seconds);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace bcot

int main(int argc, char** argv) { return bcot::Run(argc, argv); }
