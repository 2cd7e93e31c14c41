#include "bcot/annotate/annotator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

#include "bcot/annotate/done_file.h"
#include "bcot/annotate/output_dir.h"
#include "bcot/annotate/output_lock.h"
#include "bcot/annotate/pose_scorer.h"
#include "bcot/annotate/splice.h"
#include "bcot/annotate/tracking_plan.h"
#include "bcot/core/annotation_poses.h"
#include "bcot/core/content_hash.h"
#include "bcot/core/file_util.h"
#include "bcot/core/image_cache.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/optim/window_problem.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

namespace bcot {
namespace {

// The pose of frame 0 must show the object to at least one selected view: centre in front of
// the camera, no farther than 1000 object diameters, and projecting within the image grown by
// half its size on each side (partly visible objects are fine). Anything else is a typo in
// init_pose.txt (a unit, a sign, a transposed matrix) that no solve can recover from.
// An anchor pose (init_pose.txt or a keyframe) must put the object in at least one view.
Status CheckAnchorPose(const Eigen::Isometry3d& rig_from_object, const std::string& source,
                       int frame, const std::vector<TrackedView>& views, const Mesh& mesh) {
  const Eigen::Vector3d centre_in_rig = rig_from_object * mesh.bbox_center();
  std::vector<std::string> where;
  for (const TrackedView& view : views) {
    const Camera& camera = view.camera;
    const Eigen::Vector3d centre = view.cam_from_rig * centre_in_rig;
    if (!(centre.z() > 0.0)) {
      where.push_back(fmt::format("behind {} (z = {:.4g} mm)", camera.name, centre.z()));
      continue;
    }
    if (centre.z() > 1000.0 * mesh.diameter()) {
      where.push_back(
          fmt::format("{:.4g} mm in front of {}, over 1000 object diameters ({:.4g} mm)",
                      centre.z(), camera.name, mesh.diameter()));
      continue;
    }
    const Eigen::Vector2d pixel = camera.Project(centre);
    if (pixel.allFinite() && pixel.x() >= -0.5 * camera.width && pixel.x() <= 1.5 * camera.width &&
        pixel.y() >= -0.5 * camera.height && pixel.y() <= 1.5 * camera.height) {
      return Status::Ok();
    }
    where.push_back(fmt::format("outside {}'s {}x{} image (at {:.4g}, {:.4g} px)", camera.name,
                                camera.width, camera.height, pixel.x(), pixel.y()));
  }
  std::string places;
  for (const std::string& place : where) places += (places.empty() ? "" : "; ") + place;
  return Status::InvalidInput(fmt::format(
      "{}: the object is not in view at frame {}: its centre is {}", source, frame, places));
}

// The mesh's rotational symmetry in O_t when options.symmetry asks for it and it has one;
// `candidates` (may be null) receives the axes checked (DetectRotationalSymmetry).
StatusOr<std::optional<RotationalSymmetry>> ObjectSymmetry(
    const RayCaster& caster, const AnnotateOptions& options,
    std::vector<SymmetryCandidate>* candidates = nullptr) {
  if (!options.symmetry.detect) return std::optional<RotationalSymmetry>();
  return DetectRotationalSymmetry(caster, options.symmetry.detection, candidates);
}

// Frames before and after a re-annotated span whose existing poses the window holds as its
// context: a window's size (the whole sequence for size 0), at least the priors' reach.
int WindowMargin(const WindowProblemOptions& window, int num_frames) {
  return window.size == 0 ? num_frames : std::max(window.size, window.ContextFrames());
}

// Where tracking restarts: rig_from_object by frame (keyframes win over init_pose.txt at
// frame 0), each checked to put the object in view.
// Only anchors in frames [first, end) are returned; none is an error of the caller's to report.
StatusOr<std::map<int, Eigen::Isometry3d>> AnchorPoses(const Sequence& sequence,
                                                       const std::vector<TrackedView>& views,
                                                       const Mesh& mesh, int first, int end) {
  std::map<int, Eigen::Isometry3d> anchors;
  if (first == 0 && sequence.init_rig_from_object.has_value() && sequence.keyframes.count(0) == 0) {
    BCOT_RETURN_IF_ERROR(CheckAnchorPose(*sequence.init_rig_from_object,
                                         sequence.dir + "/init_pose.txt", 0, views, mesh));
    anchors[0] = *sequence.init_rig_from_object;
  }
  for (const auto& [frame, rig_from_object] : sequence.keyframes) {
    if (frame < first || frame >= end) continue;
    BCOT_RETURN_IF_ERROR(
        CheckAnchorPose(rig_from_object, sequence.keyframes_path, frame, views, mesh));
    anchors[frame] = rig_from_object;
  }
  return anchors;
}

// The tracked views of the cameras the options' `views` ask for (their weights, and how their
// files store chroma), and the cameras' indices into the rig.
StatusOr<std::vector<TrackedView>> SelectViews(const Sequence& sequence,
                                               const AnnotateOptions& options,
                                               std::vector<int>* rig_indices) {
  const Rig& rig = sequence.rig;
  const ViewSelection& selection = options.views;
  std::vector<int> indices;
  if (selection.cameras.empty()) {
    for (int i = 0; i < rig.size(); ++i) indices.push_back(i);
  } else {
    for (const std::string& name : selection.cameras) {
      const int index = rig.Find(name);
      if (index < 0) {
        std::string known;
        for (const RigCamera& camera : rig.cameras()) {
          known += (known.empty() ? "" : ", ") + camera.camera.name;
        }
        return Status::InvalidConfig(
            fmt::format("views.cameras: no camera '{}' in the rig (cameras: {})", name, known));
      }
      indices.push_back(index);
    }
  }
  if (!selection.weights.empty() && selection.weights.size() != indices.size()) {
    return Status::InvalidConfig(fmt::format("views.weights: {} weights for {} cameras",
                                             selection.weights.size(), indices.size()));
  }
  std::vector<TrackedView> views;
  for (size_t i = 0; i < indices.size(); ++i) {
    const RigCamera& camera = rig[indices[i]];
    BCOT_ASSIGN_OR_RETURN(const ChromaSampling chroma,
                          ResolveChromaSampling(sequence, indices[i], options.chroma_sampling));
    views.push_back({camera.camera, camera.cam_from_rig,
                     selection.weights.empty() ? 1.0 : selection.weights[i], chroma});
  }
  *rig_indices = indices;
  return views;
}

// The images of `frame` from the selected cameras (SelectViews), decoded concurrently (through
// `cache` when given); the first failure in view order is reported.
StatusOr<std::vector<cv::Mat3b>> ReadFrameImages(const Sequence& sequence,
                                                 const std::vector<int>& rig_indices,
                                                 const std::vector<TrackedView>& views, int frame,
                                                 DecodedImageCache* cache) {
  std::vector<StatusOr<cv::Mat3b>> read(rig_indices.size(), Status::Internal("not read"));
  tbb::parallel_for(size_t{0}, rig_indices.size(), [&](size_t v) {
    read[v] = ReadCameraImage(sequence.image_paths[rig_indices[v]][frame], views[v].camera, cache);
  });
  std::vector<cv::Mat3b> images;
  for (StatusOr<cv::Mat3b>& image : read) {
    if (!image.ok()) return image.status();
    images.push_back(std::move(image).value());
  }
  return images;
}

// What the tracker decoded the edges with, for image_response.yaml.
ImageResponseRecord ImageResponseRecordOf(const MultiViewTracker& tracker) {
  ImageResponseRecord record;
  record.response = tracker.image_response();
  const std::optional<StatusOr<ResponseEstimate>>& estimate = tracker.response_estimate();
  if (estimate.has_value() && estimate->ok()) {
    record.estimated = true;
    record.scores = (*estimate)->scores;
  } else if (estimate.has_value()) {
    record.estimate_error = estimate->status().message();
  } else if (!tracker.options().frame.edge.lines.response.IsResolved()) {
    record.estimate_error = "not estimated: no frame was initialised with the edge stage on";
  }
  return record;
}

}  // namespace

StatusOr<ChromaSampling> ResolveChromaSampling(const Sequence& sequence, int index,
                                               ChromaSamplingSetting setting) {
  switch (setting) {
    case ChromaSamplingSetting::kFull:
      return ChromaSampling::Full();
    case ChromaSamplingSetting::kJpeg420:
      return ChromaSampling::Jpeg420();
    case ChromaSamplingSetting::kJpeg422:
      return ChromaSampling::Jpeg422();
    case ChromaSamplingSetting::kAuto:
      break;
  }
  if (sequence.image_paths[index].empty()) return ChromaSampling::Full();
  return ReadChromaSampling(sequence.image_paths[index].front());
}

std::string FormatFramesCsv(const SequenceAnnotation& annotation) {
  std::string csv = "frame,termination,rounds,iterations,initial_energy,final_energy";
  for (const std::string& name : annotation.view_names) csv += ",energy_" + name;
  for (const std::string& name : annotation.view_names) csv += ",pixels_" + name;
  for (const std::string& name : annotation.view_names) csv += ",edge_lines_" + name;
  csv += ",milliseconds,window_rotation_deg,window_translation_mm\n";
  for (size_t f = 0; f < annotation.frames.size(); ++f) {
    const AnnotatedFrame& frame = annotation.frames[f];
    const FrameSummary& s = frame.summary;
    csv += fmt::format("{},{},{},{},{:.6g},{:.6g}", annotation.first_frame + f,
                       FrameTerminationName(s.termination), s.rounds, s.iterations,
                       s.initial_energy, s.final_energy);
    for (const FrameViewSummary& view : s.views) csv += fmt::format(",{:.6g}", view.energy);
    for (const FrameViewSummary& view : s.views) csv += fmt::format(",{}", view.pixels);
    for (const FrameViewSummary& view : s.views) csv += fmt::format(",{}", view.edge_lines);
    csv += fmt::format(",{:.1f},{:.6g},{:.6g}\n", frame.milliseconds, frame.window_rotation_deg,
                       frame.window_translation_mm);
  }
  return csv;
}

std::string AnnotateConfigHash(const AnnotateOptions& options) {
  ContentHash hash;
  hash.Add(FormatAnnotateOptions(options));
  return hash.Hex();
}

StatusOr<std::string> SequenceInputHash(const Sequence& sequence) {
  ContentHash hash;
  const std::string dir = sequence.dir;
  std::vector<std::string> paths = {dir + "/rig.yaml", dir + "/object.yaml",
                                    sequence.object.mesh_path};
  if (sequence.init_rig_from_object.has_value()) paths.push_back(dir + "/init_pose.txt");
  for (const std::string& path : paths) {
    StatusOr<std::string> content = ReadTextFile(path);
    if (!content.ok()) return content.status();
    hash.Add(*content);
  }
  if (!sequence.keyframes_path.empty()) {
    BCOT_ASSIGN_OR_RETURN(const std::string keyframes, ReadTextFile(sequence.keyframes_path));
    hash.Add("keyframes");
    hash.Add(keyframes);
  }
  for (const std::vector<std::string>& camera : sequence.image_paths) {
    for (const std::string& path : camera) {
      std::error_code error;
      const uintmax_t size = std::filesystem::file_size(path, error);
      if (error) return Status::IoError(path + ": " + error.message());
      hash.Add(std::filesystem::path(path).filename().string() + ":" + std::to_string(size));
    }
  }
  return hash.Hex();
}

StatusOr<SequenceAnnotation> AnnotateSequence(const Sequence& sequence,
                                              const AnnotateOptions& options,
                                              const AnnotateProgress& progress,
                                              const AnnotateFrameObserver& observer) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  return AnnotateSequence(sequence, RayCaster(mesh), options, progress, observer);
}

