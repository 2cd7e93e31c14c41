// `bcot synth`: synthetic multi-view sequences with exact ground truth (paper §5.1,
// supplement §B), written in the sequence-directory input contract (DESIGN.md):
//
//   <out>/rig.yaml, object.yaml, model/<name>.<ext> (the mesh, unit_to_mm in object.yaml),
//   <out>/<camera>/000000.png ..., init_pose.txt, timestamps.csv,
//   <out>/gt/rig_from_object.txt (one line per frame), gt/<camera>/pose.txt (cam_from_object),
//   <out>/gt/world_from_rig.txt, gt/world_from_object.txt, synth.resolved.yaml,
//   optionally gt/<camera>/coverage_000000.png (8-bit object coverage).
// Poses refer to the mesh template frame O_t, translations in mm; rig frame = C-0's frame.
//
// Rendering. The object and distractor meshes are ray-cast with Embree (RayCaster), n×n
// samples per pixel (render.object_samples_per_axis) inside the object's projected box and
// render.background_samples_per_axis elsewhere; every sample takes the nearest of object,
// distractors, the view's backdrop plane and the table plane (all fixed in the world and
// intersected analytically, so a moving rig sees correct parallax), and pixels are box
// averages of their samples. Rays come from Camera::PixelToRay, so lens distortion is
// rendered exactly as rig.yaml states it. The backdrop of view i is seen by view i only (each
// camera has its own wall behind the object, so wide arcs never look at another view's wall
// from behind); distractors and the table are shared by all views.
//
// Determinism: all randomness derives from options.seed; per-pixel noise is a hash of
// (seed, view, frame, pixel), so output files are identical for any thread count.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bcot/core/rig.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synth_scene.h"

namespace bcot {

// One render of one view: linear RGB radiance and the object's anti-aliased coverage (the
// fraction of each pixel's samples where the object is the nearest surface), image size.
struct SynthViewRender {
  cv::Mat3f radiance;
  cv::Mat1f coverage;
};

// The scene of one synthetic sequence: cameras, trajectories, object, distractors,
// backgrounds and light, all built from the options. Thread safety: const methods may run
// concurrently.
class SynthWorld {
 public:
  static StatusOr<std::unique_ptr<SynthWorld>> Create(const SynthOptions& options);
  ~SynthWorld();
  SynthWorld(const SynthWorld&) = delete;
  SynthWorld& operator=(const SynthWorld&) = delete;

  const SynthOptions& options() const;
  const Rig& rig() const;
  const std::vector<SynthCamera>& cameras() const;
  const SynthMotion& motion() const;
  int num_frames() const;
  int num_distractors() const;

  // The object mesh in mm (O_t) exactly as the annotator loads it from the written sequence.
  const Mesh& object_mesh() const;
  const RayCaster& object_caster() const;
  const std::string& object_name() const;
  double object_unit_to_mm() const;

  // Ground truth at (possibly fractional) frame time t.
  Eigen::Isometry3d RigFromObject(double t) const;
  Eigen::Isometry3d CamFromObject(int view, double t) const;

  // One render of `view` at time t: no motion blur, no sensor effects.
  SynthViewRender RenderView(int view, double t) const;
  // The frame as written: motion-blur average of RenderView over the exposure, then the
  // sensor model; BGR 8-bit. `coverage` (optional) receives the exposure-averaged coverage.
  cv::Mat3b RenderFrame(int view, int frame, cv::Mat1f* coverage = nullptr) const;

  // Writes the model file (copied, or the built-in mesh as OBJ) to `path` atomically.
  Status WriteModel(const std::string& path) const;
  // "model/<name>.<ext>" (relative to the sequence directory).
  std::string ModelRelativePath() const;

 private:
  struct Impl;
  explicit SynthWorld(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Called after each finished frame (from worker threads, serialised): frames done, total.
using SynthProgress = std::function<void(int frames_done, int num_frames)>;

// Validates the options, builds the world and writes the sequence to `out_dir`, which must
// not exist or be empty (kInvalidConfig otherwise). Frames render in parallel
// (render.threads). kInvalidConfig for option problems (including an object that leaves a
// view), kNotFound/kInvalidInput for unreadable meshes or photos, kIoError for write errors.
Status Synthesize(const SynthOptions& options, const std::string& out_dir,
                  const SynthProgress& progress = {});

}  // namespace bcot
