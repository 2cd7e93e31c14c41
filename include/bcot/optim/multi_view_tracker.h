// Frame-to-frame pose tracking of one object seen by one or more calibrated views: owns the
// per-view colour models and applies the colour policy of DESIGN.md "Colour model" around
// FrameProblem (the joint solve of one frame).
//
//   Reset(images, T):      colour models learned from scratch at T; no solve.
//   Initialize(images, T): bootstrap of frame 0 from a rough T (init_pose.txt): up to
//                          `bootstrap_passes` times { learn the colour models from scratch at the
//                          current pose, solve }, until a pass moves the pose by less than the
//                          convergence thresholds. A colour model learned at a pose several degrees
//                          off mixes object and background colours and biases the minimum;
//                          re-learning it at the first solution removes most of that bias (measured
//                          on the bunny 5°/10 mm test: 1.0° → 0.03° after the second pass). These
//                          passes use the capture models (color.kind) only; with a separate
//                          refinement model (color.refine_kind), the models are then learned
//                          once more at the result and one more solve uses it: a local model
//                          learned at a pose degrees off has object and background swapped
//                          along parts of the contour and holds the pose there (measured: a
//                          5°/10 mm start ends 2.9° / 5.4 mm off without this order).
//   Track(images, T):      solve from T (the previous frame's pose) moved on by the motion between
//                          the two previous frames (velocity_prediction; not after Reset or
//                          Initialize, which forget the velocity) with the current models, then
//                          blend the models at the result (RBOT's temporal update). Real handheld
//                          motion reaches 40 mm and 25° per frame at 30 fps (BCOT), beyond what
//                          one linearised band can capture from the last pose. With
//                          viewpoint_model_for_two_views, a frame two views see is solved
//                          along the sparse viewpoint model instead (SeenByTwoViews).
//
// Image response. With frame.edge.lines.response = kAuto (and the edge stage on) the first
// Reset, or Initialize that solves, estimates the cameras' response from its frame at its pose
// (response_estimation.h); Initialize then solves the frame once more with it. Until then, and
// when the estimate fails, edges are decoded as sRGB. Every later solve uses image_response().
//
// Poses are rig_from_objcentre (O_o, see se3_manifold.h); images are in view order.
// Not thread-safe (the colour models change); one tracker per sequence.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/frame_problem.h"
#include "bcot/optim/response_estimation.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

// Where the colour models learn their samples after a solve (LearnColors).
enum class ColorSampleSource {
  kSilhouette,      // the silhouette rendered at the pose (ColorModel::Update)
  kViewpointModel,  // along the sparse viewpoint model's contour at the pose, without a render
                    // (ColorModel::UpdateAlongContour); needs frame.lines_from_viewpoint_model
};