StatusOr<SequenceAnnotation> AnnotateSequence(const Sequence& sequence, const RayCaster& caster,
                                              const AnnotateOptions& options,
                                              const AnnotateProgress& progress,
                                              const AnnotateFrameObserver& observer,
                                              DecodedImageCache* images) {
  FrameSpan span;
  span.end = sequence.num_frames;
  return AnnotateFrames(sequence, caster, options, span, progress, observer, images);
}

StatusOr<RefinedFrame> RefineFrame(const Sequence& sequence, const RayCaster& caster,
                                   const AnnotateOptions& options, int frame,
                                   const Eigen::Isometry3d& rig_from_object) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  if (frame < 0 || frame >= sequence.num_frames) {
    return Status::InvalidInput(
        fmt::format("frame {}: the sequence has frames 0..{}", frame, sequence.num_frames - 1));
  }
  std::vector<int> rig_indices;
  BCOT_ASSIGN_OR_RETURN(std::vector<TrackedView> views,
                        SelectViews(sequence, options, &rig_indices));
  BCOT_ASSIGN_OR_RETURN(std::vector<cv::Mat3b> images,
                        ReadFrameImages(sequence, rig_indices, views, frame, nullptr));
  BCOT_ASSIGN_OR_RETURN(const std::optional<RotationalSymmetry> symmetry,
                        ObjectSymmetry(caster, options));
  BCOT_ASSIGN_OR_RETURN(
      std::unique_ptr<MultiViewTracker> tracker,
      MultiViewTracker::Create(caster, std::move(views), options.tracker, symmetry));
  const Eigen::Isometry3d objcentre_from_template = caster.mesh().objcentre_from_template();
  Eigen::Isometry3d rig_from_objcentre = rig_from_object * objcentre_from_template.inverse();
  RefinedFrame refined;
  BCOT_ASSIGN_OR_RETURN(refined.summary, tracker->Initialize(images, &rig_from_objcentre));
  refined.rig_from_object = rig_from_objcentre * objcentre_from_template;
  return refined;
}

