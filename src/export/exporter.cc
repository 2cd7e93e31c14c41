#include "bcot/export/exporter.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/camera.h"
#include "bcot/core/file_util.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/core/yaml_util.h"
#include "bcot/eval/bcot_layout.h"
#include "bcot/render/mesh.h"
#include "bcot/render/mesh_writer.h"
#include "bcot/core/version.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

// Empty when `name` can be one folder / file-name component.
std::string FolderNameProblem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return "is not a folder name";
  if (name.find('/') != std::string::npos || name.find('\\') != std::string::npos) {
    return "must not contain '/' or '\\'";
  }
  return "";
}

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

StatusOr<std::vector<Eigen::Isometry3d>> ReadCamFromObject(const std::string& annotation_dir,
                                                           const RigCamera& rig_camera) {
  const fs::path per_camera = fs::path(annotation_dir) / rig_camera.camera.name / "pose.txt";
  std::error_code error;
  if (fs::exists(per_camera, error)) return ReadPoseFile(per_camera.string());
  const fs::path rig_path = fs::path(annotation_dir) / "rig_from_object.txt";
  if (!fs::exists(rig_path, error)) {
    return Status::NotFound(
        fmt::format("{}: annotation not found (nor {})", rig_path.string(), per_camera.string()));
  }
  BCOT_ASSIGN_OR_RETURN(std::vector<Eigen::Isometry3d> poses, ReadPoseFile(rig_path.string()));
  for (Eigen::Isometry3d& pose : poses) pose = rig_camera.cam_from_rig * pose;
  return poses;
}

struct CameraExport {
  int index = 0;
  std::string scene;
  Camera camera;    // as in rig.yaml
  Camera exported;  // undistorted and scaled
  std::vector<Eigen::Isometry3d> cam_from_object;
  std::string pose_source;
};

}  // namespace

namespace {

// The rule a folder-name option breaks, or "" (an empty name keeps the default).
std::string FolderNameRule(const std::string& name) {
  const std::string problem = name.empty() ? "" : FolderNameProblem(name);
  return problem.empty() ? "" : "must be a folder name (it " + problem + ")";
}

OptionSchema<ExportOptions>* BuildExportOptionSchema() {
  auto* s = new OptionSchema<ExportOptions>();
  s->Add(
       "frame_step", [](auto& o) -> auto& { return o.frame_step; }, "frames",
       "keep every n-th frame (60 -> 30 fps: 2)")
      .Range(Closed(1, 1000));
  s->Add(
       "image_scale", [](auto& o) -> auto& { return o.image_scale; }, "",
       "image scale factor (1280x1024 -> 640x512: 0.5); K follows Camera::Scaled")
      .Range(LeftOpen(0, 1));
  s->Add(
       "cameras", [](auto& o) -> auto& { return o.cameras; }, "",
       "rig cameras to export; [] = the first only (indoor), outdoor: <scene>_<camera> each")
      .Check([](const ExportOptions& o) -> std::string {
        for (size_t i = 0; i < o.cameras.size(); ++i) {
          if (o.cameras[i].empty()) return fmt::format("must not hold an empty name ([{}])", i);
          for (size_t j = 0; j < i; ++j) {
            if (o.cameras[i] == o.cameras[j]) {
              return fmt::format("must not list '{}' twice (cameras[{}] repeats cameras[{}])",
                                 o.cameras[i], i, j);
            }
          }
        }
        return "";
      });
  s->Add(
       "scene", [](auto& o) -> auto& { return o.scene; }, "",
       "scene folder name; \"\" = the sequence folder's name")
      .Check([](const ExportOptions& o) { return FolderNameRule(o.scene); });
  s->Add(
       "object", [](auto& o) -> auto& { return o.object; }, "",
       "object name (model file and folder); \"\" = object.yaml's name")
      .Check([](const ExportOptions& o) { return FolderNameRule(o.object); });
  s->Add(
      "overwrite", [](auto& o) -> auto& { return o.overwrite; }, "",
      "replace an existing non-empty <scene>/<Object> folder");
  return s;
}

}  // namespace

const OptionSchema<ExportOptions>& ExportOptionSchema() {
  static const OptionSchema<ExportOptions>* const schema = BuildExportOptionSchema();
  return *schema;
}

Status ExportOptions::Validate() const { return ExportOptionSchema().Validate(*this, nullptr); }

StatusOr<ExportOptions> ReadExportOptions(const std::string& path,
                                          const std::vector<std::string>& overrides) {
  return ExportOptionSchema().Read(path, overrides);
}

std::string FormatExportOptions(const ExportOptions& options) {
  return ExportOptionSchema().Emit(options,
                                   {fmt::format("bcot {}: fully resolved options (bcot {})", "export", BcotVersion())});
}

