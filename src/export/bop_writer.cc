#include "bcot/export/bop_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/version.h"
#include "bcot/render/mesh_writer.h"
#include "bcot/render/symmetry_detection.h"
#include "export_plan.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;
using export_internal::CameraPlan;
using export_internal::ExportPlan;
using Json = nlohmann::ordered_json;

// Row-major entries of a 3×3 matrix, and the entries of a 3-vector.
std::vector<double> RowMajor(const Eigen::Matrix3d& m) {
  std::vector<double> values;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) values.push_back(m(r, c));
  }
  return values;
}
std::vector<double> Entries(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// A BOP per-image file: an object keyed by image id ("0", "1", …), one image per line.
std::string FormatPerImageJson(const std::vector<Json>& per_image) {
  std::string text = "{\n";
  for (size_t i = 0; i < per_image.size(); ++i) {
    text += fmt::format("  \"{}\": {}{}\n", i, per_image[i].dump(),
                        i + 1 < per_image.size() ? "," : "");
  }
  return text + "}\n";
}

// [x, y, max_x − min_x, max_y − min_y] of the non-zero pixels of `mask`, shifted by `offset`;
// [−1, −1, −1, −1] when there are none.
std::array<int, 4> BoundingBox(const cv::Mat1b& mask, const cv::Point& offset) {
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return {-1, -1, -1, -1};
  return {box.x + offset.x, box.y + offset.y, box.width - 1, box.height - 1};
}

// The region bop_toolkit renders to count the whole silhouette (3× the image, centred on it),
// narrowed to the projected bounding box of the mesh when that lies in front of the camera.
cv::Rect CanvasRoi(const RayCaster& caster, const Camera& camera,
                   const Eigen::Isometry3d& cam_from_object) {
  const cv::Rect canvas(-camera.width, -camera.height, 3 * camera.width, 3 * camera.height);
  const Mesh& mesh = caster.mesh();
  double u_min = 1e300, v_min = 1e300, u_max = -1e300, v_max = -1e300;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p(corner & 1 ? mesh.bbox_max().x() : mesh.bbox_min().x(),
                            corner & 2 ? mesh.bbox_max().y() : mesh.bbox_min().y(),
                            corner & 4 ? mesh.bbox_max().z() : mesh.bbox_min().z());
    const Eigen::Vector3d p_in_cam = cam_from_object * p;
    if (p_in_cam.z() <= 1e-3) return canvas;
    const Eigen::Vector2d pixel = camera.Project(p_in_cam);
    u_min = std::min(u_min, pixel.x());
    v_min = std::min(v_min, pixel.y());
    u_max = std::max(u_max, pixel.x());
    v_max = std::max(v_max, pixel.y());
  }
  const auto clamp = [](double value) { return static_cast<int>(std::clamp(value, -1e7, 1e7)); };
  const cv::Rect box(cv::Point(clamp(std::floor(u_min)) - 1, clamp(std::floor(v_min)) - 1),
                     cv::Point(clamp(std::ceil(u_max)) + 2, clamp(std::ceil(v_max)) + 2));
  return box & canvas;
}

// Pairwise maximum distance, exact: with r_i the distance to the centroid (sorted decreasing),
// |v_i − v_j| <= r_i + r_j, so the pairs that could beat the best so far are few.
double MaxVertexDistance(const std::vector<Eigen::Vector3f>& vertices) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& v : vertices) centroid += v.cast<double>();
  centroid /= std::max<size_t>(1, vertices.size());
  std::vector<std::pair<double, Eigen::Vector3d>> by_radius;
  for (const Eigen::Vector3f& v : vertices) {
    by_radius.emplace_back((v.cast<double>() - centroid).norm(), v.cast<double>());
  }
  std::sort(by_radius.begin(), by_radius.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  double best = 0.0;
  for (size_t i = 0; i < by_radius.size(); ++i) {
    if (2.0 * by_radius[i].first <= best) break;
    for (size_t j = i + 1; j < by_radius.size(); ++j) {
      if (by_radius[i].first + by_radius[j].first <= best) break;
      best = std::max(best, (by_radius[i].second - by_radius[j].second).norm());
    }
  }
  return best;
}

Json ModelInfoJson(const BopModelInfo& info) {
  Json json{{"diameter", info.diameter}, {"min_x", info.min.x()},   {"min_y", info.min.y()},
            {"min_z", info.min.z()},     {"size_x", info.size.x()}, {"size_y", info.size.y()},
            {"size_z", info.size.z()}};
  if (info.symmetry.has_value()) {
    const Eigen::Vector3d& a = info.symmetry->axis;
    const Eigen::Vector3d& p = info.symmetry->point;
    json["symmetries_continuous"] =
        Json::array({Json{{"axis", {a.x(), a.y(), a.z()}}, {"offset", {p.x(), p.y(), p.z()}}}});
  }
  return json;
}

