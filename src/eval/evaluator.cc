#include "bcot/eval/evaluator.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "bcot/core/config_file.h"
#include "bcot/core/file_util.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/yaml_util.h"
#include "bcot/eval/bcot_layout.h"
#include "bcot/eval/rbot_layout.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

// Mesh cache: sequences of one object share the loaded mesh.
class MeshCache {
 public:
  StatusOr<const Mesh*> Get(const std::string& path) {
    auto it = meshes_.find(path);
    if (it == meshes_.end()) {
      BCOT_ASSIGN_OR_RETURN(Mesh mesh, Mesh::Load(path));
      it = meshes_.emplace(path, std::move(mesh)).first;
    }
    return &it->second;
  }

 private:
  std::map<std::string, Mesh> meshes_;
};

}  // namespace

Status EvalOptions::Validate() const {
  std::vector<std::string> violations;
  if (layout != "bcot" && layout != "rbot") {
    violations.push_back(fmt::format("layout = '{}', must be 'bcot' or 'rbot'", layout));
  }
  if (rbot_variant.empty() || rbot_variant.find('/') != std::string::npos) {
    violations.push_back(
        fmt::format("rbot_variant = '{}', must be a non-empty file-name prefix", rbot_variant));
  }
  if (rbot_poses.empty()) violations.push_back("rbot_poses is empty, must name the GT file");
  if (!(reset_rotation_deg > 0.0 && reset_rotation_deg <= 180.0)) {
    violations.push_back(
        fmt::format("reset_rotation_deg = {}, must be in (0, 180]", reset_rotation_deg));
  }
  if (!(reset_translation_mm > 0.0 && std::isfinite(reset_translation_mm))) {
    violations.push_back(
        fmt::format("reset_translation_mm = {}, must be > 0", reset_translation_mm));
  }
  const Status curve_status = curve.Validate();
  if (!curve_status.ok()) violations.push_back(curve_status.message());
  if (violations.empty()) return Status::Ok();
  return Status::InvalidConfig(JoinMessages(violations));
}

StatusOr<EvalOptions> ReadEvalOptions(const std::string& path,
                                      const std::vector<std::string>& overrides) {
  std::string source;
  BCOT_ASSIGN_OR_RETURN(const YAML::Node root, LoadConfigWithOverrides(path, overrides, &source));
  EvalOptions options;
  YamlMap map(root, source, "", StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.GetOptional("layout", &options.layout));
  BCOT_RETURN_IF_ERROR(map.GetOptional("rbot_variant", &options.rbot_variant));
  BCOT_RETURN_IF_ERROR(map.GetOptional("rbot_poses", &options.rbot_poses));
  BCOT_RETURN_IF_ERROR(map.GetOptional("reset_rotation_deg", &options.reset_rotation_deg));
  BCOT_RETURN_IF_ERROR(map.GetOptional("reset_translation_mm", &options.reset_translation_mm));
  if (map.Has("curve")) {
    YamlMap curve(map.Node("curve"), source, "curve", StatusCode::kInvalidConfig);
    BCOT_RETURN_IF_ERROR(curve.GetOptional("max_fraction_of_d", &options.curve.max_fraction_of_d));
    BCOT_RETURN_IF_ERROR(curve.GetOptional("steps", &options.curve.steps));
    BCOT_RETURN_IF_ERROR(curve.CheckNoUnknownKeys());
  }
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  const Status valid = options.Validate();
  if (!valid.ok()) return valid.WithContext(source);
  return options;
}

std::string FormatEvalOptions(const EvalOptions& o) {
  return fmt::format("# bcot eval: fully resolved options (bcot " BCOT_VERSION
                     ")\n"
                     "layout: {}\nrbot_variant: {}\nrbot_poses: {}\nreset_rotation_deg: {}\n"
                     "reset_translation_mm: {}\ncurve:\n  max_fraction_of_d: {}\n  steps: {}\n",
                     FormatYamlString(o.layout), FormatYamlString(o.rbot_variant),
                     FormatYamlString(o.rbot_poses), o.reset_rotation_deg, o.reset_translation_mm,
                     o.curve.max_fraction_of_d, o.curve.steps);
}

StatusOr<std::vector<BenchmarkSequence>> LoadBenchmark(const std::string& root,
                                                       const EvalOptions& options) {
  if (options.layout == "rbot") {
    return LoadRbotDataset(root, options.rbot_variant, options.rbot_poses);
  }
  return LoadBcotDataset(root);
}

StatusOr<SequenceResult> ScoreSequence(
    const BenchmarkSequence& sequence, const Mesh& mesh,
    const std::vector<Eigen::Isometry3d>& estimated_cam_from_object, const std::string& source,
    const EvalOptions& options) {
  const size_t n = sequence.gt_cam_from_object.size();
  const size_t m = estimated_cam_from_object.size();
  if (m != n && m + 1 != n) {
    return Status::InvalidInput(
        fmt::format("{}: {} poses, expected {} (frames 0..{}) or {} (frames 1..{}) for {} ({})",
                    source, m, n, n - 1, n - 1, n - 1, sequence.RelativeDir(), sequence.gt_path));
  }
  const size_t offset = n - m;  // 0: the file holds frame 0 too
  SequenceResult result;
  result.scene = sequence.scene;
  result.object = sequence.object;
  for (size_t frame = 1; frame < n; ++frame) {
    ScoredFrame scored;
    scored.errors = ComputeFrameErrors(mesh.vertices(), estimated_cam_from_object[frame - offset],
                                       sequence.gt_cam_from_object[frame]);
    scored.diameter_mm = mesh.diameter();
    scored.time_ms = std::numeric_limits<double>::quiet_NaN();
    scored.lost =
        IsTrackingFailure(scored.errors, options.reset_rotation_deg, options.reset_translation_mm);
    result.frames.push_back(scored);
  }
  return result;
}

