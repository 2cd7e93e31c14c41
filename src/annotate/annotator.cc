#include "bcot/annotate/annotator.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <system_error>

#include "bcot/annotate/done_file.h"
#include "bcot/core/file_util.h"
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
Status CheckInitialPose(const Sequence& sequence, const std::vector<TrackedView>& views,
                        const Mesh& mesh) {
  const Eigen::Vector3d centre_in_rig = *sequence.init_rig_from_object * mesh.bbox_center();
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
  return Status::InvalidInput(
      fmt::format("{}/init_pose.txt: the object is not in view at frame 0: its centre is {}",
                  sequence.dir, places));
}

// FNV-1a, 64 bit: a stable content hash (not cryptographic; it detects changed inputs).
class Fnv1a {
 public:
  // Adds `bytes` and a field separator, so ("ab", "c") and ("a", "bc") differ.
  void Add(const std::string& bytes) {
    for (unsigned char byte : bytes) Mix(byte);
    Mix(0xff);
  }
  std::string Hex() const { return fmt::format("{:016x}", hash_); }

 private:
  void Mix(unsigned char byte) {
    hash_ ^= byte;
    hash_ *= 1099511628211ULL;
  }
  uint64_t hash_ = 14695981039346656037ULL;
};

// Indices into the rig of the cameras `selection` asks for, with their weights.
StatusOr<std::vector<TrackedView>> SelectViews(const Rig& rig, const ViewSelection& selection,
                                               std::vector<int>* rig_indices) {
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
    views.push_back({camera.camera, camera.cam_from_rig,
                     selection.weights.empty() ? 1.0 : selection.weights[i]});
  }
  *rig_indices = indices;
  return views;
}

std::string FramesCsv(const SequenceAnnotation& annotation) {
  std::string csv = "frame,termination,rounds,iterations,initial_energy,final_energy";
  for (const std::string& name : annotation.view_names) csv += ",energy_" + name;
  for (const std::string& name : annotation.view_names) csv += ",pixels_" + name;
  for (const std::string& name : annotation.view_names) csv += ",edge_lines_" + name;
  csv += ",milliseconds,window_rotation_deg,window_translation_mm\n";
  for (size_t f = 0; f < annotation.frames.size(); ++f) {
    const AnnotatedFrame& frame = annotation.frames[f];
    const FrameSummary& s = frame.summary;
    csv += fmt::format("{},{},{},{},{:.6g},{:.6g}", f, FrameTerminationName(s.termination),
                       s.rounds, s.iterations, s.initial_energy, s.final_energy);
    for (const FrameViewSummary& view : s.views) csv += fmt::format(",{:.6g}", view.energy);
    for (const FrameViewSummary& view : s.views) csv += fmt::format(",{}", view.pixels);
    for (const FrameViewSummary& view : s.views) csv += fmt::format(",{}", view.edge_lines);
    csv += fmt::format(",{:.1f},{:.6g},{:.6g}\n", frame.milliseconds, frame.window_rotation_deg,
                       frame.window_translation_mm);
  }
  return csv;
}

}  // namespace

std::string AnnotateConfigHash(const AnnotateOptions& options) {
  Fnv1a hash;
  hash.Add(FormatAnnotateOptions(options));
  return hash.Hex();
}

StatusOr<std::string> SequenceInputHash(const Sequence& sequence) {
  Fnv1a hash;
  const std::string dir = sequence.dir;
  for (const std::string& path : {dir + "/rig.yaml", dir + "/object.yaml",
                                  sequence.object.mesh_path, dir + "/init_pose.txt"}) {
    StatusOr<std::string> content = ReadTextFile(path);
    if (!content.ok()) return content.status();
    hash.Add(*content);
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
                                              const AnnotateFrameObserver& observer) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  if (!sequence.init_rig_from_object.has_value()) {
    return Status::NotFound(sequence.dir + "/init_pose.txt: missing (the pose of frame 0)");
  }
  std::vector<int> rig_indices;
  StatusOr<std::vector<TrackedView>> views = SelectViews(sequence.rig, options.views, &rig_indices);
  if (!views.ok()) return views.status();
  const Mesh& mesh = caster.mesh();
  BCOT_RETURN_IF_ERROR(CheckInitialPose(sequence, *views, mesh));
  StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
      MultiViewTracker::Create(caster, *views, options.tracker);
  if (!tracker.ok()) return tracker.status();

  SequenceAnnotation annotation;
  for (const TrackedView& view : *views) annotation.view_names.push_back(view.camera.name);
  const Eigen::Isometry3d objcentre_from_template = mesh.objcentre_from_template();
  const Eigen::Isometry3d template_from_objcentre = objcentre_from_template.inverse();
  Eigen::Isometry3d rig_from_objcentre = *sequence.init_rig_from_object * template_from_objcentre;
  std::unique_ptr<WindowSmoother> window;
  if (options.window.enabled) window = std::make_unique<WindowSmoother>(options.window);
  std::vector<ViewLinearisation> linearisations;
  std::vector<ViewLinearisation>* const templates_out =
      window || observer ? &linearisations : nullptr;

  for (int frame = 0; frame < sequence.num_frames; ++frame) {
    std::vector<cv::Mat3b> images;
    for (size_t v = 0; v < rig_indices.size(); ++v) {
      StatusOr<cv::Mat3b> image =
          ReadCameraImage(sequence.image_paths[rig_indices[v]][frame], (*views)[v].camera);
      if (!image.ok()) return image.status();
      images.push_back(*image);
    }
    const auto start = std::chrono::steady_clock::now();
    StatusOr<FrameSummary> summary =
        frame == 0 ? (*tracker)->Initialize(images, &rig_from_objcentre, templates_out)
                   : (*tracker)->Track(images, &rig_from_objcentre, templates_out);
    if (!summary.ok()) return summary.status();
    AnnotatedFrame record;
    record.summary = *summary;
    record.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!summary->usable()) ++annotation.failed_frames;
    annotation.frames.push_back(record);
    annotation.rig_from_object.push_back(rig_from_objcentre * objcentre_from_template);
    if (observer) observer(frame, rig_from_objcentre, linearisations);
    if (window) window->Push(rig_from_objcentre, std::move(linearisations));
    if (progress) progress(frame + 1, sequence.num_frames);
  }
  annotation.per_frame_rig_from_object = annotation.rig_from_object;
  if (window) {
    window->Finish();
    for (int frame = 0; frame < sequence.num_frames; ++frame) {
      const Eigen::Isometry3d smoothed =
          window->rig_from_objcentre()[frame] * objcentre_from_template;
      AnnotatedFrame& record = annotation.frames[frame];
      record.window_rotation_deg =
          RotationDistanceDeg(annotation.rig_from_object[frame].linear(), smoothed.linear());
      record.window_translation_mm =
          (annotation.rig_from_object[frame].translation() - smoothed.translation()).norm();
      annotation.rig_from_object[frame] = smoothed;
    }
  }
  return annotation;
}