StatusOr<ExportSummary> ExportToBcot(const std::string& sequence_dir,
                                     const std::string& annotation_dir, const std::string& out_root,
                                     const ExportOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_ASSIGN_OR_RETURN(const Sequence sequence,
                        LoadSequence(sequence_dir, /*require_init_pose=*/false));
  const std::string object = options.object.empty() ? sequence.object.name : options.object;
  if (!FolderNameProblem(object).empty()) {
    return Status::InvalidInput(
        fmt::format("{}/object.yaml: name '{}' {}; set the export option "
                    "`object`",
                    sequence_dir, object, FolderNameProblem(object)));
  }
  std::string scene = options.scene;
  if (scene.empty()) {
    fs::path dir = fs::path(sequence_dir).lexically_normal();
    if (dir.filename().empty()) dir = dir.parent_path();
    scene = fs::absolute(dir).filename().string();
  }

  // Which cameras, and everything about them, before writing anything.
  std::vector<std::string> names = options.cameras;
  if (names.empty()) names.push_back(sequence.rig[0].camera.name);
  std::vector<CameraExport> exports;
  for (const std::string& name : names) {
    CameraExport e;
    e.index = sequence.rig.Find(name);
    if (e.index < 0) {
      return Status::InvalidConfig(
          fmt::format("cameras: '{}' is not a camera of {}/rig.yaml", name, sequence_dir));
    }
    e.scene = names.size() > 1 ? scene + "_" + name : scene;
    e.camera = sequence.rig[e.index].camera;
    const double w = e.camera.width * options.image_scale,
                 h = e.camera.height * options.image_scale;
    if (!IsWholeNumber(w) || !IsWholeNumber(h) || std::lround(w) < 1 || std::lround(h) < 1) {
      return Status::InvalidConfig(fmt::format(
          "image_scale = {}: camera '{}' is {}x{}, scaled {}x{} is not a whole number of pixels",
          options.image_scale, name, e.camera.width, e.camera.height, w, h));
    }
    Camera pinhole = e.camera;
    pinhole.distortion.fill(0.0);
    e.exported = pinhole.Scaled(options.image_scale);
    BCOT_ASSIGN_OR_RETURN(e.cam_from_object,
                          ReadCamFromObject(annotation_dir, sequence.rig[e.index]));
    if (static_cast<int>(e.cam_from_object.size()) != sequence.num_frames) {
      return Status::InvalidInput(
          fmt::format("{}: annotation has {} poses, the sequence has {} frames", annotation_dir,
                      e.cam_from_object.size(), sequence.num_frames));
    }
    exports.push_back(std::move(e));
  }
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));

  ExportSummary summary;
  for (const CameraExport& e : exports) {
    const fs::path scene_dir = fs::path(out_root) / e.scene;
    const fs::path object_dir = scene_dir / object;
    const std::string k_text = FormatBcotIntrinsics(e.exported);
    const std::string k_path = (scene_dir / "K.txt").string();
    std::error_code error;
    if (fs::exists(k_path, error)) {
      BCOT_ASSIGN_OR_RETURN(const std::string existing, ReadTextFile(k_path));
      if (existing != k_text) {
        return Status::InvalidInput(fmt::format(
            "{}: holds other intrinsics than camera '{}' of {} ({}); export to another scene",
            k_path, e.camera.name, sequence_dir, TrimWhitespace(k_text)));
      }
    }
    if (fs::exists(object_dir, error) && !fs::is_empty(object_dir, error)) {
      if (!options.overwrite) {
        return Status::InvalidConfig(fmt::format(
            "{}: exists and is not empty; set overwrite to replace it", object_dir.string()));
      }
      fs::remove_all(object_dir, error);
      if (error) {
        return Status::IoError(
            fmt::format("{}: cannot remove: {}", object_dir.string(), error.message()));
      }
    }
    BCOT_RETURN_IF_ERROR(CreateDirectories(object_dir.string()));

    cv::Mat1f map_x, map_y;
    if (e.camera.HasDistortion()) {
      UndistortMaps(e.camera, &map_x, &map_y);
      summary.undistorted = true;
    }
    std::vector<int> frames;
    for (int f = 0; f < sequence.num_frames; f += options.frame_step) frames.push_back(f);
    std::vector<Status> statuses(frames.size());
    const cv::Size out_size(e.exported.width, e.exported.height);
    tbb::parallel_for(size_t{0}, frames.size(), [&](size_t i) {
      const std::string& path = sequence.image_paths[e.index][frames[i]];
      StatusOr<cv::Mat3b> read = ReadCameraImage(path, e.camera);
      if (!read.ok()) {
        statuses[i] = read.status();
        return;
      }
      cv::Mat image = *read;
      if (!map_x.empty()) {
        cv::Mat undistorted;
        cv::remap(image, undistorted, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
        image = undistorted;
      }
      if (out_size != image.size()) {
        cv::Mat resized;
        cv::resize(image, resized, out_size, 0, 0, cv::INTER_AREA);
        image = resized;
      }
      std::vector<uchar> png;
      if (!cv::imencode(".png", image, png)) {
        statuses[i] = Status::Internal(fmt::format("{}: PNG encoding failed", path));
        return;
      }
      statuses[i] = WriteFileAtomic((object_dir / fmt::format("{:04d}.png", i)).string(),
                                    std::string(png.begin(), png.end()));
    });
    for (const Status& status : statuses) BCOT_RETURN_IF_ERROR(status);

    std::vector<Eigen::Isometry3d> poses;
    for (int f : frames) poses.push_back(e.cam_from_object[f]);
    BCOT_RETURN_IF_ERROR(WritePoseFile((object_dir / "pose.txt").string(), poses));
    BCOT_RETURN_IF_ERROR(WriteFileAtomic(k_path, k_text));
    summary.scene_dirs.push_back(scene_dir.string());
    summary.frames_per_camera = static_cast<int>(frames.size());
  }
  summary.model_path = BcotModelPath(out_root, object);
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(
      summary.model_path,
      FormatObjMesh(mesh, fmt::format("{}: written by bcot export (bcot {}), units mm, object "
                                      "template frame\n{} vertices, {} triangles",
                                      object, BcotVersion(), mesh.vertices().size(),
                                      mesh.triangles().size()))));
  summary.width = exports[0].exported.width;
  summary.height = exports[0].exported.height;
  return summary;
}

}  // namespace bcot
