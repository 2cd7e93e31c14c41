#include "bcot/review/review_session.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bcot/annotate/annotator.h"
#include "bcot/core/image_io.h"
#include "bcot/core/se3.h"
#include "bcot/render/contour_drawing.h"

namespace bcot {
namespace {

using nlohmann::ordered_json;

// NaN and infinities as null (JSON has no such numbers).
ordered_json Number(double value) {
  return std::isfinite(value) ? ordered_json(value) : ordered_json(nullptr);
}

ordered_json TimelineJson(const QualityTimeline& timeline) {
  ordered_json json = {{"available", true},
                       {"threshold_px", timeline.threshold_px},
                       {"statistic", timeline.statistic},
                       {"bad_frames", timeline.BadFrames()}};
  for (size_t v = 0; v < timeline.view_names.size(); ++v) {
    ordered_json errors = ordered_json::array();
    for (double error : timeline.error_px[v]) errors.push_back(Number(error));
    ordered_json bad = ordered_json::array();
    ordered_json verifiable = ordered_json::array();
    for (size_t f = 0; f < timeline.bad[v].size(); ++f) {
      if (timeline.bad[v][f]) bad.push_back(f);
      if (!timeline.verifiable[v][f]) verifiable.push_back(f);
    }
    json["views"].push_back({{"name", timeline.view_names[v]},
                             {"error_px", errors},
                             {"bad_frames", bad},
                             {"unverifiable_frames", verifiable}});
  }
  return json;
}

// The pose JSON of /api/frame/N/pose (review_session.h).
ordered_json PoseObject(const PoseEdits& edits, int frame) {
  const Eigen::Isometry3d pose = edits.Pose(frame);
  ordered_json numbers = ordered_json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) numbers.push_back(pose.linear()(r, c));
  }
  for (int k = 0; k < 3; ++k) numbers.push_back(pose.translation()[k]);
  return {{"frame", frame}, {"edits", edits.Depth(frame)}, {"rig_from_object", numbers}};
}

Status NoAnnotationToEdit() {
  return Status::InvalidInput("no annotation to edit (bcot review --annotation)");
}

}  // namespace

ReviewSession::ReviewSession(Sequence sequence, std::optional<ReviewAnnotation> annotation,
                             const Mesh& mesh)
    : sequence_(std::move(sequence)), annotation_(std::move(annotation)), caster_(mesh) {
  if (annotation_) {
    edits_ = std::make_unique<PoseEdits>(annotation_->rig_from_object);
    annotate_options_ = ReadAnnotateOptions(annotation_->dir + "/config.resolved.yaml", {});
  }
}

StatusOr<std::string> ReviewSession::Refine(int frame) {
  if (!edits_) return NoAnnotationToEdit();
  if (!annotate_options_.ok()) {
    return Status::InvalidInput("refine needs the annotation's options: " +
                                annotate_options_.status().message());
  }
  BCOT_ASSIGN_OR_RETURN(
      const RefinedFrame refined,
      RefineFrame(sequence_, caster_, *annotate_options_, frame, edits_->Pose(frame)));
  if (!refined.summary.usable()) {
    return Status::InvalidInput(fmt::format(
        "frame {}: the solve failed ({}); the pose is unchanged", frame, refined.summary.message));
  }
  edits_->Push(frame, refined.rig_from_object);
  ordered_json json = PoseObject(*edits_, frame);
  json["termination"] = FrameTerminationName(refined.summary.termination);
  json["rounds"] = refined.summary.rounds;
  return json.dump();
}

StatusOr<std::string> ReviewSession::PoseJson(int frame) const {
  BCOT_CHECK(frame >= 0 && frame < sequence_.num_frames);
  if (!edits_) return NoAnnotationToEdit();
  return PoseObject(*edits_, frame).dump();
}

StatusOr<std::string> ReviewSession::Nudge(const ReviewTarget& target, const PoseNudge& nudge) {
  if (!edits_) return NoAnnotationToEdit();
  BCOT_ASSIGN_OR_RETURN(const Eigen::Isometry3d nudged,
                        NudgePose(edits_->Pose(target.frame), caster_.mesh().bbox_center(),
                                  sequence_.rig[target.camera], nudge));
  edits_->Push(target.frame, nudged);
  return PoseJson(target.frame);
}

StatusOr<std::string> ReviewSession::Undo(int frame) {
  if (!edits_) return NoAnnotationToEdit();
  if (!edits_->Undo(frame)) {
    return Status::InvalidInput(fmt::format("frame {} has no edit to undo", frame));
  }
  return PoseJson(frame);
}

StatusOr<std::string> ReviewSession::SetKeyframeJson(int frame) {
  if (!edits_) return NoAnnotationToEdit();
  const std::string path = sequence_.dir + "/keyframes.txt";
  {
    std::lock_guard<std::mutex> lock(keyframes_mutex_);
    BCOT_RETURN_IF_ERROR(SetKeyframe(path, frame, edits_->Pose(frame), sequence_.num_frames));
  }
  int first = frame, last = frame;
  if (annotation_->quality) {
    const std::vector<int> bad = annotation_->quality->BadFrames();
    const auto is_bad = [&](int f) { return std::binary_search(bad.begin(), bad.end(), f); };
    while (first > 0 && is_bad(first - 1)) --first;
    while (last + 1 < sequence_.num_frames && is_bad(last + 1)) ++last;
  }
  const std::string command =
      fmt::format("bcot annotate {} --out {} --config {}/config.resolved.yaml --frames {}:{}",
                  sequence_.dir, annotation_->dir, annotation_->dir, first, last);
  return ordered_json{{"path", path}, {"frame", frame}, {"command", command}}.dump();
}