// models/obj_<OBJ>.ply (the mesh in BOP's model frame) and its entry in models_info.json,
// keeping the entries of other objects.
Status WriteModel(const fs::path& models_dir, int obj_id, const Mesh& model,
                  bool symmetries_continuous, bool overwrite, std::string* model_path) {
  *model_path = (models_dir / fmt::format("obj_{:06d}.ply", obj_id)).string();
  const std::string ply = FormatPlyMesh(
      model, fmt::format("written by bcot export (bcot {}), units mm, origin at the "
                         "bounding-box centre\n{} vertices, {} triangles",
                         BcotVersion(), model.vertices().size(), model.triangles().size()));
  std::error_code error;
  if (fs::exists(*model_path, error) && !overwrite) {
    BCOT_ASSIGN_OR_RETURN(const std::string existing, ReadTextFile(*model_path));
    if (existing != ply) {
      return Status::InvalidConfig(fmt::format(
          "{}: holds another model; set bop.obj_id to a free id or pass --overwrite", *model_path));
    }
  }
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(*model_path, ply));

  const std::string info_path = (models_dir / "models_info.json").string();
  Json infos = Json::object();
  if (fs::exists(info_path, error)) {
    BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(info_path));
    infos = Json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (infos.is_discarded() || !infos.is_object()) {
      return Status::InvalidInput(info_path + ": not a JSON object (BOP models_info.json)");
    }
  }
  BopModelInfo info = ComputeBopModelInfo(model);
  if (symmetries_continuous) {
    BCOT_ASSIGN_OR_RETURN(info.symmetry,
                          DetectRotationalSymmetry(RayCaster(model), SymmetryDetectionOptions()));
  }
  infos[std::to_string(obj_id)] = ModelInfoJson(info);
  return WriteFileAtomic(info_path, infos.dump(2) + "\n");
}

// ".png" or ".jpg", by the extension of a sequence frame.
std::string ImageExtension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".png" ? ".png" : ".jpg";
}

// The per-image JSON entries of one camera.
struct CameraFiles {
  std::vector<Json> scene_camera, scene_gt, scene_gt_info;
};

// rgb, mask and mask_visib images of one camera and its JSON entries. `caster` holds the mesh
// in the template frame O_t (the frame of camera.cam_from_object).
Status WriteCameraImages(const ExportPlan& plan, const CameraPlan& camera, const RayCaster& caster,
                         const Eigen::Isometry3d& objcentre_from_template, int obj_id,
                         const fs::path& scene_dir, const std::string& suffix, CameraFiles* files) {
  const export_internal::FrameConverter converter(camera);
  const size_t count = plan.frames.size();
  std::vector<BopGtInfo> infos(count);
  BCOT_RETURN_IF_ERROR(export_internal::ForEachIndex(count, [&](size_t i) -> Status {
    const std::string& path = plan.sequence.image_paths[camera.index][plan.frames[i]];
    const std::string extension = ImageExtension(path);
    std::string bytes;
    if (converter.IsIdentity()) {
      BCOT_RETURN_IF_ERROR(converter.Convert(path).status());  // checks size and integrity
      BCOT_ASSIGN_OR_RETURN(bytes, ReadTextFile(path));
    } else {
      BCOT_ASSIGN_OR_RETURN(const cv::Mat image, converter.Convert(path));
      BCOT_ASSIGN_OR_RETURN(bytes, export_internal::EncodeImage(image, extension, path));
    }
    BCOT_RETURN_IF_ERROR(WriteFileAtomic(
        (scene_dir / ("rgb" + suffix) / fmt::format("{:06d}{}", i, extension)).string(), bytes));
    cv::Mat1b mask;
    infos[i] =
        RenderBopMask(caster, camera.exported, camera.cam_from_object[plan.frames[i]], &mask);
    BCOT_ASSIGN_OR_RETURN(const std::string png, export_internal::EncodeImage(mask, ".png", path));
    const std::string name = fmt::format("{:06d}_{:06d}.png", i, 0);
    BCOT_RETURN_IF_ERROR(WriteFileAtomic((scene_dir / ("mask" + suffix) / name).string(), png));
    return WriteFileAtomic((scene_dir / ("mask_visib" + suffix) / name).string(), png);
  }));

  const Eigen::Isometry3d& cam_from_rig = camera.cam_from_rig;
  for (size_t i = 0; i < count; ++i) {
    files->scene_camera.push_back(Json{{"cam_K", RowMajor(camera.exported.K())},
                                       {"cam_R_w2c", RowMajor(cam_from_rig.linear())},
                                       {"cam_t_w2c", Entries(cam_from_rig.translation())}});
    const Eigen::Isometry3d cam_from_objcentre =
        camera.cam_from_object[plan.frames[i]] * objcentre_from_template.inverse();
    files->scene_gt.push_back(
        Json::array({Json{{"obj_id", obj_id},
                          {"cam_R_m2c", RowMajor(cam_from_objcentre.linear())},
                          {"cam_t_m2c", Entries(cam_from_objcentre.translation())}}}));
    const BopGtInfo& info = infos[i];
    files->scene_gt_info.push_back(Json::array({Json{{"bbox_obj", info.bbox_obj},
                                                     {"bbox_visib", info.bbox_visib},
                                                     {"px_count_all", info.px_count_all},
                                                     {"px_count_valid", info.px_count_valid},
                                                     {"px_count_visib", info.px_count_visib},
                                                     {"visib_fract", info.visib_fract}}}));
  }
  return Status::Ok();
}

}  // namespace