StatusOr<SequenceAnnotation> AnnotateFrames(const Sequence& sequence, const RayCaster& caster,
                                            const AnnotateOptions& options, const FrameSpan& span,
                                            const AnnotateProgress& progress,
                                            const AnnotateFrameObserver& observer,
                                            DecodedImageCache* images) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  const std::vector<Eigen::Isometry3d>& existing = span.existing_rig_from_object;
  if (!(0 <= span.first && span.first < span.end && span.end <= sequence.num_frames)) {
    return Status::InvalidInput(fmt::format("frames {}:{}: outside the sequence's frames 0:{}",
                                            span.first, span.end - 1, sequence.num_frames - 1));
  }
  if (!existing.empty() && static_cast<int>(existing.size()) != sequence.num_frames) {
    return Status::InvalidInput(fmt::format("the existing annotation has {} poses for {} frames",
                                            existing.size(), sequence.num_frames));
  }
  std::vector<int> rig_indices;
  StatusOr<std::vector<TrackedView>> views = SelectViews(sequence, options, &rig_indices);
  if (!views.ok()) return views.status();
  const Mesh& mesh = caster.mesh();
  using AnchorMap = std::map<int, Eigen::Isometry3d>;
  BCOT_ASSIGN_OR_RETURN(AnchorMap anchors,
                        AnchorPoses(sequence, *views, mesh, span.first, span.end));
  // Re-annotating a span of an existing annotation: tracking continues from the pose before it,
  // unless a keyframe starts the span.
  if (!existing.empty() && span.first > 0 && anchors.count(span.first) == 0) {
    anchors[span.first - 1] = existing[span.first - 1];
  }
  std::vector<SymmetryCandidate> symmetry_candidates;
  BCOT_ASSIGN_OR_RETURN(const std::optional<RotationalSymmetry> symmetry,
                        ObjectSymmetry(caster, options, &symmetry_candidates));
  if (symmetry.has_value()) {
    // Each anchor (a hand-set pose has its own angle about the axis) turned about the axis to
    // the angle nearest the one before it, so that every tracking segment keeps one angle.
    for (auto it = anchors.begin(); it != anchors.end() && std::next(it) != anchors.end(); ++it) {
      std::next(it)->second = symmetry->HoldAngle(std::next(it)->second, it->second);
    }
  }
  if (anchors.empty()) {
    return Status::NotFound(fmt::format(
        "{}: no pose to start tracking from in frames {}:{} (init_pose.txt for frame 0, a "
        "keyframe, or an existing annotation before the range)",
        sequence.dir, span.first, span.end - 1));
  }
  StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
      MultiViewTracker::Create(caster, *views, options.tracker, symmetry);
  if (!tracker.ok()) return tracker.status();

  SequenceAnnotation annotation;
  annotation.symmetry = symmetry;
  annotation.symmetry_candidates = std::move(symmetry_candidates);
  annotation.first_frame = span.first;
  for (const TrackedView& view : *views) annotation.view_names.push_back(view.camera.name);
  const Eigen::Isometry3d objcentre_from_template = mesh.objcentre_from_template();
  const Eigen::Isometry3d template_from_objcentre = objcentre_from_template.inverse();
  std::optional<RotationalSymmetry> symmetry_in_objcentre;
  if (symmetry.has_value()) symmetry_in_objcentre = symmetry->Transformed(objcentre_from_template);
  // A pose turned about the symmetry axis to the angle nearest `reference` (both
  // rig_from_objcentre); unchanged for an asymmetric object.
  const auto hold_angle = [&](const Eigen::Isometry3d& pose, const Eigen::Isometry3d& reference) {
    return symmetry_in_objcentre.has_value() ? symmetry_in_objcentre->HoldAngle(pose, reference)
                                             : pose;
  };
  // The window sees frames [window_first, window_end): the span and, around it, the existing
  // poses its priors reach, held constant (no templates).
  const int margin = existing.empty() ? 0 : WindowMargin(options.window, sequence.num_frames);
  const int window_first = std::max(0, span.first - margin);
  const int window_end = std::min(sequence.num_frames, span.end + margin);
  std::unique_ptr<WindowSmoother> window;
  const auto push_held = [&](int first, int end) {
    for (int frame = first; frame < end; ++frame) {
      window->Push(existing[frame] * template_from_objcentre, {});
    }
  };
  if (options.window.enabled) {
    window = std::make_unique<WindowSmoother>(options.window, symmetry_in_objcentre);
    std::map<int, Eigen::Isometry3d> keyframe_anchors;
    for (const auto& [frame, rig_from_object] : anchors) {
      if (sequence.keyframes.count(frame) != 0 && frame >= span.first && frame < span.end) {
        keyframe_anchors[frame - window_first] = rig_from_object * template_from_objcentre;
      }
    }
    window->SetAnchors(std::move(keyframe_anchors));
    push_held(window_first, span.first);
  }
  const bool keep_templates = window || observer;

  const auto read_images = [&](int frame) {
    return ReadFrameImages(sequence, rig_indices, *views, frame, images);
  };
  // One solved frame before it is recorded (backward segments are recorded in frame order).
  struct Solved {
    AnnotatedFrame record;
    Eigen::Isometry3d rig_from_objcentre;
    std::vector<ViewLinearisation> linearisations;
  };
  const auto solve = [&](int frame, bool initialize,
                         Eigen::Isometry3d* rig_from_objcentre) -> StatusOr<Solved> {
    BCOT_ASSIGN_OR_RETURN(const std::vector<cv::Mat3b> images, read_images(frame));
    Solved solved;
    const auto start = std::chrono::steady_clock::now();
    std::vector<ViewLinearisation>* templates_out =
        keep_templates ? &solved.linearisations : nullptr;
    BCOT_ASSIGN_OR_RETURN(solved.record.summary,
                          initialize
                              ? (*tracker)->Initialize(images, rig_from_objcentre, templates_out)
                              : (*tracker)->Track(images, rig_from_objcentre, templates_out));
    solved.record.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    solved.rig_from_objcentre = *rig_from_objcentre;
    return solved;
  };
  const int span_frames = span.end - span.first;
  const auto record = [&](int frame, Solved solved) {
    if (frame < span.first) return;  // the existing pose before the span only starts tracking
    BCOT_CHECK(frame == span.first + static_cast<int>(annotation.frames.size()));
    if (!solved.record.summary.usable()) ++annotation.failed_frames;
    annotation.frames.push_back(solved.record);
    annotation.rig_from_object.push_back(solved.rig_from_objcentre * objcentre_from_template);
    if (observer) observer(frame, solved.rig_from_objcentre, solved.linearisations);
    if (window) window->Push(solved.rig_from_objcentre, std::move(solved.linearisations));
    if (progress) progress(frame + 1 - span.first, span_frames);
  };

  // Between two anchors a < b each frame is solved twice, forwards from a and backwards from b;
  // the solve of the nearer anchor (tracking_plan.h) is kept unless the two disagree and the
  // other one scores better (pose_scorer.h: colour models learned at each pose, so the scores
  // compare), e.g. when tracking from the nearer anchor lost the object at a jump between it
  // and the frame. Poses within these bounds agree:
  constexpr double kAgreeDeg = 2.0;
  const double agree_mm = 0.02 * mesh.diameter();
  Rig view_rig;
  for (const TrackedView& view : *views) view_rig.Add({view.camera, view.cam_from_rig});
  struct OtherSolve {
    Eigen::Isometry3d rig_from_objcentre = Eigen::Isometry3d::Identity();
    bool usable = false;
  };
  const auto choose = [&](int frame, Solved nearer, const OtherSolve& other) -> StatusOr<Solved> {
    if (!other.usable) return nearer;
    const Eigen::Isometry3d other_pose =
        hold_angle(other.rig_from_objcentre, nearer.rig_from_objcentre);
    const bool agree =
        nearer.record.summary.usable() &&
        RotationDistanceDeg(nearer.rig_from_objcentre.linear(), other_pose.linear()) <= kAgreeDeg &&
        (nearer.rig_from_objcentre.translation() - other_pose.translation()).norm() <= agree_mm;
    if (agree) return nearer;
    BCOT_ASSIGN_OR_RETURN(const std::vector<cv::Mat3b> images, read_images(frame));
    const PoseScorer scorer(caster, view_rig, images, PoseScorerOptions());
    const double nearer_score = nearer.record.summary.usable()
                                    ? scorer.Score(nearer.rig_from_objcentre)
                                    : std::numeric_limits<double>::infinity();
    if (!(scorer.Score(other_pose) < nearer_score)) return nearer;
    // The frame is solved again from the other pose, so that its record and templates are a
    // solve's (the tracker restarts there, as at an anchor).
    Eigen::Isometry3d rig_from_objcentre = other_pose;
    return solve(frame, /*initialize=*/true, &rig_from_objcentre);
  };

  // Tracking plans in frames counted from the first anchor or the span, whichever is earlier.
  const int plan_first = std::min(span.first, anchors.begin()->first);
  std::vector<int> anchor_frames;
  for (const auto& anchor : anchors) anchor_frames.push_back(anchor.first - plan_first);
  const std::vector<TrackingSegment> segments = PlanTracking(anchor_frames, span.end - plan_first);
  for (size_t s = 0; s < segments.size(); ++s) {
    const TrackingSegment& segment = segments[s];
    const int anchor = plan_first + segment.anchor;
    const int first = plan_first + segment.first;
    const int end = plan_first + segment.end;
    Eigen::Isometry3d rig_from_objcentre = anchors.at(anchor) * template_from_objcentre;
    const bool gap = !segment.backward && s + 1 < segments.size() && segments[s + 1].backward &&
                     plan_first + segments[s + 1].first == end;
    if (gap) {
      // Frames [a, mid) belong to anchor a, [mid, b) to anchor b; both passes cover (a, b).
      const int a = anchor, mid = end, b = plan_first + segments[s + 1].anchor;
      std::vector<Solved> forward;
      std::vector<OtherSolve> forward_other(b - mid);
      for (int frame = a; frame < b; ++frame) {
        BCOT_ASSIGN_OR_RETURN(Solved solved, solve(frame, frame == a, &rig_from_objcentre));
        if (frame < mid) {
          forward.push_back(std::move(solved));
        } else {
          forward_other[frame - mid] = {solved.rig_from_objcentre, solved.record.summary.usable()};
        }
      }
      // Anchor b at the angle about a symmetry axis the forward pass arrived with (frame b − 1),
      // also for the segment that starts at b.
      rig_from_objcentre = hold_angle(anchors.at(b) * template_from_objcentre, rig_from_objcentre);
      anchors[b] = rig_from_objcentre * objcentre_from_template;
      BCOT_RETURN_IF_ERROR(solve(b, true, &rig_from_objcentre).status());
      std::vector<Solved> backward(b - mid);
      std::vector<OtherSolve> backward_other(mid - a);  // frame a has none: it is the anchor
      for (int frame = b - 1; frame > a; --frame) {
        BCOT_ASSIGN_OR_RETURN(Solved solved, solve(frame, false, &rig_from_objcentre));
        if (frame >= mid) {
          backward[frame - mid] = std::move(solved);
        } else {
          backward_other[frame - a] = {solved.rig_from_objcentre, solved.record.summary.usable()};
        }
      }
      for (int frame = a; frame < b; ++frame) {
        BCOT_ASSIGN_OR_RETURN(
            Solved chosen,
            frame < mid
                ? choose(frame, std::move(forward[frame - a]), backward_other[frame - a])
                : choose(frame, std::move(backward[frame - mid]), forward_other[frame - mid]));
        record(frame, std::move(chosen));
      }
      ++s;  // the backward segment of the gap is done
      continue;
    }
    if (segment.backward) {
      // Before the first anchor. The anchor frame starts the tracker; its forward segment
      // records it.
      BCOT_RETURN_IF_ERROR(solve(anchor, true, &rig_from_objcentre).status());
      std::vector<Solved> solved(end - first);
      for (int frame = end - 1; frame >= first; --frame) {
        BCOT_ASSIGN_OR_RETURN(solved[frame - first], solve(frame, false, &rig_from_objcentre));
      }
      for (int frame = first; frame < end; ++frame) record(frame, std::move(solved[frame - first]));
      continue;
    }
    for (int frame = first; frame < end; ++frame) {
      BCOT_ASSIGN_OR_RETURN(Solved solved, solve(frame, frame == anchor, &rig_from_objcentre));
      record(frame, std::move(solved));
    }
  }
  annotation.image_response = ImageResponseRecordOf(**tracker);
  annotation.per_frame_rig_from_object = annotation.rig_from_object;
  if (window) {
    push_held(span.end, window_end);
    window->Finish();
    Eigen::Isometry3d previous_smoothed = Eigen::Isometry3d::Identity();  // rig_from_objcentre
    for (int i = 0; i < span_frames; ++i) {
      // For a body of revolution, each frame turned about the axis to the angle nearest the
      // frame before it (the first: nearest its per-frame pose), as the tracker holds it.
      previous_smoothed = hold_angle(
          window->rig_from_objcentre()[span.first + i - window_first],
          i == 0 ? annotation.rig_from_object[0] * template_from_objcentre : previous_smoothed);
      const Eigen::Isometry3d smoothed = previous_smoothed * objcentre_from_template;
      AnnotatedFrame& record = annotation.frames[i];
      record.window_rotation_deg =
          RotationDistanceDeg(annotation.rig_from_object[i].linear(), smoothed.linear());
      record.window_translation_mm =
          (annotation.rig_from_object[i].translation() - smoothed.translation()).norm();
      annotation.rig_from_object[i] = smoothed;
    }
  }
  return annotation;
}