StatusOr<std::unique_ptr<ReviewSession>> ReviewSession::Load(const std::string& sequence_dir,
                                                             const std::string& annotation_dir) {
  BCOT_ASSIGN_OR_RETURN(Sequence sequence, LoadSequence(sequence_dir, /*require_init_pose=*/false));
  std::optional<ReviewAnnotation> annotation;
  if (!annotation_dir.empty()) {
    BCOT_ASSIGN_OR_RETURN(annotation, LoadReviewAnnotation(annotation_dir, sequence.num_frames));
  }
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  return std::unique_ptr<ReviewSession>(
      new ReviewSession(std::move(sequence), std::move(annotation), mesh));
}

StatusOr<ReviewTarget> ReviewSession::Resolve(const std::string& frame_text,
                                              const std::string& camera_name) const {
  return ResolveReviewTarget(frame_text, camera_name, sequence_.num_frames, sequence_.rig);
}

std::string ReviewSession::SequenceJson() const {
  ordered_json json = {{"sequence", sequence_.dir},
                       {"num_frames", sequence_.num_frames},
                       {"annotation", annotation_ ? ordered_json(annotation_->dir) : nullptr},
                       {"contour", annotation_.has_value()},
                       {"cameras", ordered_json::array()}};
  for (const RigCamera& camera : sequence_.rig.cameras()) {
    json["cameras"].push_back({{"name", camera.camera.name},
                               {"width", camera.camera.width},
                               {"height", camera.camera.height}});
  }
  return json.dump();
}

std::string ReviewSession::QualityJson() const {
  if (!annotation_ || !annotation_->quality) return ordered_json{{"available", false}}.dump();
  return TimelineJson(*annotation_->quality).dump();
}

std::string ReviewSession::DiagnosticsJson(int frame) const {
  BCOT_CHECK(frame >= 0 && frame < sequence_.num_frames);
  if (!annotation_ || !annotation_->diagnostics) {
    return ordered_json{{"available", false}, {"frame", frame}}.dump();
  }
  const FrameDiagnostics& diagnostics = *annotation_->diagnostics;
  ordered_json values;
  for (size_t c = 0; c < diagnostics.columns.size(); ++c) {
    values[diagnostics.columns[c]] = diagnostics.rows[frame][c];
  }
  return ordered_json{{"available", true}, {"frame", frame}, {"values", values}}.dump();
}

std::string ReviewSession::TrajectoryJson() const {
  if (!annotation_) return ordered_json{{"available", false}}.dump();
  const std::vector<Eigen::Isometry3d>& poses = annotation_->rig_from_object;
  const Eigen::Vector3d centre = caster_.mesh().bbox_center();
  ordered_json rotation = ordered_json::array(), x = ordered_json::array(),
               y = ordered_json::array(), z = ordered_json::array();
  for (const Eigen::Isometry3d& pose : poses) {
    rotation.push_back(RotationDistanceDeg(poses.front().linear(), pose.linear()));
    const Eigen::Vector3d position = pose * centre;
    x.push_back(position.x());
    y.push_back(position.y());
    z.push_back(position.z());
  }
  ordered_json keyframes = ordered_json::array();
  for (const auto& keyframe : sequence_.keyframes) keyframes.push_back(keyframe.first);
  return ordered_json{{"available", true},
                      {"rotation_deg", rotation},
                      {"centre_mm", {{"x", x}, {"y", y}, {"z", z}}},
                      {"keyframes", keyframes}}
      .dump();
}

StatusOr<std::vector<unsigned char>> ReviewSession::ViewJpeg(const ReviewTarget& target,
                                                             int jpeg_quality, bool mask) const {
  BCOT_CHECK(target.frame >= 0 && target.frame < sequence_.num_frames);
  BCOT_CHECK(target.camera >= 0 && target.camera < sequence_.rig.size());
  const RigCamera& camera = sequence_.rig[target.camera];
  BCOT_ASSIGN_OR_RETURN(
      cv::Mat3b image,
      ReadCameraImage(sequence_.image_paths[target.camera][target.frame], camera.camera));
  if (annotation_) {
    const Eigen::Isometry3d cam_from_object =
        camera.cam_from_rig * annotation_->rig_from_object[target.frame];
    if (mask) {
      RenderOptions options;
      options.depth = options.normal_in_cam = options.point_in_object = options.triangle_id = false;
      const RenderedView view = caster_.Render(camera.camera, cam_from_object, options);
      const cv::Rect roi = view.roi & cv::Rect(0, 0, image.cols, image.rows);
      for (int y = roi.y; y < roi.y + roi.height; ++y) {
        for (int x = roi.x; x < roi.x + roi.width; ++x) {
          if (view.mask(y - view.roi.y, x - view.roi.x) == 0) continue;
          cv::Vec3b& pixel = image(y, x);
          pixel = cv::Vec3b(static_cast<uchar>(0.65 * pixel[0]),
                            static_cast<uchar>(0.65 * pixel[1] + 0.35 * 255),
                            static_cast<uchar>(0.65 * pixel[2]));
        }
      }
    }
    DrawContour(caster_.ExtractContour(camera.camera, cam_from_object), cv::Scalar(0, 255, 0),
                &image);
    if (edits_->Depth(target.frame) > 0) {
      DrawContour(
          caster_.ExtractContour(camera.camera, camera.cam_from_rig * edits_->Pose(target.frame)),
          cv::Scalar(0, 230, 255), &image);
    }
  }
  std::vector<unsigned char> jpeg;
  if (!cv::imencode(".jpg", image, jpeg, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality})) {
    return Status::Internal("cannot encode a JPEG frame image");
  }
  return jpeg;
}

}  // namespace bcot