struct MultiViewTrackerOptions {
  FrameProblemOptions frame;
  ColorModelOptions color;
  // kViewpointModel: with the region rounds' lines from the sparse viewpoint model, no frame
  // renders the object unless the edge stage or the quality check does (issue 19; precision and
  // time in docs/sparse_viewpoint_model.md).
  ColorSampleSource color_samples = ColorSampleSource::kSilhouette;
  // Tracked frames that two or more views see (SeenByTwoViews) solve their region rounds with
  // the sparse energy along the sparse viewpoint model and learn their colours along its contour
  // (the options above would say energy sparse, frame.lines_from_viewpoint_model and
  // kViewpointModel), without a render; the edge stage then places the contour from the
  // rendered silhouette. Frames that one view sees, and frame 0's bootstrap, keep `frame` and
  // `color_samples`: with one view the model's contour alone sets the depth, and it loses
  // frames there (docs/sparse_viewpoint_model.md). Needs frame.lines_from_viewpoint_model =
  // false (which applies the model to every frame).
  bool viewpoint_model_for_two_views = false;
  // Fraction of the last inter-frame motion (rotation about the object centre, displacement of
  // the centre, both in the rig frame) added to the last pose to start the next solve; in
  // [0, 1]. 0 = start at the last pose, 1 = constant velocity.
  double velocity_prediction = 1.0;
  // Most learn-and-solve passes of Initialize; >= 1. Passes stop early once one moved the pose
  // by less than both bootstrap_converged_deg (rotation) and bootstrap_converged_mm (object
  // centre): the colour models were then learned where the solve ends. Measured by
  // scripts/bench_init.sh (demo scene, 3 seeds): from 20° / 40 mm, frame 0 converges to the
  // accuracy of a 5° / 10 mm start in 3 of 3 (two fixed passes: 1 of 3), from 30° / 50 mm in
  // 1 of 3 (two passes: 0 of 3); see also the 15° / 30 mm tracker test.
  int bootstrap_passes = 8;
  // Convergence thresholds of the bootstrap passes; > 0.
  double bootstrap_converged_deg = 0.05;
  double bootstrap_converged_mm = 0.1;
  // Full-resolution rounds of each bootstrap solve (frame.rounds replaced); >= 0, 0 = frame.rounds.
  // Frame 0 starts from a rough pose and the colour models are learned where its solve ends,
  // so its region energy must converge on its own; a tracked frame starts within a fraction of
  // a pixel and may stop earlier (the edge stage places the contour). Annotation: 5 here,
  // frame.rounds 2 (a monocular pinion of the Cycles scenes is lost from frame 0 with 2 bootstrap
  // rounds, docs/notes/issue19_speed.md).
  int bootstrap_rounds = 0;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

struct TrackedView {
  Camera camera;
  Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
  double weight = 1.0;  // w_v >= 0 of eq. 8
  // How the view's images store chroma (FrameView::chroma).
  ChromaSampling chroma = ChromaSampling::Full();
};

class MultiViewTracker {
 public:
  // `caster` must outlive the tracker. `symmetry`: the mesh's rotational symmetry in O_t
  // (render/symmetry_detection.h), if any; no solve then turns the object about its axis
  // (FrameProblem). `viewpoint_model`: the caster's mesh's sparse viewpoint model for
  // frame.lines_from_viewpoint_model; when that option is on and none is given, the tracker
  // makes one that builds its viewpoints on demand (SparseViewpointModel::BuildOnDemand).
  // Errors: invalid options or cameras, no view, a negative or non-finite weight
  // (kInvalidConfig).
  static StatusOr<std::unique_ptr<MultiViewTracker>> Create(
      const RayCaster& caster, std::vector<TrackedView> views,
      const MultiViewTrackerOptions& options,
      const std::optional<RotationalSymmetry>& symmetry = std::nullopt,
      std::shared_ptr<const SparseViewpointModel> viewpoint_model = nullptr);

  // See the header comment. Images must match the views' camera sizes (else kInvalidInput).
  Status Reset(const std::vector<cv::Mat3b>& images, const Eigen::Isometry3d& rig_from_objcentre);
  // `linearisations`, when not null, receives the final solve's level-0 templates (see
  // FrameProblem::Solve), built with the colour models before this frame's update.
  StatusOr<FrameSummary> Initialize(const std::vector<cv::Mat3b>& images,
                                    Eigen::Isometry3d* rig_from_objcentre,
                                    std::vector<ViewLinearisation>* linearisations = nullptr);
  StatusOr<FrameSummary> Track(const std::vector<cv::Mat3b>& images,
                               Eigen::Isometry3d* rig_from_objcentre,
                               std::vector<ViewLinearisation>* linearisations = nullptr);

  const std::vector<TrackedView>& views() const { return views_; }
  const MultiViewTrackerOptions& options() const { return options_; }
  // The response the edges are decoded with (resolved; see "Image response" above).
  const ImageResponse& image_response() const { return image_response_; }
  // The estimate behind image_response() when the response is kAuto: empty until a Reset or
  // Initialize made one; an error status when the estimate failed (sRGB is used then).
  const std::optional<StatusOr<ResponseEstimate>>& response_estimate() const {
    return response_estimate_;
  }