Status WriteAnnotation(const std::string& out_dir, const Sequence& sequence,
                       const AnnotateOptions& options, const std::string& input_hash,
                       const SequenceAnnotation& annotation) {
  BCOT_RETURN_IF_ERROR(WriteAnnotationPoses(out_dir, sequence.rig, annotation.rig_from_object));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/frames.csv", FormatFramesCsv(annotation)));
  BCOT_RETURN_IF_ERROR(WriteImageResponseFile(out_dir, annotation.image_response));
  const std::string config = FormatAnnotateOptions(options);
  const Provenance provenance = CurrentProvenance(AnnotateConfigHash(options));
  const std::string header = fmt::format(
      "# bcot annotate: fully resolved options\n# bcot_version: {}\n# created_utc: {}\n"
      "# config_hash: {}\n# sequence: {}\n# input_hash: {}\n",
      provenance.bcot_version, provenance.created_utc, provenance.config_hash, sequence.dir,
      input_hash);
  return WriteFileAtomic(out_dir + "/config.resolved.yaml", header + config);
}

StatusOr<Sequence> LoadSequenceToAnnotate(const std::string& sequence_dir,
                                          const AnnotateInputs& inputs, bool require_anchor) {
  BCOT_ASSIGN_OR_RETURN(Sequence sequence, LoadSequence(sequence_dir, /*require_init_pose=*/false));
  if (!inputs.keyframes_path.empty()) {
    BCOT_RETURN_IF_ERROR(LoadKeyframes(
        std::filesystem::absolute(inputs.keyframes_path).lexically_normal().string(), &sequence));
  }
  if (require_anchor && !sequence.init_rig_from_object.has_value() && sequence.keyframes.empty()) {
    return Status::NotFound(fmt::format(
        "{}/init_pose.txt: not found; it holds one pose line, the rough rig_from_object of frame "
        "0 (or give keyframes: keyframes.txt or --keyframes FILE)",
        sequence.dir));
  }
  return sequence;
}

