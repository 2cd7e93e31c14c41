#include "export_plan.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/annotation_poses.h"
#include "bcot/core/file_util.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"

namespace bcot::export_internal {
namespace {

namespace fs = std::filesystem;

bool IsWholeNumber(double value) { return std::abs(value - std::round(value)) < 1e-9; }

// Remap tables taking a distorted image of `camera` to the ideal pinhole image with the same K.
void UndistortMaps(const Camera& camera, cv::Mat1f* map_x, cv::Mat1f* map_y) {
  map_x->create(camera.height, camera.width);
  map_y->create(camera.height, camera.width);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector2d ideal((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy);
      const Eigen::Vector2d distorted = camera.Distort(ideal);
      (*map_x)(v, u) = static_cast<float>(camera.fx * distorted.x() + camera.cx);
      (*map_y)(v, u) = static_cast<float>(camera.fy * distorted.y() + camera.cy);
    }
  }
}

// The camera's poses from the annotation's one source of truth, rig_from_object.txt (so a hand
// edit of it is exported; the per-camera files are derived and never read back).
StatusOr<std::vector<Eigen::Isometry3d>> ReadCamFromObject(const std::string& annotation_dir,
                                                           const RigCamera& rig_camera) {
  BCOT_ASSIGN_OR_RETURN(const std::vector<Eigen::Isometry3d> rig_from_object,
                        ReadAnnotationPoses(annotation_dir));
  return CamFromObjectPoses(rig_camera.cam_from_rig, rig_from_object);
}

StatusOr<std::vector<int>> SelectFrames(const ExportOptions& options, int num_frames) {
  const int end = options.end_frame < 0 ? num_frames : options.end_frame;
  if (options.first_frame >= num_frames || end > num_frames) {
    return Status::InvalidConfig(fmt::format(
        "frames {}:{}: outside the sequence's {} frames (0:{})", options.first_frame,
        options.end_frame < 0 ? "" : std::to_string(options.end_frame), num_frames, num_frames));
  }
  std::vector<int> frames;
  for (int f = options.first_frame; f < end; f += options.frame_step) frames.push_back(f);
  return frames;
}

StatusOr<CameraPlan> PlanCamera(const Sequence& sequence, const std::string& annotation_dir,
                                const std::string& name, double image_scale) {
  CameraPlan plan;
  plan.index = sequence.rig.Find(name);
  if (plan.index < 0) {
    return Status::InvalidConfig(
        fmt::format("cameras: '{}' is not a camera of {}/rig.yaml", name, sequence.dir));
  }
  const RigCamera& rig_camera = sequence.rig[plan.index];
  plan.camera = rig_camera.camera;
  plan.cam_from_rig = rig_camera.cam_from_rig;
  const double w = plan.camera.width * image_scale, h = plan.camera.height * image_scale;
  if (!IsWholeNumber(w) || !IsWholeNumber(h) || std::lround(w) < 1 || std::lround(h) < 1) {
    return Status::InvalidConfig(fmt::format(
        "image_scale = {}: camera '{}' is {}x{}, scaled {}x{} is not a whole number of pixels",
        image_scale, name, plan.camera.width, plan.camera.height, w, h));
  }
  Camera pinhole = plan.camera;
  pinhole.distortion.fill(0.0);
  plan.exported = pinhole.Scaled(image_scale);
  BCOT_ASSIGN_OR_RETURN(plan.cam_from_object, ReadCamFromObject(annotation_dir, rig_camera));
  if (static_cast<int>(plan.cam_from_object.size()) != sequence.num_frames) {
    return Status::InvalidInput(
        fmt::format("{}: annotation has {} poses, the sequence has {} frames", annotation_dir,
                    plan.cam_from_object.size(), sequence.num_frames));
  }
  return plan;
}

}  // namespace

std::string FolderNameProblem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return "is not a folder name";
  if (name.find('/') != std::string::npos || name.find('\\') != std::string::npos) {
    return "must not contain '/' or '\\'";
  }
  return "";
}

