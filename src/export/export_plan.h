// What both export formats share (internal to the export layer): resolving the options against
// a sequence and its annotation into a plan (cameras, their exported pinhole intrinsics, poses,
// frames), converting one frame image to the exported camera, and preparing output folders.
// Nothing is written before the plan is complete, so option and input errors leave no output.
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/export/exporter.h"

namespace bcot::export_internal {

// Empty when `name` can be one folder / file-name component, else what is wrong with it.
std::string FolderNameProblem(const std::string& name);

struct CameraPlan {
  int index = 0;    // in rig.yaml
  Camera camera;    // as in rig.yaml
  Camera exported;  // undistorted (pinhole, same K) and scaled by image_scale
  Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Isometry3d> cam_from_object;  // every frame of the sequence, mm
};

struct ExportPlan {
  Sequence sequence;
  std::vector<CameraPlan> cameras;
  std::vector<int> frames;  // exported frames (sequence indices), increasing
};

// Loads the sequence and the annotation's poses and checks the options against them: camera
// names, frame range, whole-pixel scaled sizes. An empty options.cameras means every camera of
// the rig.
StatusOr<ExportPlan> PlanExport(const std::string& sequence_dir, const std::string& annotation_dir,
                                const ExportOptions& options);

// The summary fields every format fills the same way (cameras, frames, sizes).
ExportSummary SummarizePlan(const ExportPlan& plan, const ExportOptions& options);

// Converts the images of one camera to its exported camera (undistortion, then scaling).
// Thread safety: Convert is const and may run concurrently.
class FrameConverter {
 public:
  explicit FrameConverter(const CameraPlan& camera);
  // True when the exported image equals the input (no distortion, scale 1).
  bool IsIdentity() const { return map_x_.empty() && !resize_; }
  // Reads `path` (checked against the rig camera) and returns the exported image.
  StatusOr<cv::Mat> Convert(const std::string& path) const;

 private:
  Camera camera_;
  cv::Size out_size_;
  bool resize_ = false;
  cv::Mat1f map_x_, map_y_;  // empty without distortion
};

// `image` encoded for a file with extension `extension` (".png", ".jpg"); `source` names the
// frame in the error message.
StatusOr<std::string> EncodeImage(const cv::Mat& image, const std::string& extension,
                                  const std::string& source);

// Runs `task(i)` for i in [0, count) in parallel; the first error in index order, else OK.
Status ForEachIndex(size_t count, const std::function<Status(size_t)>& task);

// Makes `dir` exist and be empty: an existing non-empty folder is kInvalidConfig unless
// `overwrite` (then removed first).
Status PrepareEmptyFolder(const std::filesystem::path& dir, bool overwrite);

}  // namespace bcot::export_internal