StatusOr<AnnotationOutcome> AnnotateSequenceDir(const std::string& sequence_dir,
                                                const std::string& out_dir,
                                                const AnnotateOptions& options,
                                                const AnnotateProgress& progress) {
  return AnnotateSequenceDir(sequence_dir, out_dir, options, AnnotateInputs(), progress);
}

StatusOr<AnnotationOutcome> AnnotateSequenceDir(const std::string& sequence_dir,
                                                const std::string& out_dir,
                                                const AnnotateOptions& options,
                                                const AnnotateInputs& inputs,
                                                const AnnotateProgress& progress) {
  if (!inputs.frames.empty()) {
    // A splice needs a finished annotation (SpliceFrames says so when there is none).
    std::optional<OutputLock> lock;
    if (std::filesystem::is_directory(out_dir)) {
      BCOT_ASSIGN_OR_RETURN(lock, OutputLock::Acquire(out_dir));
    }
    return SpliceFrames(sequence_dir, out_dir, options, inputs, progress);
  }
  // An absolute path, so DONE lets `bcot report` find the images again.
  BCOT_ASSIGN_OR_RETURN(
      const Sequence sequence,
      LoadSequenceToAnnotate(std::filesystem::absolute(sequence_dir).lexically_normal().string(),
                             inputs));
  BCOT_ASSIGN_OR_RETURN(const std::string input_hash, SequenceInputHash(sequence));
  // The output must be ours and writable before the solve, not after it.
  BCOT_RETURN_IF_ERROR(
      CheckAnnotationOutputDir(out_dir, sequence.dir, sequence.rig, inputs.overwrite));
  BCOT_RETURN_IF_ERROR(CheckWritableDirectory(out_dir));
  BCOT_ASSIGN_OR_RETURN(const OutputLock lock, OutputLock::Acquire(out_dir));
  // A directory holding DONE is complete; take DONE away before anything in it changes.
  BCOT_RETURN_IF_ERROR(RemoveDoneFile(out_dir));
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  const RayCaster caster(mesh);
  // The quality check reads the frames again, after the window has settled the poses.
  DecodedImageCache images(inputs.image_cache_bytes());
  BCOT_ASSIGN_OR_RETURN(const SequenceAnnotation annotation,
                        AnnotateSequence(sequence, caster, options, progress, {}, &images));
  BCOT_RETURN_IF_ERROR(WriteAnnotation(out_dir, sequence, options, input_hash, annotation));
  BCOT_ASSIGN_OR_RETURN(
      QualityReport quality,
      MeasureQuality(sequence, caster, annotation.rig_from_object, annotation.view_names,
                     options.quality, annotation.image_response.response, &images));
  BCOT_ASSIGN_OR_RETURN(
      AnnotationOutcome outcome,
      FinishAnnotation(out_dir, sequence, caster, options, input_hash, annotation.rig_from_object,
                       std::move(quality), annotation.failed_frames));
  // The capture and symmetry notes first, then FinishAnnotation's from the quality check.
  std::vector<std::string> notes = CaptureNotes(sequence);
  for (std::string& note : SymmetryNotes(annotation, options.symmetry.detection.tolerance)) {
    notes.push_back(std::move(note));
  }
  notes.insert(notes.end(), outcome.notes.begin(), outcome.notes.end());
  outcome.notes = std::move(notes);
  return outcome;
}