 private:
  MultiViewTracker(const RayCaster& caster, std::vector<TrackedView> views,
                   const MultiViewTrackerOptions& options,
                   const std::optional<RotationalSymmetry>& symmetry,
                   std::shared_ptr<const SparseViewpointModel> viewpoint_model);
  Status CheckImages(const std::vector<cv::Mat3b>& images) const;
  // Updates every view's colour models at the pose; `fresh` replaces the models first.
  void LearnColors(const std::vector<cv::Mat3b>& images,
                   const Eigen::Isometry3d& rig_from_objcentre, bool fresh,
                   ColorSampleSource samples);
  // One joint solve by `problem` (problem_, bootstrap_problem_ or two_view_problem_); `refine` lets
  // the full-resolution rounds use the refinement models.
  FrameSummary Solve(const FrameProblem& problem, const std::vector<cv::Mat3b>& images,
                     Eigen::Isometry3d* rig_from_objcentre,
                     std::vector<ViewLinearisation>* linearisations, bool refine);
  // For a body of revolution, *rig_from_objcentre turned about the axis to the angle nearest
  // `reference` (RotationalSymmetry::HoldAngle): the solves never turn about the axis
  // (AxisLockedSe3Manifold), but their increments compose to a turn of second order (~0.01° per
  // frame), which this takes off. Then from one frame to the next the rotation has no part about
  // the axis at all. A no-op for other objects.
  void HoldSymmetryAngle(const Eigen::Isometry3d& reference,
                         Eigen::Isometry3d* rig_from_objcentre) const;
  // Whether two or more views of weight > 0 see the object centre of `rig_from_objcentre` in
  // front of them and inside their image (viewpoint_model_for_two_views).
  bool SeenByTwoViews(const Eigen::Isometry3d& rig_from_objcentre) const;
  // The frame's views for a FrameProblem (colour models by `refine` as in Solve).
  std::vector<FrameView> FrameViews(const std::vector<cv::Mat3b>& images, bool refine) const;
  // Decodes edges with `response` from now on (rebuilds the frame problems).
  void UseImageResponse(const ImageResponse& response);
  // With a kAuto response and the edge stage on, the first call estimates the response on this
  // frame at `rig_from_objcentre` (a solved or known pose); true when edges are decoded
  // differently from now on.
  bool ResolveImageResponse(const std::vector<cv::Mat3b>& images,
                            const Eigen::Isometry3d& rig_from_objcentre);

  const RayCaster& caster_;
  std::vector<TrackedView> views_;
  MultiViewTrackerOptions options_;
  std::optional<RotationalSymmetry> symmetry_;  // O_t
  // With options_.frame.lines_from_viewpoint_model or viewpoint_model_for_two_views, else null.
  std::shared_ptr<const SparseViewpointModel> viewpoint_model_;
  ImageResponse image_response_;
  std::optional<StatusOr<ResponseEstimate>> response_estimate_;
  // The frame problems of options_ with image_response_ (resolved) as the edge response.
  std::unique_ptr<FrameProblem> problem_;
  std::unique_ptr<FrameProblem> bootstrap_problem_;  // problem_ with bootstrap_rounds
  // With viewpoint_model_for_two_views: problem_ with the sparse energy along the model.
  std::unique_ptr<FrameProblem> two_view_problem_;
  std::vector<ViewColorModels> color_models_;  // per view
  // The estimate of the frame before the last one, when Track produced both.
  std::optional<Eigen::Isometry3d> previous_rig_from_objcentre_;
};

// T_last moved on by `fraction` of the motion from T_before to T_last (see
// MultiViewTrackerOptions::velocity_prediction). Poses are rig_from_objcentre.
Eigen::Isometry3d PredictPose(const Eigen::Isometry3d& rig_from_objcentre_before,
                              const Eigen::Isometry3d& rig_from_objcentre_last, double fraction);

}  // namespace bcot
