#include "bcot/review/review_session.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bcot/annotate/annotator.h"
#include "bcot/annotate/image_response_file.h"
#include "bcot/core/annotation_poses.h"
#include "bcot/core/file_util.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"
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

// A pose as the 12 numbers of a pose-file line (rotation row-major, then translation).
ordered_json PoseNumbers(const Eigen::Isometry3d& pose) {
  ordered_json numbers = ordered_json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) numbers.push_back(pose.linear()(r, c));
  }
  for (int k = 0; k < 3; ++k) numbers.push_back(pose.translation()[k]);
  return numbers;
}

// The pose JSON of /api/frame/N/pose (review_session.h).
ordered_json PoseObject(const PoseEdits& edits, int frame) {
  return {{"frame", frame},
          {"edits", edits.Depth(frame)},
          {"rig_from_object", PoseNumbers(edits.Pose(frame))}};
}

bool IsFile(const std::string& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

// A directory that does not exist or holds nothing (where an annotation can be written).
bool IsEmptyOrAbsent(const std::string& dir) {
  std::error_code error;
  if (!std::filesystem::exists(dir, error)) return true;
  return std::filesystem::is_directory(dir, error) && std::filesystem::is_empty(dir, error);
}

// "the sequence is accepted (worst 0.29 px)", or rejected with its first reason.
std::string Verdict(const AnnotationOutcome& outcome) {
  const QualityVerdict& verdict = outcome.verdict;
  if (!verdict.accepted && !verdict.reasons.empty()) {
    return "the sequence is rejected: " + verdict.reasons.front();
  }
  return fmt::format("the sequence is {} (worst {:.2f} px)",
                     verdict.accepted ? "accepted" : "rejected", verdict.worst_px);
}

Status NoAnnotationToEdit() {
  return Status::InvalidInput("no annotation to edit (bcot review --annotation)");
}

}  // namespace

ReviewSession::ReviewSession(Sequence sequence, std::optional<ReviewAnnotation> annotation,
                             std::string annotation_target, const Mesh& mesh,
                             const InitOptions& init_options)
    : sequence_(std::move(sequence)),
      annotation_target_(std::move(annotation_target)),
      caster_(mesh),
      init_options_(init_options) {
  if (annotation) shown_ = NewShown(std::move(*annotation));
}

ReviewSession::~ReviewSession() = default;

std::shared_ptr<const ReviewSession::ShownAnnotation> ReviewSession::NewShown(
    ReviewAnnotation files) {
  auto shown = std::make_shared<ShownAnnotation>();
  shown->edits = std::make_shared<PoseEdits>(files.rig_from_object);
  shown->options = ReadAnnotateOptions(files.dir + "/config.resolved.yaml", {});
  shown->files = std::move(files);
  return shown;
}

std::shared_ptr<const ReviewSession::ShownAnnotation> ReviewSession::Shown() const {
  std::lock_guard<std::mutex> lock(shown_mutex_);
  return shown_;
}

void ReviewSession::Show(std::shared_ptr<const ShownAnnotation> shown) {
  std::lock_guard<std::mutex> lock(shown_mutex_);
  shown_ = std::move(shown);
}

StatusOr<std::string> ReviewSession::Refine(int frame) {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown) return NoAnnotationToEdit();
  if (!shown->options.ok()) {
    return Status::InvalidInput("refine needs the annotation's options: " +
                                shown->options.status().message());
  }
  PoseEdits& edits = *shown->edits;
  // The frame's edges decoded as the annotation's were (its estimate when edge.response is auto).
  AnnotateOptions options = *shown->options;
  BCOT_ASSIGN_OR_RETURN(
      const ImageResponseRecord image_response,
      RecordedImageResponse(shown->files.dir, options.tracker.frame.edge.lines.response));
  options.tracker.frame.edge.lines.response = image_response.response;
  BCOT_ASSIGN_OR_RETURN(const RefinedFrame refined,
                        RefineFrame(sequence_, caster_, options, frame, edits.Pose(frame)));
  if (!refined.summary.usable()) {
    return Status::InvalidInput(fmt::format(
        "frame {}: the solve failed ({}); the pose is unchanged", frame, refined.summary.message));
  }
  edits.Push(frame, refined.rig_from_object);
  ordered_json json = PoseObject(edits, frame);
  json["termination"] = FrameTerminationName(refined.summary.termination);
  json["rounds"] = refined.summary.rounds;
  return json.dump();
}

