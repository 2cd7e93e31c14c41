#include "bcot/export/exporter.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "bcot/core/camera.h"
#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/core/version.h"
#include "bcot/core/yaml_util.h"
#include "bcot/eval/bcot_layout.h"
#include "bcot/export/bop_writer.h"
#include "bcot/render/mesh.h"
#include "bcot/render/mesh_writer.h"
#include "export_plan.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;
using export_internal::CameraPlan;
using export_internal::ExportPlan;
using export_internal::FolderNameProblem;

// The rule a folder-name option breaks, or "" (an empty name keeps the default).
std::string FolderNameRule(const std::string& name) {
  const std::string problem = name.empty() ? "" : FolderNameProblem(name);
  return problem.empty() ? "" : "must be a folder name (it " + problem + ")";
}

OptionSchema<ExportOptions>* BuildExportOptionSchema() {
  auto* s = new OptionSchema<ExportOptions>();
  s->AddChoice(
      "format", [](auto& o) -> auto& { return o.format; },
      std::vector<std::pair<std::string, ExportFormat>>{{"bcot", ExportFormat::kBcot},
                                                        {"bop", ExportFormat::kBop}},
      "dataset layout: the BCOT release or BOP (docs/export.md)");
  s->Add(
       "frame_step", [](auto& o) -> auto& { return o.frame_step; }, "frames",
       "keep every n-th frame (60 -> 30 fps: 2)")
      .Range(Closed(1, 1000));
  s->Add(
       "first_frame", [](auto& o) -> auto& { return o.first_frame; }, "frames",
       "first exported frame (0-based)")
      .Range(AtLeast(0));
  s->Add(
       "end_frame", [](auto& o) -> auto& { return o.end_frame; }, "frames",
       "the frame after the last exported one; -1 = to the end")
      .Range(AtLeast(-1))
      .Check([](const ExportOptions& o) -> std::string {
        if (o.end_frame < 0 || o.end_frame > o.first_frame) return "";
        return fmt::format("must be -1 or > first_frame ({})", o.first_frame);
      });
  s->Add(
       "image_scale", [](auto& o) -> auto& { return o.image_scale; }, "",
       "image scale factor (1280x1024 -> 640x512: 0.5); K follows Camera::Scaled")
      .Range(LeftOpen(0, 1));
  s->Add(
       "cameras", [](auto& o) -> auto& { return o.cameras; }, "",
       "rig cameras to export; [] = every camera of the rig")
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
      "replace an existing non-empty output folder (bcot: <scene>/<Object>, bop: the scene)");
  s->Add(
       "bop.split", [](auto& o) -> auto& { return o.bop.split; }, "",
       "bop: split folder (test, val, train, optionally with a _TYPE suffix)")
      .Check([](const ExportOptions& o) {
        return o.bop.split.empty() ? "must be a folder name (it is empty)"
                                   : FolderNameRule(o.bop.split);
      });
  s->Add(
       "bop.scene_id", [](auto& o) -> auto& { return o.bop.scene_id; }, "",
       "bop: scene id, folder <split>/<6 digits>")
      .Range(Closed(0, 999999));
  s->Add(
       "bop.obj_id", [](auto& o) -> auto& { return o.bop.obj_id; }, "",
       "bop: object id, models/obj_<6 digits>.ply")
      .Range(Closed(1, 999999));
  s->Add(
      "bop.symmetries_continuous", [](auto& o) -> auto& { return o.bop.symmetries_continuous; }, "",
      "bop: list a body of revolution's axis in models_info.json (symmetries_continuous)");
  return s;
}

}  // namespace

const OptionSchema<ExportOptions>& ExportOptionSchema() {
  static const OptionSchema<ExportOptions>* const schema = BuildExportOptionSchema();
  return *schema;
}

Status ExportOptions::Validate() const { return ExportOptionSchema().Validate(*this, nullptr); }

StatusOr<ExportOptions> ExportPreset(const std::string& name) {
  ExportOptions options;
  if (name.empty()) return options;
  if (name == "bcot-release") {
    options.frame_step = 2;
    options.image_scale = 0.5;
    return options;
  }
  return Status::InvalidConfig(fmt::format("--preset '{}': unknown preset; known: {}", name,
                                           fmt::join(ExportPresetNames(), ", ")));
}

const std::vector<std::string>& ExportPresetNames() {
  static const std::vector<std::string>* const names = new std::vector<std::string>{"bcot-release"};
  return *names;
}

StatusOr<ExportOptions> ReadExportOptions(const std::string& path,
                                          const std::vector<std::string>& overrides,
                                          const ExportOptions& base) {
  return ExportOptionSchema().ReadOnto(base, path, overrides);
}