StatusOr<ExportPlan> PlanExport(const std::string& sequence_dir, const std::string& annotation_dir,
                                const ExportOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  ExportPlan plan;
  BCOT_ASSIGN_OR_RETURN(plan.sequence, LoadSequence(sequence_dir, /*require_init_pose=*/false));
  BCOT_ASSIGN_OR_RETURN(plan.frames, SelectFrames(options, plan.sequence.num_frames));
  std::vector<std::string> names = options.cameras;
  if (names.empty()) {
    for (const RigCamera& camera : plan.sequence.rig.cameras()) names.push_back(camera.camera.name);
  }
  for (const std::string& name : names) {
    BCOT_ASSIGN_OR_RETURN(CameraPlan camera,
                          PlanCamera(plan.sequence, annotation_dir, name, options.image_scale));
    plan.cameras.push_back(std::move(camera));
  }
  return plan;
}

ExportSummary SummarizePlan(const ExportPlan& plan, const ExportOptions& options) {
  ExportSummary summary;
  for (const CameraPlan& camera : plan.cameras) {
    summary.cameras.push_back(camera.camera.name);
    summary.undistorted = summary.undistorted || camera.camera.HasDistortion();
  }
  summary.rig_cameras = plan.sequence.rig.size();
  summary.frames = plan.frames;
  summary.sequence_frames = plan.sequence.num_frames;
  summary.frame_step = options.frame_step;
  summary.width = plan.cameras[0].exported.width;
  summary.height = plan.cameras[0].exported.height;
  summary.source_width = plan.cameras[0].camera.width;
  summary.source_height = plan.cameras[0].camera.height;
  return summary;
}

FrameConverter::FrameConverter(const CameraPlan& camera)
    : camera_(camera.camera),
      out_size_(camera.exported.width, camera.exported.height),
      resize_(out_size_ != cv::Size(camera.camera.width, camera.camera.height)) {
  if (camera_.HasDistortion()) UndistortMaps(camera_, &map_x_, &map_y_);
}

StatusOr<cv::Mat> FrameConverter::Convert(const std::string& path) const {
  BCOT_ASSIGN_OR_RETURN(const cv::Mat3b read, ReadCameraImage(path, camera_));
  cv::Mat image = read;
  if (!map_x_.empty()) {
    cv::Mat undistorted;
    cv::remap(image, undistorted, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    image = undistorted;
  }
  if (resize_) {
    cv::Mat resized;
    cv::resize(image, resized, out_size_, 0, 0, cv::INTER_AREA);
    image = resized;
  }
  return image;
}

StatusOr<std::string> EncodeImage(const cv::Mat& image, const std::string& extension,
                                  const std::string& source) {
  std::vector<uchar> bytes;
  std::vector<int> parameters;
  if (extension != ".png") parameters = {cv::IMWRITE_JPEG_QUALITY, 95};
  if (!cv::imencode(extension, image, bytes, parameters)) {
    return Status::Internal(fmt::format("{}: {} encoding failed", source, extension));
  }
  return std::string(bytes.begin(), bytes.end());
}

Status ForEachIndex(size_t count, const std::function<Status(size_t)>& task) {
  std::vector<Status> statuses(count);
  tbb::parallel_for(size_t{0}, count, [&](size_t i) { statuses[i] = task(i); });
  for (const Status& status : statuses) BCOT_RETURN_IF_ERROR(status);
  return Status::Ok();
}

Status PrepareEmptyFolder(const fs::path& dir, bool overwrite) {
  std::error_code error;
  if (fs::exists(dir, error) && !fs::is_empty(dir, error)) {
    if (!overwrite) {
      return Status::InvalidConfig(
          fmt::format("{}: exists and is not empty; pass --overwrite to replace it", dir.string()));
    }
    fs::remove_all(dir, error);
    if (error) {
      return Status::IoError(fmt::format("{}: cannot remove: {}", dir.string(), error.message()));
    }
  }
  return CreateDirectories(dir.string());
}

}  // namespace bcot::export_internal