StatusOr<std::string> ReviewSession::PoseJson(int frame) const {
  BCOT_CHECK(frame >= 0 && frame < sequence_.num_frames);
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown) return NoAnnotationToEdit();
  return PoseObject(*shown->edits, frame).dump();
}

StatusOr<std::string> ReviewSession::Nudge(const ReviewTarget& target, const PoseNudge& nudge) {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown) return NoAnnotationToEdit();
  BCOT_ASSIGN_OR_RETURN(const Eigen::Isometry3d nudged,
                        NudgePose(shown->edits->Pose(target.frame), caster_.mesh().bbox_center(),
                                  sequence_.rig[target.camera], nudge));
  shown->edits->Push(target.frame, nudged);
  return PoseObject(*shown->edits, target.frame).dump();
}

StatusOr<std::string> ReviewSession::Undo(int frame) {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown) return NoAnnotationToEdit();
  if (!shown->edits->Undo(frame)) {
    return Status::InvalidInput(fmt::format("frame {} has no edit to undo", frame));
  }
  return PoseObject(*shown->edits, frame).dump();
}

StatusOr<std::string> ReviewSession::SetKeyframeJson(int frame) {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown) return NoAnnotationToEdit();
  const std::string path = sequence_.dir + "/keyframes.txt";
  {
    std::lock_guard<std::mutex> lock(keyframes_mutex_);
    BCOT_RETURN_IF_ERROR(SetKeyframe(path, frame, shown->edits->Pose(frame), sequence_.num_frames));
  }
  int first = frame, last = frame;
  const ReviewAnnotation& annotation = shown->files;
  if (annotation.quality) {
    const std::vector<int> bad = annotation.quality->BadFrames();
    const auto is_bad = [&](int f) { return std::binary_search(bad.begin(), bad.end(), f); };
    while (first > 0 && is_bad(first - 1)) --first;
    while (last + 1 < sequence_.num_frames && is_bad(last + 1)) ++last;
  }
  const std::string command =
      fmt::format("bcot annotate {} --out {} --config {}/config.resolved.yaml --frames {}:{}",
                  sequence_.dir, annotation.dir, annotation.dir, first, last);
  return ordered_json{
      {"path", path}, {"frame", frame}, {"first", first}, {"last", last}, {"command", command}}
      .dump();
}

StatusOr<std::unique_ptr<ReviewSession>> ReviewSession::Load(const std::string& sequence_dir,
                                                             const std::string& annotation_dir,
                                                             const InitOptions& init_options) {
  BCOT_RETURN_IF_ERROR(init_options.Validate());
  BCOT_ASSIGN_OR_RETURN(Sequence sequence, LoadSequence(sequence_dir, /*require_init_pose=*/false));
  std::optional<ReviewAnnotation> annotation;
  std::string annotation_target;
  if (IsEmptyOrAbsent(annotation_dir)) {
    annotation_target = annotation_dir;  // "" without one
  } else if (!IsFile(annotation_dir + "/" + kRigFromObjectFileName)) {
    return Status::InvalidInput(fmt::format(
        "--annotation {}: neither an annotation (no {}) nor a new or empty directory to "
        "annotate into",
        annotation_dir, kRigFromObjectFileName));
  } else {
    BCOT_ASSIGN_OR_RETURN(annotation, LoadReviewAnnotation(annotation_dir, sequence.num_frames));
  }
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  return std::unique_ptr<ReviewSession>(new ReviewSession(
      std::move(sequence), std::move(annotation), annotation_target, mesh, init_options));
}