std::string FormatExportOptions(const ExportOptions& options) {
  return ExportOptionSchema().Emit(
      options, {fmt::format("bcot {}: fully resolved options (bcot {})", "export", BcotVersion())});
}

std::string DescribeExport(const ExportSummary& summary, ExportFormat format) {
  const int count = static_cast<int>(summary.frames.size());
  const std::string rate = summary.frame_step == 1
                               ? "full rate"
                               : fmt::format("1/{} of the frame rate", summary.frame_step);
  const bool full =
      summary.width == summary.source_width && summary.height == summary.source_height;
  const std::string resolution =
      full ? "full resolution"
           : fmt::format("scaled from {}x{}", summary.source_width, summary.source_height);
  return fmt::format(
      "{} format: {} of {} frames ({}..{}, step {}, {}), camera{} {} ({} of {}), {}x{} ({}{}) -> "
      "{}",
      format == ExportFormat::kBop ? "bop" : "bcot", count, summary.sequence_frames,
      summary.frames.front(), summary.frames.back(), summary.frame_step, rate,
      summary.cameras.size() > 1 ? "s" : "", fmt::join(summary.cameras, ","),
      summary.cameras.size(), summary.rig_cameras, summary.width, summary.height, resolution,
      summary.undistorted ? ", undistorted" : "", fmt::join(summary.scene_dirs, ", "));
}

StatusOr<ExportSummary> ExportToBcot(const std::string& sequence_dir,
                                     const std::string& annotation_dir, const std::string& out_root,
                                     const ExportOptions& options) {
  BCOT_ASSIGN_OR_RETURN(const ExportPlan plan,
                        export_internal::PlanExport(sequence_dir, annotation_dir, options));
  const Sequence& sequence = plan.sequence;
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
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));

  ExportSummary summary = export_internal::SummarizePlan(plan, options);
  for (const CameraPlan& camera : plan.cameras) {
    const fs::path scene_dir =
        fs::path(out_root) / (plan.cameras.size() > 1 ? scene + "_" + camera.camera.name : scene);
    const fs::path object_dir = scene_dir / object;
    const std::string k_text = FormatBcotIntrinsics(camera.exported);
    const std::string k_path = (scene_dir / "K.txt").string();
    std::error_code error;
    if (fs::exists(k_path, error)) {
      BCOT_ASSIGN_OR_RETURN(const std::string existing, ReadTextFile(k_path));
      if (existing != k_text) {
        return Status::InvalidInput(fmt::format(
            "{}: holds other intrinsics than camera '{}' of {} ({}); export to another scene",
            k_path, camera.camera.name, sequence_dir, TrimWhitespace(k_text)));
      }
    }
    BCOT_RETURN_IF_ERROR(export_internal::PrepareEmptyFolder(object_dir, options.overwrite));

    const export_internal::FrameConverter converter(camera);
    BCOT_RETURN_IF_ERROR(export_internal::ForEachIndex(plan.frames.size(), [&](size_t i) {
      const std::string& path = sequence.image_paths[camera.index][plan.frames[i]];
      BCOT_ASSIGN_OR_RETURN(const cv::Mat image, converter.Convert(path));
      BCOT_ASSIGN_OR_RETURN(const std::string png,
                            export_internal::EncodeImage(image, ".png", path));
      return WriteFileAtomic((object_dir / fmt::format("{:04d}.png", i)).string(), png);
    }));

    std::vector<Eigen::Isometry3d> poses;
    for (int f : plan.frames) poses.push_back(camera.cam_from_object[f]);
    BCOT_RETURN_IF_ERROR(WritePoseFile((object_dir / "pose.txt").string(), poses));
    BCOT_RETURN_IF_ERROR(WriteFileAtomic(k_path, k_text));
    summary.scene_dirs.push_back(scene_dir.string());
  }
  summary.model_path = BcotModelPath(out_root, object);
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(
      summary.model_path,
      FormatObjMesh(mesh, fmt::format("{}: written by bcot export (bcot {}), units mm, object "
                                      "template frame\n{} vertices, {} triangles",
                                      object, BcotVersion(), mesh.vertices().size(),
                                      mesh.triangles().size()))));
  return summary;
}

StatusOr<ExportSummary> ExportAnnotation(const std::string& sequence_dir,
                                         const std::string& annotation_dir,
                                         const std::string& out_root,
                                         const ExportOptions& options) {
  if (options.format == ExportFormat::kBop) {
    return ExportToBop(sequence_dir, annotation_dir, out_root, options);
  }
  return ExportToBcot(sequence_dir, annotation_dir, out_root, options);
}

}  // namespace bcot