std::vector<std::string> SymmetryNotes(const SequenceAnnotation& annotation, double tolerance) {
  constexpr double kNearMissFactor = 10.0;
  if (annotation.symmetry.has_value()) {
    const Eigen::Vector3d& a = annotation.symmetry->axis;
    const Eigen::Vector3d& p = annotation.symmetry->point;
    return {fmt::format(
        "the object is a body of revolution about the axis ({:.3f}, {:.3f}, {:.3f}) through "
        "({:.2f}, {:.2f}, {:.2f}) mm of its mesh frame: no image shows its angle about that "
        "axis, so the poses keep the angle of the first pose (init_pose.txt or a keyframe); set "
        "symmetry.detect: false if its texture makes the angle visible (docs/method.md, "
        "\"Symmetric objects\")",
        a.x(), a.y(), a.z(), p.x(), p.y(), p.z())};
  }
  std::vector<std::string> notes;
  for (const SymmetryCandidate& candidate : annotation.symmetry_candidates) {
    if (candidate.displacement > kNearMissFactor * tolerance) continue;
    const Eigen::Vector3d& a = candidate.symmetry.axis;
    notes.push_back(fmt::format(
        "the object is nearly a body of revolution about the axis ({:.3f}, {:.3f}, {:.3f}) of "
        "its mesh frame: a turn about it changes the silhouette by {:.2g} of the diameter, more "
        "than symmetry.tolerance ({:.2g}), so the angle about it is solved like any other; if "
        "the real object is round (a scanned or faceted mesh) and its poses turn about that "
        "axis from frame to frame, raise symmetry.tolerance above {:.2g} (docs/method.md, "
        "\"Symmetric objects\")",
        a.x(), a.y(), a.z(), candidate.displacement, tolerance, candidate.displacement));
  }
  return notes;
}

