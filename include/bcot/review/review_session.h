// What `bcot review` serves: one sequence, optionally one annotation of it, and the Embree caster
// of its object. Loaded and validated once; afterwards every method is thread-safe (the HTTP
// server answers requests from several threads): the read-only ones are const, the edits of
// the annotation's poses (review_edits.h) are kept in memory behind their own locks and reach
// the disk only as keyframes.txt.
//
// The JSON documents are described in docs/review.md. Images are always the sequence's own
// files, addressed by a validated ReviewTarget, never by a path from a request.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/review/review_annotation.h"
#include "bcot/review/review_edits.h"
#include "bcot/review/review_request.h"

namespace bcot {

class ReviewSession {
 public:
  // Loads the sequence in `sequence_dir` (init_pose.txt not required) and, when
  // `annotation_dir` is not empty, its annotation. Errors name the file at fault.
  static StatusOr<std::unique_ptr<ReviewSession>> Load(const std::string& sequence_dir,
                                                       const std::string& annotation_dir);

  const Sequence& sequence() const { return sequence_; }
  const std::optional<ReviewAnnotation>& annotation() const { return annotation_; }

  // The frame index and camera of a request, validated against the sequence.
  StatusOr<ReviewTarget> Resolve(const std::string& frame_text,
                                 const std::string& camera_name) const;

  // /api/sequence: directory, frame count, cameras (name, size), annotation directory or null,
  // whether the images show a contour.
  std::string SequenceJson() const;
  // /api/quality: the quality timeline, or {"available": false} without one.
  std::string QualityJson() const;
  // /api/frame/N/diagnostics: frames.csv's row of `frame` as {column: value}, or
  // {"available": false}. `frame` must be a valid index (CHECKed).
  std::string DiagnosticsJson(int frame) const;
  // /api/frame/N/view/CAM.jpg[?mask=1]: the frame image of the target's camera, with the
  // silhouette contour of the annotated pose drawn in green when there is an annotation, and
  // with `mask` its silhouette tinted green at 35 % (where the model covers the image).
  // An edited frame shows the edited pose's contour in yellow over the annotated one.
  StatusOr<std::vector<unsigned char>> ViewJpeg(const ReviewTarget& target, int jpeg_quality,
                                                bool mask = false) const;
  // /api/frame/N/pose: {"frame", "edits" (on the frame's undo stack), "rig_from_object" (12
  // numbers, the pose-file order)}; kInvalidInput without an annotation.
  StatusOr<std::string> PoseJson(int frame) const;
  // POST /api/frame/N/nudge: moves the frame's pose in the target camera (NudgePose); its pose
  // JSON.
  StatusOr<std::string> Nudge(const ReviewTarget& target, const PoseNudge& nudge);
  // POST /api/frame/N/refine: the frame solved as an anchor of `bcot annotate` from its current
  // pose (RefineFrame) with the annotation's options (config.resolved.yaml), pushed as an edit;
  // its pose JSON plus "termination" and "rounds" of the solve.
  StatusOr<std::string> Refine(int frame);
  // POST /api/frame/N/undo: drops the frame's last edit; its pose JSON (kInvalidInput
  // when there is none).
  StatusOr<std::string> Undo(int frame);
  // POST /api/frame/N/keyframe: the frame's pose (edited or not) as its keyframe in
  // <sequence>/keyframes.txt (SetKeyframe); {"path", "frame", "command"}: the `bcot annotate
  // --frames A:B` that re-annotates the bad frames around it (A:B the run of bad frames of
  // quality.json that holds or touches N, else N:N).
  StatusOr<std::string> SetKeyframeJson(int frame);
  // /api/trajectory: per frame of the annotation, the rotation (deg) of the object from its
  // frame-0 orientation and the position of its bounding-box centre in the rig (mm), and the
  // sequence's keyframes; {"available": false} without an annotation.
  std::string TrajectoryJson() const;

 private:
  ReviewSession(Sequence sequence, std::optional<ReviewAnnotation> annotation, const Mesh& mesh);

  Sequence sequence_;
  std::optional<ReviewAnnotation> annotation_;
  RayCaster caster_;
  std::unique_ptr<PoseEdits> edits_;  // with an annotation
  // The annotation's options (config.resolved.yaml), or why they could not be read.
  StatusOr<AnnotateOptions> annotate_options_ = Status::NotFound("no annotation");
  std::mutex keyframes_mutex_;  // one keyframes.txt writer at a time
};

}  // namespace bcot
