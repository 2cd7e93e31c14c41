// Annotates one sequence directory (DESIGN.md input contract) and writes its annotation
// directory (output contract): tracking starts at the anchors — frame 0 from init_pose.txt and
// every keyframe (keyframes.h) — by MultiViewTracker::Initialize (colour bootstrap + joint
// solve), and runs forwards and backwards from each by MultiViewTracker::Track, each frame from
// its nearer anchor (tracking_plan.h). Keyframes are anchors of the temporal window too. With
// `window.enabled`, the temporal smoothing window (window_problem.h) then refines the poses,
// streaming: it runs while the frames are solved and keeps the templates of at most window.size +
// window.ContextFrames() (2 or 3) frames.
//
// One pass (AnnotateSequenceDir): remove DONE → solve every frame → write the poses, frames.csv
// and config.resolved.yaml → measure the quality on the poses in memory with the same mesh and
// ray caster → write the report files → write DONE. A failure while writing the report leaves
// the poses on disk (without DONE, so a rerun redoes the sequence).
//
// Outputs in `out_dir`, each written atomically (temp + rename):
//   rig_from_object.txt     one pose line per frame (O_t, mm)
//   <camera>/pose.txt       cam_from_object per frame, for every rig camera (also unused ones)
//   frames.csv              per frame: termination, rounds, iterations, energy per view, ms,
//                           and the pose change the window made (0 when it is off)
//   quality.json, quality.csv, report.html   the reprojection-error check (quality_report.h)
//   config.resolved.yaml    every option used, the tool version, the sequence's absolute path
//                           and the input hash
//   DONE                    last (done_file.h): the config and input hashes and the sequence.
//                           Removed first when a run starts, so a directory with DONE is always
//                           complete and consistent.
// A frame whose solve fails (object out of every view, solver failure) keeps the previous
// pose and is recorded as such in frames.csv; the run continues.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/image_response_file.h"
#include "bcot/core/image_cache.h"
#include "bcot/core/rotational_symmetry.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/optim/frame_problem.h"
#include "bcot/quality/quality_files.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct AnnotatedFrame {
  FrameSummary summary;
  double milliseconds = 0.0;  // wall time of the solve (information only)
  // Pose change made by the temporal window (per-frame → final pose); 0 when it is off.
  double window_rotation_deg = 0.0;
  double window_translation_mm = 0.0;
};

struct SequenceAnnotation {
  int first_frame = 0;                  // frame index of the first entry of the vectors below
  std::vector<std::string> view_names;  // the cameras used, in solve order
  std::vector<Eigen::Isometry3d> rig_from_object;  // per frame, O_t (final)
  // The mesh's rotational symmetry (O_t) when it is a body of revolution: the poses' angle about
  // its axis is then a convention (kept from the first anchor), not a measurement.
  std::optional<RotationalSymmetry> symmetry;
  // Every candidate axis the symmetry detection checked (render/symmetry_detection.h).
  std::vector<SymmetryCandidate> symmetry_candidates;
  std::vector<Eigen::Isometry3d> per_frame_rig_from_object;  // before the window, O_t
  std::vector<AnnotatedFrame> frames;                        // per frame
  int failed_frames = 0;                                     // frames whose solve was not usable
  ImageResponseRecord image_response;  // what the edges were decoded with (image_response.yaml)
};

// Called after every frame with (frames done, total frames).
using AnnotateProgress = std::function<void(int done, int total)>;
// Called after every frame's solve with the frame index, its per-frame rig_from_objcentre and
// the level-0 templates of its last round (empty when the solve failed), i.e. what the window
// receives; lets a caller run further windows on the same solves (tests/bench/window_bench.cc).
// The templates are shared and immutable; the vector is valid during the call only.
using AnnotateFrameObserver =
    std::function<void(int frame, const Eigen::Isometry3d& rig_from_objcentre,
                       const std::vector<ViewLinearisation>& linearisations)>;

// Solves every frame. Errors: invalid options (kInvalidConfig); a selected camera missing from
// the rig (kInvalidConfig); the mesh does not load, an image does not read or has the wrong
// size, neither init_pose.txt nor a keyframe, an anchor pose with the object out of every view
// (kInvalidInput / kNotFound, naming the file).
StatusOr<SequenceAnnotation> AnnotateSequence(const Sequence& sequence,
                                              const AnnotateOptions& options,
                                              const AnnotateProgress& progress = {},
                                              const AnnotateFrameObserver& observer = {});
// The same with the ray caster of the sequence's mesh (O_t, mm) built by the caller; the frames
// are read through `images` when given (kept there for a second pass).
StatusOr<SequenceAnnotation> AnnotateSequence(const Sequence& sequence, const RayCaster& caster,
                                              const AnnotateOptions& options,
                                              const AnnotateProgress& progress = {},
                                              const AnnotateFrameObserver& observer = {},
                                              DecodedImageCache* images = nullptr);

// A span of frames to annotate; the other frames of the sequence keep their poses.
struct FrameSpan {
  int first = 0;  // frames [first, end)
  int end = 0;
  // Empty, or the final rig_from_object of every frame of an existing annotation of the
  // sequence: then tracking starts from its pose at first − 1 (unless a keyframe is at `first`),
  // and the temporal window holds its poses within a window's size around the span constant as
  // context, so the span joins its neighbours smoothly while they stay unchanged.
  std::vector<Eigen::Isometry3d> existing_rig_from_object;
};