std::vector<std::string> CaptureNotes(const Sequence& sequence) {
  std::vector<std::string> subsampled;
  for (int v = 0; v < sequence.rig.size(); ++v) {
    if (sequence.image_paths[v].empty()) continue;
    const StatusOr<ChromaSampling> sampling = ReadChromaSampling(sequence.image_paths[v].front());
    if (sampling.ok() && sampling->subsampled()) {
      subsampled.push_back(sequence.rig[v].camera.name + " (" + sampling->Name() + ")");
    }
  }
  if (subsampled.empty()) return {};
  return {fmt::format(
      "{}: JPEG frames with subsampled chroma: colour is kept at half resolution, which blurs "
      "and shifts the edges the annotation is measured on; the edge stage takes part of the "
      "shift off (edge.chroma_sampling), but on our renders the rotation error was still a "
      "third to a half above PNG frames', and a saturated object whose red clipped sat "
      "0.05-0.06 mm too high in both cameras; record PNG or 4:4:4 JPEG if you can "
      "(docs/notes/issue12_jpeg_chroma.md)",
      fmt::join(subsampled, ", "))};
}

StatusOr<AnnotationOutcome> FinishAnnotation(const std::string& out_dir, const Sequence& sequence,
                                             const RayCaster& caster,
                                             const AnnotateOptions& options,
                                             const std::string& input_hash,
                                             const std::vector<Eigen::Isometry3d>& rig_from_object,
                                             QualityReport quality, int failed_frames) {
  quality.provenance = CurrentProvenance(AnnotateConfigHash(options));
  BCOT_RETURN_IF_ERROR(WriteQualityFiles(out_dir, quality, sequence, caster, rig_from_object));
  AnnotationOutcome outcome;
  outcome.notes = SaturationWarnings(quality);
  outcome.verdict = VerdictOf(quality);
  outcome.frames = static_cast<int>(rig_from_object.size());
  outcome.failed_frames = failed_frames;
  DoneRecord done;
  done.config_hash = AnnotateConfigHash(options);
  done.input_hash = input_hash;
  done.sequence_dir = sequence.dir;
  done.frames = outcome.frames;
  done.failed_frames = outcome.failed_frames;
  BCOT_RETURN_IF_ERROR(WriteDoneFile(out_dir, done));
  return outcome;
}

}  // namespace bcot