StatusOr<ReviewTarget> ReviewSession::Resolve(const std::string& frame_text,
                                              const std::string& camera_name) const {
  return ResolveReviewTarget(frame_text, camera_name, sequence_.num_frames, sequence_.rig);
}

std::string ReviewSession::SequenceJson() const {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  const bool can_annotate = !shown && !annotation_target_.empty();
  ordered_json json = {{"sequence", sequence_.dir},
                       {"num_frames", sequence_.num_frames},
                       {"annotation", shown ? ordered_json(shown->files.dir) : nullptr},
                       {"contour", shown != nullptr},
                       {"init_pose", IsFile(sequence_.dir + "/init_pose.txt")},
                       {"annotation_target",
                        can_annotate ? ordered_json(annotation_target_) : ordered_json(nullptr)},
                       {"cameras", ordered_json::array()}};
  for (const RigCamera& camera : sequence_.rig.cameras()) {
    json["cameras"].push_back({{"name", camera.camera.name},
                               {"width", camera.camera.width},
                               {"height", camera.camera.height}});
  }
  return json.dump();
}

std::string ReviewSession::QualityJson() const {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown || !shown->files.quality) return ordered_json{{"available", false}}.dump();
  return TimelineJson(*shown->files.quality).dump();
}

std::string ReviewSession::DiagnosticsJson(int frame) const {
  BCOT_CHECK(frame >= 0 && frame < sequence_.num_frames);
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown || !shown->files.diagnostics) {
    return ordered_json{{"available", false}, {"frame", frame}}.dump();
  }
  const FrameDiagnostics& diagnostics = *shown->files.diagnostics;
  ordered_json values;
  for (size_t c = 0; c < diagnostics.columns.size(); ++c) {
    values[diagnostics.columns[c]] = diagnostics.rows[frame][c];
  }
  return ordered_json{{"available", true}, {"frame", frame}, {"values", values}}.dump();
}

std::string ReviewSession::TrajectoryJson() const {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown) return ordered_json{{"available", false}}.dump();
  const std::vector<Eigen::Isometry3d>& poses = shown->files.rig_from_object;
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
  // keyframes.txt as it is now (the page sets keyframes); what was loaded if it cannot be read.
  KeyframePoses keyframe_poses = sequence_.keyframes;
  const std::string keyframes_path = sequence_.dir + "/keyframes.txt";
  if (IsFile(keyframes_path)) {
    std::lock_guard<std::mutex> lock(keyframes_mutex_);
    StatusOr<KeyframePoses> current = ReadKeyframeFile(keyframes_path, sequence_.num_frames);
    if (current.ok()) keyframe_poses = std::move(*current);
  }
  ordered_json keyframes = ordered_json::array();
  for (const auto& keyframe : keyframe_poses) keyframes.push_back(keyframe.first);
  return ordered_json{{"available", true},
                      {"rotation_deg", rotation},
                      {"centre_mm", {{"x", x}, {"y", y}, {"z", z}}},
                      {"keyframes", keyframes}}
      .dump();
}