// One frame solved as `bcot annotate` solves an anchor (MultiViewTracker::Initialize: colour
// models learned at the pose, then the joint solve of the views options.views selects), from
// `rig_from_object` (O_t): `bcot review`'s "refine". Errors: as AnnotateSequence's for the
// views and images; kInvalidInput for a frame outside the sequence.
struct RefinedFrame {
  Eigen::Isometry3d rig_from_object = Eigen::Isometry3d::Identity();
  FrameSummary summary;
};
StatusOr<RefinedFrame> RefineFrame(const Sequence& sequence, const RayCaster& caster,
                                   const AnnotateOptions& options, int frame,
                                   const Eigen::Isometry3d& rig_from_object);

// Solves frames [span.first, span.end) (the returned vectors hold those frames only; observer
// and progress count them). Anchors: init_pose.txt when the span starts at 0, the keyframes in
// the span, and the existing pose before it (see FrameSpan). Errors as AnnotateSequence's, and
// kInvalidInput for a span outside the sequence, kNotFound when no anchor starts tracking.
// The frames are read through `images` when given.
StatusOr<SequenceAnnotation> AnnotateFrames(const Sequence& sequence, const RayCaster& caster,
                                            const AnnotateOptions& options, const FrameSpan& span,
                                            const AnnotateProgress& progress = {},
                                            const AnnotateFrameObserver& observer = {},
                                            DecodedImageCache* images = nullptr);

// A hash (16 hex digits) of everything a sequence's annotation depends on: rig.yaml,
// object.yaml, the mesh file, init_pose.txt (when present), the keyframes file (when the
// sequence has one) and every image file's name and size.
StatusOr<std::string> SequenceInputHash(const Sequence& sequence);

// The config hash DONE records: a hash (16 hex digits) of FormatAnnotateOptions(options).
std::string AnnotateConfigHash(const AnnotateOptions& options);

// frames.csv: a header line, then one row per frame of `annotation` (numbered from its
// first_frame).
std::string FormatFramesCsv(const SequenceAnnotation& annotation);

// Writes the poses, frames.csv and config.resolved.yaml (not the quality files, not DONE).
Status WriteAnnotation(const std::string& out_dir, const Sequence& sequence,
                       const AnnotateOptions& options, const std::string& input_hash,
                       const SequenceAnnotation& annotation);

// What AnnotateSequenceDir returns besides the files.
struct AnnotationOutcome {
  QualityVerdict verdict;
  int frames = 0;
  int failed_frames = 0;
  // Advice about the input that does not stop the run (CaptureNotes), for the user to read.
  std::vector<std::string> notes;
};

// The notes `bcot annotate` prints about the object's symmetry: that it is a body of revolution
// (annotation.symmetry), or that it nearly is one (a candidate axis whose silhouette change was
// within ten times `tolerance`).
std::vector<std::string> SymmetryNotes(const SequenceAnnotation& annotation, double tolerance);

// Notes about how `sequence` was captured that limit the precision a user can expect: today,
// cameras whose first frame is a JPEG with subsampled chroma (ReadChromaSampling), named
// together in one note. Files that cannot be read are left to the solve to report.
std::vector<std::string> CaptureNotes(const Sequence& sequence);

// How the frames of rig camera `index` store chroma for the edge stage: `setting`, or with
// kAuto read from the camera's first frame (ReadChromaSampling). Errors name the file.
StatusOr<ChromaSampling> ResolveChromaSampling(const Sequence& sequence, int index,
                                               ChromaSamplingSetting setting);

// The end of a run, after the poses, frames.csv and config.resolved.yaml are written: the
// quality files of `quality` (measured on `rig_from_object`; its provenance is set here), then
// DONE. The outcome's notes are the quality check's SaturationWarnings.
StatusOr<AnnotationOutcome> FinishAnnotation(const std::string& out_dir, const Sequence& sequence,
                                             const RayCaster& caster,
                                             const AnnotateOptions& options,
                                             const std::string& input_hash,
                                             const std::vector<Eigen::Isometry3d>& rig_from_object,
                                             QualityReport quality, int failed_frames);

// Inputs of one run besides the sequence directory and the options.
struct AnnotateInputs {
  // Keyframes file in place of <seq>/keyframes.txt (keyframes.h); empty = that file if any.
  std::string keyframes_path;
  // `--frames A:B`: re-annotate frames A..B (inclusive) of the finished annotation in out_dir
  // and splice them in (splice.h); empty = annotate the whole sequence.
  std::string frames;
  // Write into an --out that holds files bcot annotate does not write (output_dir.h).
  bool overwrite = false;
  // Decoded frames kept in memory (MiB) so that the quality check after the solve does not
  // decode them again (image_cache.h); 0 = none. Changes no result, so it is not an option of
  // the config (nor of its hash). 1024: 230 binocular 960×768 frames.
  size_t image_cache_mb = 1024;
  size_t image_cache_bytes() const { return image_cache_mb << 20; }
};

// LoadSequence with the keyframes of `inputs`; with `require_anchor`, kNotFound when the
// sequence has neither init_pose.txt nor a keyframe.
StatusOr<Sequence> LoadSequenceToAnnotate(const std::string& sequence_dir,
                                          const AnnotateInputs& inputs, bool require_anchor = true);

// Loads the sequence at `sequence_dir`, annotates it and writes `out_dir` in one pass (see the
// header comment). The sequence needs init_pose.txt or at least one keyframe.
StatusOr<AnnotationOutcome> AnnotateSequenceDir(const std::string& sequence_dir,
                                                const std::string& out_dir,
                                                const AnnotateOptions& options,
                                                const AnnotateInputs& inputs,
                                                const AnnotateProgress& progress = {});
StatusOr<AnnotationOutcome> AnnotateSequenceDir(const std::string& sequence_dir,
                                                const std::string& out_dir,
                                                const AnnotateOptions& options,
                                                const AnnotateProgress& progress = {});

}  // namespace bcot
