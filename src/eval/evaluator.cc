#include "bcot/eval/evaluator.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/yaml_util.h"
#include "bcot/eval/bcot_layout.h"
#include "bcot/eval/rbot_layout.h"
#include "bcot/core/version.h"

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

namespace {

OptionSchema<EvalOptions>* BuildEvalOptionSchema() {
  auto* s = new OptionSchema<EvalOptions>();
  s->Add(
       "layout", [](auto& o) -> auto& { return o.layout; }, "", "dataset layout of --data")
      .OneOf({"bcot", "rbot"});
  s->Add(
       "rbot_variant", [](auto& o) -> auto& { return o.rbot_variant; }, "",
       "RBOT only: image variant (a_regular, b_dynamiclight, c_noisy, d_occlusion)")
      .Check([](const EvalOptions& o) {
        return o.rbot_variant.empty() || o.rbot_variant.find('/') != std::string::npos
                   ? "must be a non-empty file-name prefix"
                   : "";
      });
  s->Add(
       "rbot_poses", [](auto& o) -> auto& { return o.rbot_poses; }, "",
       "RBOT only: GT file relative to the dataset root")
      .Check(
          [](const EvalOptions& o) { return o.rbot_poses.empty() ? "must name the GT file" : ""; });
  s->Add(
       "reset_rotation_deg", [](auto& o) -> auto& { return o.reset_rotation_deg; }, "deg",
       "a frame is lost (and the tracker reset) above this rotation error ...")
      .Range(LeftOpen(0, 180));
  s->Add(
       "reset_translation_mm", [](auto& o) -> auto& { return o.reset_translation_mm; }, "mm",
       "... or above this translation error")
      .Range(Positive());
  s->Include(
      CurveOptionSchema(), [](auto& o) -> auto& { return o.curve; });
  return s;
}

}  // namespace

const OptionSchema<EvalOptions>& EvalOptionSchema() {
  static const OptionSchema<EvalOptions>* const schema = BuildEvalOptionSchema();
  return *schema;
}

Status EvalOptions::Validate() const { return EvalOptionSchema().Validate(*this, nullptr); }

StatusOr<EvalOptions> ReadEvalOptions(const std::string& path,
                                      const std::vector<std::string>& overrides) {
  return EvalOptionSchema().Read(path, overrides);
}

std::string FormatEvalOptions(const EvalOptions& options) {
  return EvalOptionSchema().Emit(options,
                                 {fmt::format("bcot {}: fully resolved options (bcot {})", "eval", BcotVersion())});
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