StatusOr<std::vector<unsigned char>> ReviewSession::ViewJpeg(const ReviewTarget& target,
                                                             int jpeg_quality, bool mask,
                                                             int candidate) const {
  BCOT_CHECK(target.frame >= 0 && target.frame < sequence_.num_frames);
  BCOT_CHECK(target.camera >= 0 && target.camera < sequence_.rig.size());
  const RigCamera& camera = sequence_.rig[target.camera];
  BCOT_ASSIGN_OR_RETURN(
      cv::Mat3b image,
      ReadCameraImage(sequence_.image_paths[target.camera][target.frame], camera.camera));
  std::optional<Eigen::Isometry3d> candidate_pose;
  if (candidate >= 0) {
    std::lock_guard<std::mutex> lock(init_mutex_);
    if (!init_result_ || candidate >= static_cast<int>(init_result_->candidates.size())) {
      return Status::InvalidInput(fmt::format("no initial-pose candidate {}", candidate));
    }
    if (target.frame == init_frame_) {
      candidate_pose = init_result_->candidates[candidate].rig_from_object;
    }
  }
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (shown) {
    const Eigen::Isometry3d cam_from_object =
        camera.cam_from_rig * shown->files.rig_from_object[target.frame];
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
    if (shown->edits->Depth(target.frame) > 0) {
      DrawContour(caster_.ExtractContour(camera.camera,
                                         camera.cam_from_rig * shown->edits->Pose(target.frame)),
                  cv::Scalar(0, 230, 255), &image);
    }
  }
  if (candidate_pose) {
    DrawContour(caster_.ExtractContour(camera.camera, camera.cam_from_rig * *candidate_pose),
                cv::Scalar(255, 0, 255), &image);
  }
  std::vector<unsigned char> jpeg;
  if (!cv::imencode(".jpg", image, jpeg, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality})) {
    return Status::Internal("cannot encode a JPEG frame image");
  }
  return jpeg;
}

StatusOr<std::string> ReviewSession::StartReannotate(int first, int last) {
  const std::shared_ptr<const ShownAnnotation> shown = Shown();
  if (!shown) return NoAnnotationToEdit();
  if (!shown->options.ok()) {
    return Status::InvalidInput("re-annotating needs the annotation's options: " +
                                shown->options.status().message());
  }
  if (first < 0 || last < first || last >= sequence_.num_frames) {
    return Status::InvalidInput(fmt::format("re-annotate {}:{}: the sequence has frames 0..{}",
                                            first, last, sequence_.num_frames - 1));
  }
  const std::string name = fmt::format("re-annotate {}:{}", first, last);
  BCOT_RETURN_IF_ERROR(job_.Start(
      name,
      [this, first, last, shown](const ReviewJob::Progress& progress) -> StatusOr<std::string> {
        AnnotateInputs inputs;
        inputs.frames = fmt::format("{}:{}", first, last);
        BCOT_ASSIGN_OR_RETURN(const AnnotationOutcome outcome,
                              AnnotateSequenceDir(sequence_.dir, shown->files.dir, *shown->options,
                                                  inputs, progress));
        BCOT_ASSIGN_OR_RETURN(ReviewAnnotation reloaded,
                              LoadReviewAnnotation(shown->files.dir, sequence_.num_frames));
        // The same edits (those of the re-annotated frames dropped) over the new poses.
        shown->edits->Rebase(reloaded.rig_from_object, first, last);
        auto next = std::make_shared<ShownAnnotation>(*shown);
        next->files = std::move(reloaded);
        Show(std::move(next));
        return fmt::format("frames {}:{} re-annotated; {}", first, last, Verdict(outcome));
      }));
  return ordered_json{{"job", name}}.dump();
}

StatusOr<std::string> ReviewSession::StartAnnotate() {
  if (Shown()) {
    return Status::InvalidInput("an annotation is shown already; re-annotate frames instead");
  }
  if (annotation_target_.empty()) {
    return Status::InvalidInput(
        "no annotation directory to write: start bcot review with --annotation DIR (a new or "
        "empty directory)");
  }
  const std::string name = "annotate into " + annotation_target_;
  BCOT_RETURN_IF_ERROR(
      job_.Start(name, [this](const ReviewJob::Progress& progress) -> StatusOr<std::string> {
        BCOT_ASSIGN_OR_RETURN(const AnnotationOutcome outcome,
                              AnnotateSequenceDir(sequence_.dir, annotation_target_,
                                                  init_options_.annotate, progress));
        BCOT_ASSIGN_OR_RETURN(ReviewAnnotation loaded,
                              LoadReviewAnnotation(annotation_target_, sequence_.num_frames));
        Show(NewShown(std::move(loaded)));
        return fmt::format("annotated {} frames into {}; {}", outcome.frames, annotation_target_,
                           Verdict(outcome));
      }));
  return ordered_json{{"job", name}}.dump();
}

