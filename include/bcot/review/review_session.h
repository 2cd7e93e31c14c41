// What `bcot review` serves: one sequence, optionally one annotation of it, and the Embree caster
// of its object. Loaded and validated once; afterwards every method is thread-safe (the HTTP
// server answers requests from several threads): the edits of the annotation's poses
// (review_edits.h) are kept in memory behind their own locks and reach the disk only as
// keyframes.txt; the annotation itself is replaced as a whole (a snapshot per request) when a
// re-annotation started from the page has finished. Long tasks (re-annotating frames,
// searching an initial pose) run one at a time as a ReviewJob (review_job.h).
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
#include "bcot/annotate/initializer.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/review/review_annotation.h"
#include "bcot/review/review_edits.h"
#include "bcot/review/review_job.h"
#include "bcot/review/review_request.h"

namespace bcot {

class ReviewSession {
 public:
  // Loads the sequence in `sequence_dir` (init_pose.txt not required) and, when
  // `annotation_dir` is not empty, its annotation; an `annotation_dir` that does not exist yet
  // or is empty is where the page's "annotate" writes one (StartAnnotate). Errors name the file
  // at fault. The page's initialisation searches with `init_options` (bcot init's; `bcot review
  // --config`), and its annotation runs with `init_options.annotate`.
  static StatusOr<std::unique_ptr<ReviewSession>> Load(const std::string& sequence_dir,
                                                       const std::string& annotation_dir,
                                                       const InitOptions& init_options = {});
  // Waits for a running job.
  ~ReviewSession();

  const Sequence& sequence() const { return sequence_; }

  // The frame index and camera of a request, validated against the sequence.
  StatusOr<ReviewTarget> Resolve(const std::string& frame_text,
                                 const std::string& camera_name) const;

  // /api/sequence: directory, frame count, cameras (name, size), annotation directory or null,
  // whether the images show a contour, whether init_pose.txt exists, and the directory the
  // page's "annotate" would write (null when there is an annotation or no such directory).
  std::string SequenceJson() const;
  // /api/quality: the quality timeline, or {"available": false} without one.
  std::string QualityJson() const;
  // /api/frame/N/diagnostics: frames.csv's row of `frame` as {column: value}, or
  // {"available": false}. `frame` must be a valid index (CHECKed).
  std::string DiagnosticsJson(int frame) const;
  // /api/frame/N/view/CAM.jpg[?mask=1][&candidate=K]: the frame image of the target's camera,
  // with the silhouette contour of the annotated pose drawn in green when there is an
  // annotation, and with `mask` its silhouette tinted green at 35 % (where the model covers the
  // image). An edited frame shows the edited pose's contour in yellow over the annotated one.
  // `candidate` >= 0 draws that candidate of the last initial-pose search in magenta (on the
  // searched frame; kInvalidInput for a candidate that does not exist).
  StatusOr<std::vector<unsigned char>> ViewJpeg(const ReviewTarget& target, int jpeg_quality,
                                                bool mask = false, int candidate = -1) const;
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
  // sequence's keyframes (as keyframes.txt holds them now); {"available": false} without an
  // annotation.
  std::string TrajectoryJson() const;

  // GET /api/job: the state of the last job (ReviewJob::Json).
  std::string JobJson() const { return job_.Json(); }
  // POST /api/reannotate?frames=A:B: starts re-annotating frames first..last as `bcot annotate
  // SEQ --out ANN --config ANN/config.resolved.yaml --frames A:B` would (the keyframes of
  // keyframes.txt as it is at the start), then reloads the annotation, so the page shows the
  // new poses, errors and diagnostics; the edits of those frames are dropped, the others kept.
  // {"job": name}; kInvalidInput without an annotation, with frames outside the sequence or
  // while a job runs.
  StatusOr<std::string> StartReannotate(int first, int last);
  // POST /api/init?frame=N&click=CAM:X,Y&click=...: starts bcot init's search from clicks on the
  // object's centre (FindInitialPose; CheckInitRequest's errors come back at once); its
  // candidates then in InitJson. {"job": name}.
  StatusOr<std::string> StartInit(const InitRequest& request);
  // GET /api/init: {"frame", "centre_source", "candidates": [{"energy", "merged",
  // "rig_from_object" (12 numbers)}] best first}; no "frame" and no candidates before a search.
  std::string InitJson() const;
  // POST /api/init/save?candidate=K[&overwrite=1]: candidate K of the last search written as
  // <seq>/init_pose.txt (atomically) when it was searched at frame 0, else as that frame's
  // keyframe in <seq>/keyframes.txt (SetKeyframe): {"path", "frame", "command"} (the `bcot
  // annotate` to run next). kInvalidInput for an unknown candidate, or when init_pose.txt
  // exists and !overwrite.
  StatusOr<std::string> SaveInitPose(int candidate, bool overwrite);
  // POST /api/annotate: annotates the whole sequence into the annotation directory given to
  // Load (when it held none) with init_options.annotate, as `bcot annotate` does, then shows
  // it: the page becomes the page of that annotation. {"job": name}; kInvalidInput when an
  // annotation is shown already, no directory was given, or a job runs.
  StatusOr<std::string> StartAnnotate();

 private:
  // An annotation as the page shows it: its files, the page's edits of its poses, and its
  // options (config.resolved.yaml, or why they could not be read).
  struct ShownAnnotation {
    ReviewAnnotation files;
    std::shared_ptr<PoseEdits> edits;
    StatusOr<AnnotateOptions> options = Status::NotFound("no annotation");
  };

  ReviewSession(Sequence sequence, std::optional<ReviewAnnotation> annotation,
                std::string annotation_target, const Mesh& mesh, const InitOptions& init_options);

  // The annotation shown now (null without one); replaced whole when a job ends.
  std::shared_ptr<const ShownAnnotation> Shown() const;
  void Show(std::shared_ptr<const ShownAnnotation> shown);
  // `files` as shown with new edits and the options of its config.resolved.yaml.
  static std::shared_ptr<const ShownAnnotation> NewShown(ReviewAnnotation files);

  Sequence sequence_;
  mutable std::mutex shown_mutex_;
  std::shared_ptr<const ShownAnnotation> shown_;  // guarded by shown_mutex_
  // Where StartAnnotate writes (Load's annotation_dir when it held no annotation), else "".
  const std::string annotation_target_;
  RayCaster caster_;
  mutable std::mutex keyframes_mutex_;  // one keyframes.txt writer (or reader) at a time
  const InitOptions init_options_;
  mutable std::mutex init_mutex_;
  std::optional<InitResult> init_result_;  // the last search, guarded by init_mutex_
  int init_frame_ = 0;
  ReviewJob job_;  // last member: destroyed (joined) first, while the rest still exists
};

}  // namespace bcot