BopModelInfo ComputeBopModelInfo(const Mesh& mesh) {
  BopModelInfo info;
  info.diameter = MaxVertexDistance(mesh.vertices());
  info.min = mesh.bbox_min();
  info.size = mesh.bbox_max() - mesh.bbox_min();
  return info;
}

BopGtInfo RenderBopMask(const RayCaster& caster, const Camera& camera,
                        const Eigen::Isometry3d& cam_from_object, cv::Mat1b* mask) {
  BopGtInfo info;
  *mask = cv::Mat1b::zeros(camera.height, camera.width);
  RenderOptions options;
  options.roi = CanvasRoi(caster, camera, cam_from_object);
  options.depth = options.normal_in_cam = options.point_in_object = options.triangle_id = false;
  if (options.roi.empty()) return info;
  const RenderedView view = caster.Render(camera, cam_from_object, options);
  const cv::Rect image(0, 0, camera.width, camera.height);
  const cv::Rect visible = options.roi & image;
  if (!visible.empty()) {
    view.mask(visible - options.roi.tl()).copyTo((*mask)(visible));
  }
  info.px_count_all = cv::countNonZero(view.mask);
  info.px_count_visib = cv::countNonZero(*mask);
  if (info.px_count_visib > 0) {
    info.bbox_obj = BoundingBox(view.mask, options.roi.tl());
    info.bbox_visib = BoundingBox(*mask, cv::Point(0, 0));
  }
  info.visib_fract =
      info.px_count_all > 0 ? static_cast<double>(info.px_count_visib) / info.px_count_all : 0.0;
  return info;
}

StatusOr<ExportSummary> ExportToBop(const std::string& sequence_dir,
                                    const std::string& annotation_dir, const std::string& out_root,
                                    const ExportOptions& options) {
  BCOT_ASSIGN_OR_RETURN(const ExportPlan plan,
                        export_internal::PlanExport(sequence_dir, annotation_dir, options));
  const bool suffixed = plan.cameras.size() > 1;
  for (const CameraPlan& camera : plan.cameras) {
    const std::string problem = export_internal::FolderNameProblem(camera.camera.name);
    if (suffixed && !problem.empty()) {
      return Status::InvalidInput(
          fmt::format("{}/rig.yaml: camera name '{}' {} (BOP folder suffix)", sequence_dir,
                      camera.camera.name, problem));
    }
  }
  BCOT_ASSIGN_OR_RETURN(
      const Mesh mesh, Mesh::Load(plan.sequence.object.mesh_path, plan.sequence.object.unit_to_mm));
  const Eigen::Isometry3d objcentre_from_template = mesh.objcentre_from_template();
  const RayCaster caster(mesh);

  const fs::path scene_dir =
      fs::path(out_root) / options.bop.split / fmt::format("{:06d}", options.bop.scene_id);
  BCOT_RETURN_IF_ERROR(export_internal::PrepareEmptyFolder(scene_dir, options.overwrite));
  ExportSummary summary = export_internal::SummarizePlan(plan, options);
  BCOT_RETURN_IF_ERROR(WriteModel(
      fs::path(out_root) / "models", options.bop.obj_id, mesh.Transformed(objcentre_from_template),
      options.bop.symmetries_continuous, options.overwrite, &summary.model_path));
  for (const CameraPlan& camera : plan.cameras) {
    const std::string suffix = suffixed ? "_" + camera.camera.name : "";
    CameraFiles files;
    BCOT_RETURN_IF_ERROR(WriteCameraImages(plan, camera, caster, objcentre_from_template,
                                           options.bop.obj_id, scene_dir, suffix, &files));
    BCOT_RETURN_IF_ERROR(WriteFileAtomic((scene_dir / ("scene_camera" + suffix + ".json")).string(),
                                         FormatPerImageJson(files.scene_camera)));
    BCOT_RETURN_IF_ERROR(WriteFileAtomic((scene_dir / ("scene_gt" + suffix + ".json")).string(),
                                         FormatPerImageJson(files.scene_gt)));
    BCOT_RETURN_IF_ERROR(
        WriteFileAtomic((scene_dir / ("scene_gt_info" + suffix + ".json")).string(),
                        FormatPerImageJson(files.scene_gt_info)));
  }
  summary.scene_dirs.push_back(scene_dir.string());
  return summary;
}

}  // namespace bcot