Status WriteAnnotation(const std::string& out_dir, const Sequence& sequence,
                       const AnnotateOptions& options, const std::string& input_hash,
                       const SequenceAnnotation& annotation) {
  BCOT_RETURN_IF_ERROR(CreateDirectories(out_dir));
  BCOT_RETURN_IF_ERROR(WritePoseFile(out_dir + "/rig_from_object.txt", annotation.rig_from_object));
  for (const RigCamera& camera : sequence.rig.cameras()) {
    std::vector<Eigen::Isometry3d> cam_from_object;
    for (const Eigen::Isometry3d& rig_from_object : annotation.rig_from_object) {
      cam_from_object.push_back(camera.cam_from_rig * rig_from_object);
    }
    BCOT_RETURN_IF_ERROR(CreateDirectories(out_dir + "/" + camera.camera.name));
    BCOT_RETURN_IF_ERROR(
        WritePoseFile(out_dir + "/" + camera.camera.name + "/pose.txt", cam_from_object));
  }
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/frames.csv", FramesCsv(annotation)));
  const std::string config = FormatAnnotateOptions(options);
  const Provenance provenance = CurrentProvenance(AnnotateConfigHash(options));
  const std::string header = fmt::format(
      "# bcot annotate: fully resolved options\n# bcot_version: {}\n# created_utc: {}\n"
      "# config_hash: {}\n# sequence: {}\n# input_hash: {}\n",
      provenance.bcot_version, provenance.created_utc, provenance.config_hash, sequence.dir,
      input_hash);
  return WriteFileAtomic(out_dir + "/config.resolved.yaml", header + config);
}

StatusOr<AnnotationOutcome> AnnotateSequenceDir(const std::string& sequence_dir,
                                                const std::string& out_dir,
                                                const AnnotateOptions& options,
                                                const AnnotateProgress& progress) {
  // An absolute path, so DONE lets `bcot report` find the images again.
  BCOT_ASSIGN_OR_RETURN(
      const Sequence sequence,
      LoadSequence(std::filesystem::absolute(sequence_dir).lexically_normal().string(),
                   /*require_init_pose=*/true));
  BCOT_ASSIGN_OR_RETURN(const std::string input_hash, SequenceInputHash(sequence));
  // The output must be writable before the solve, not after it.
  BCOT_RETURN_IF_ERROR(CheckWritableDirectory(out_dir));
  // A directory holding DONE is complete; take DONE away before anything in it changes.
  BCOT_RETURN_IF_ERROR(RemoveDoneFile(out_dir));
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  const RayCaster caster(mesh);
  BCOT_ASSIGN_OR_RETURN(const SequenceAnnotation annotation,
                        AnnotateSequence(sequence, caster, options, progress));
  BCOT_RETURN_IF_ERROR(WriteAnnotation(out_dir, sequence, options, input_hash, annotation));
  BCOT_ASSIGN_OR_RETURN(QualityReport quality,
                        MeasureQuality(sequence, caster, annotation.rig_from_object,
                                       annotation.view_names, options.quality));
  quality.provenance = CurrentProvenance(AnnotateConfigHash(options));
  BCOT_RETURN_IF_ERROR(
      WriteQualityFiles(out_dir, quality, sequence, caster, annotation.rig_from_object));
  AnnotationOutcome outcome;
  outcome.verdict = VerdictOf(quality);
  outcome.frames = static_cast<int>(annotation.frames.size());
  outcome.failed_frames = annotation.failed_frames;
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