StatusOr<std::vector<SequenceResult>> EvaluateOffline(
    const std::vector<BenchmarkSequence>& sequences, const std::string& results_root,
    const EvalOptions& options) {
  MeshCache meshes;
  std::vector<SequenceResult> results;
  for (const BenchmarkSequence& sequence : sequences) {
    const std::string path =
        (fs::path(results_root) / sequence.scene / sequence.object / "pose.txt").string();
    std::error_code error;
    if (!fs::exists(path, error)) {
      return Status::NotFound(
          fmt::format("{}: result pose file of {} not found", path, sequence.RelativeDir()));
    }
    BCOT_ASSIGN_OR_RETURN(const std::vector<Eigen::Isometry3d> estimates, ReadPoseFile(path));
    BCOT_ASSIGN_OR_RETURN(const Mesh* mesh, meshes.Get(sequence.mesh_path));
    BCOT_ASSIGN_OR_RETURN(SequenceResult result,
                          ScoreSequence(sequence, *mesh, estimates, path, options));
    results.push_back(std::move(result));
  }
  return results;
}

StatusOr<SequenceResult> RunTrackingProtocol(const BenchmarkSequence& sequence, const Mesh& mesh,
                                             MonocularTracker* tracker, const EvalOptions& options,
                                             std::vector<Eigen::Isometry3d>* estimates) {
  BCOT_CHECK(tracker != nullptr);
  const size_t n = sequence.gt_cam_from_object.size();
  BCOT_CHECK(sequence.image_paths.size() == n && n > 0);
  SequenceResult result;
  result.scene = sequence.scene;
  result.object = sequence.object;
  if (estimates != nullptr) estimates->assign(1, sequence.gt_cam_from_object[0]);

  BCOT_ASSIGN_OR_RETURN(const cv::Mat3b first, ReadColorImage(sequence.image_paths[0]));
  BCOT_RETURN_IF_ERROR(tracker->Reset(first, sequence.gt_cam_from_object[0])
                           .WithContext(sequence.image_paths[0] + ": tracker reset"));
  for (size_t frame = 1; frame < n; ++frame) {
    BCOT_ASSIGN_OR_RETURN(const cv::Mat3b image, ReadColorImage(sequence.image_paths[frame]));
    if (image.size() != first.size()) {
      return Status::InvalidInput(fmt::format("{}: image is {}x{}, frame 0 is {}x{}",
                                              sequence.image_paths[frame], image.cols, image.rows,
                                              first.cols, first.rows));
    }
    const Eigen::Isometry3d& truth = sequence.gt_cam_from_object[frame];
    const auto start = std::chrono::steady_clock::now();
    StatusOr<Eigen::Isometry3d> tracked = tracker->Track(image);
    const double time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ScoredFrame scored;
    scored.diameter_mm = mesh.diameter();
    scored.time_ms = time_ms;
    if (tracked.ok()) {
      scored.errors = ComputeFrameErrors(mesh.vertices(), *tracked, truth);
      scored.lost = IsTrackingFailure(scored.errors, options.reset_rotation_deg,
                                      options.reset_translation_mm);
    } else {
      // A tracker error is a failure on every metric.
      constexpr double kInf = std::numeric_limits<double>::infinity();
      scored.errors = {kInf, kInf, kInf};
      scored.lost = true;
    }
    if (estimates != nullptr) estimates->push_back(tracked.ok() ? *tracked : estimates->back());
    result.frames.push_back(scored);
    if (scored.lost) {
      ++result.num_resets;
      BCOT_RETURN_IF_ERROR(tracker->Reset(image, truth)
                               .WithContext(sequence.image_paths[frame] + ": tracker reset"));
    }
  }
  return result;
}

StatusOr<std::vector<SequenceResult>> EvaluateOnline(
    const std::vector<BenchmarkSequence>& sequences, const MonocularTrackerFactory& factory,
    const EvalOptions& options, const std::string& poses_out_root, const EvalProgress& progress) {
  BCOT_CHECK(factory != nullptr);
  MeshCache meshes;
  std::vector<SequenceResult> results;
  for (const BenchmarkSequence& sequence : sequences) {
    BCOT_ASSIGN_OR_RETURN(const Mesh* mesh, meshes.Get(sequence.mesh_path));
    BCOT_ASSIGN_OR_RETURN(const cv::Mat3b first, ReadColorImage(sequence.image_paths.at(0)));
    Camera camera = sequence.camera;
    camera.width = first.cols;
    camera.height = first.rows;
    BCOT_RETURN_IF_ERROR(camera.Validate(sequence.RelativeDir() + " camera"));
    BCOT_ASSIGN_OR_RETURN(std::unique_ptr<MonocularTracker> tracker, factory(camera, *mesh));
    std::vector<Eigen::Isometry3d> estimates;
    BCOT_ASSIGN_OR_RETURN(SequenceResult result,
                          RunTrackingProtocol(sequence, *mesh, tracker.get(), options, &estimates));
    if (!poses_out_root.empty()) {
      BCOT_RETURN_IF_ERROR(WritePoseFile(
          (fs::path(poses_out_root) / sequence.scene / sequence.object / "pose.txt").string(),
          estimates));
    }
    results.push_back(std::move(result));
    if (progress) {
      progress(static_cast<int>(results.size()), static_cast<int>(sequences.size()),
               results.back());
    }
  }
  return results;
}

}  // namespace bcot