StatusOr<std::string> ReviewSession::StartInit(const InitRequest& request) {
  BCOT_RETURN_IF_ERROR(CheckInitRequest(sequence_, request));
  const std::string name = fmt::format("initial pose of frame {}", request.frame);
  BCOT_RETURN_IF_ERROR(job_.Start(
      name, [this, request](const ReviewJob::Progress& progress) -> StatusOr<std::string> {
        const int num_views = sequence_.rig.size();
        std::vector<cv::Mat3b> images;
        for (int v = 0; v < num_views; ++v) {
          BCOT_ASSIGN_OR_RETURN(
              images.emplace_back(),
              ReadCameraImage(sequence_.image_paths[v][request.frame], sequence_.rig[v].camera));
          progress(v + 1, num_views + 1);
        }
        BCOT_ASSIGN_OR_RETURN(InitResult result,
                              FindInitialPose(sequence_, caster_, images, request, init_options_));
        progress(num_views + 1, num_views + 1);
        const std::string summary = fmt::format(
            "{} distinct candidate(s), centre from {}; {} poses scored in {:.1f} s, refined in "
            "{:.1f} s",
            result.candidates.size(), result.centre_source, result.poses_scored,
            result.search_seconds, result.refine_seconds);
        std::lock_guard<std::mutex> lock(init_mutex_);
        init_result_ = std::move(result);
        init_frame_ = request.frame;
        return summary;
      }));
  return ordered_json{{"job", name}}.dump();
}

std::string ReviewSession::InitJson() const {
  std::lock_guard<std::mutex> lock(init_mutex_);
  ordered_json json = {{"candidates", ordered_json::array()}};
  if (!init_result_) return json.dump();
  json["frame"] = init_frame_;
  json["centre_source"] = init_result_->centre_source;
  for (const InitCandidate& candidate : init_result_->candidates) {
    json["candidates"].push_back({{"energy", Number(candidate.energy)},
                                  {"merged", candidate.merged},
                                  {"rig_from_object", PoseNumbers(candidate.rig_from_object)}});
  }
  return json.dump();
}

StatusOr<std::string> ReviewSession::SaveInitPose(int candidate, bool overwrite) {
  Eigen::Isometry3d pose;
  int frame = 0;
  {
    std::lock_guard<std::mutex> lock(init_mutex_);
    if (!init_result_ || candidate < 0 ||
        candidate >= static_cast<int>(init_result_->candidates.size())) {
      return Status::InvalidInput(fmt::format("no initial-pose candidate {}", candidate));
    }
    pose = init_result_->candidates[candidate].rig_from_object;
    frame = init_frame_;
  }
  // init_pose.txt anchors frame 0; a pose found at another frame becomes its keyframe (an
  // anchor of `bcot annotate` as well, docs/keyframes.md).
  const std::string path = sequence_.dir + (frame == 0 ? "/init_pose.txt" : "/keyframes.txt");
  if (frame == 0) {
    if (!overwrite && IsFile(path)) {
      return Status::InvalidInput(path + " exists; tick 'overwrite' to replace it");
    }
    BCOT_RETURN_IF_ERROR(WritePoseFile(path, {pose}));
  } else {
    std::lock_guard<std::mutex> lock(keyframes_mutex_);
    BCOT_RETURN_IF_ERROR(SetKeyframe(path, frame, pose, sequence_.num_frames));
  }
  return ordered_json{{"path", path},
                      {"frame", frame},
                      {"command", fmt::format("bcot annotate {} --out ANNOTATION_DIR --config "
                                              "configs/annotate.yaml",
                                              sequence_.dir)}}
      .dump();
}

}  // namespace bcot
