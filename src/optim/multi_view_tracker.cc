#include "bcot/optim/multi_view_tracker.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>
#include <utility>

#include "bcot/core/se3.h"
#include "bcot/core/violations.h"
#include "bcot/optim/silhouette.h"

namespace bcot {

namespace {

// The frame options of the frames two views see (viewpoint_model_for_two_views).
FrameProblemOptions TwoViewFrameOptions(const FrameProblemOptions& frame) {
  FrameProblemOptions two_views = frame;
  two_views.energy = RegionEnergy::kSparse;
  two_views.lines_from_viewpoint_model = true;
  return two_views;
}

}  // namespace

Status MultiViewTrackerOptions::Validate() const {
  std::vector<std::string> violations;
  const Status frame_status = frame.Validate();
  if (!frame_status.ok()) violations.push_back(frame_status.message());
  const Status color_status = color.Validate();
  if (!color_status.ok()) violations.push_back("color: " + color_status.message());
  if (color_samples == ColorSampleSource::kViewpointModel && !frame.lines_from_viewpoint_model) {
    violations.push_back(
        "color_samples = viewpoint_model, needs frame.lines_from_viewpoint_model = true");
  }
  if (viewpoint_model_for_two_views) {
    if (frame.lines_from_viewpoint_model) {
      violations.push_back(
          "viewpoint_model_for_two_views = true, needs frame.lines_from_viewpoint_model = false "
          "(which applies the model to every frame)");
    } else {
      const Status two_view_status = TwoViewFrameOptions(frame).Validate();
      if (!two_view_status.ok()) {
        violations.push_back("the frames two views see: " + two_view_status.message());
      }
    }
  }
  if (!(velocity_prediction >= 0.0 && velocity_prediction <= 1.0)) {
    violations.push_back(
        fmt::format("velocity_prediction = {}, must be in [0, 1]", velocity_prediction));
  }
  if (bootstrap_passes < 1) {
    violations.push_back(fmt::format("bootstrap_passes = {}, must be >= 1", bootstrap_passes));
  }
  if (!(bootstrap_converged_deg > 0.0)) {
    violations.push_back(
        fmt::format("bootstrap_converged_deg = {}, must be > 0", bootstrap_converged_deg));
  }
  if (bootstrap_rounds < 0) {
    violations.push_back(fmt::format("bootstrap_rounds = {}, must be >= 0", bootstrap_rounds));
  }
  if (!(bootstrap_converged_mm > 0.0)) {
    violations.push_back(
        fmt::format("bootstrap_converged_mm = {}, must be > 0", bootstrap_converged_mm));
  }
  return internal::JoinViolations("tracker", violations);
}

StatusOr<std::unique_ptr<MultiViewTracker>> MultiViewTracker::Create(
    const RayCaster& caster, std::vector<TrackedView> views, const MultiViewTrackerOptions& options,
    const std::optional<RotationalSymmetry>& symmetry,
    std::shared_ptr<const SparseViewpointModel> viewpoint_model) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  if (views.empty()) return Status::InvalidConfig("tracker: no view to track in");
  for (const TrackedView& view : views) {
    BCOT_RETURN_IF_ERROR(view.camera.Validate());
    if (!(view.weight >= 0.0) || !std::isfinite(view.weight)) {
      return Status::InvalidConfig(fmt::format("camera '{}': weight = {}, must be finite and >= 0",
                                               view.camera.name, view.weight));
    }
  }
  if (!options.frame.lines_from_viewpoint_model && !options.viewpoint_model_for_two_views) {
    viewpoint_model = nullptr;
  } else if (viewpoint_model == nullptr) {
    viewpoint_model = std::make_shared<const SparseViewpointModel>(
        SparseViewpointModel::BuildOnDemand(caster, SparseViewpointModelOptions()));
  }
  return std::unique_ptr<MultiViewTracker>(new MultiViewTracker(
      caster, std::move(views), options, symmetry, std::move(viewpoint_model)));
}

namespace {

// The frame options of the bootstrap solves (MultiViewTrackerOptions::bootstrap_rounds).
FrameProblemOptions BootstrapFrameOptions(const MultiViewTrackerOptions& options) {
  FrameProblemOptions frame = options.frame;
  if (options.bootstrap_rounds > 0) frame.rounds = options.bootstrap_rounds;
  return frame;
}

// The response edges are decoded with before an estimate: the configured one, or sRGB.
ImageResponse InitialImageResponse(const MultiViewTrackerOptions& options) {
  const ImageResponse& configured = options.frame.edge.lines.response;
  return configured.IsResolved() ? configured : ImageResponse();
}

}  // namespace

MultiViewTracker::MultiViewTracker(const RayCaster& caster, std::vector<TrackedView> views,
                                   const MultiViewTrackerOptions& options,
                                   const std::optional<RotationalSymmetry>& symmetry,
                                   std::shared_ptr<const SparseViewpointModel> viewpoint_model)
    : caster_(caster),
      views_(std::move(views)),
      options_(options),
      symmetry_(symmetry),
      viewpoint_model_(std::move(viewpoint_model)) {
  UseImageResponse(InitialImageResponse(options));
  for (size_t v = 0; v < views_.size(); ++v) {
    color_models_.emplace_back(options_.color, caster_.mesh().diameter());
  }
}

void MultiViewTracker::UseImageResponse(const ImageResponse& response) {
  image_response_ = response;
  MultiViewTrackerOptions resolved = options_;
  resolved.frame.edge.lines.response = response;
  problem_ =
      std::make_unique<FrameProblem>(caster_, resolved.frame, symmetry_, viewpoint_model_.get());
  bootstrap_problem_ = std::make_unique<FrameProblem>(caster_, BootstrapFrameOptions(resolved),
                                                      symmetry_, viewpoint_model_.get());
  if (options_.viewpoint_model_for_two_views) {
    two_view_problem_ = std::make_unique<FrameProblem>(caster_, TwoViewFrameOptions(resolved.frame),
                                                       symmetry_, viewpoint_model_.get());
  }
}

Status MultiViewTracker::CheckImages(const std::vector<cv::Mat3b>& images) const {
  if (images.size() != views_.size()) {
    return Status::InvalidInput(
        fmt::format("got {} images for {} views", images.size(), views_.size()));
  }
  for (size_t v = 0; v < views_.size(); ++v) {
    const Camera& camera = views_[v].camera;
    if (images[v].cols != camera.width || images[v].rows != camera.height) {
      return Status::InvalidInput(fmt::format("camera '{}': image is {}x{}, camera expects {}x{}",
                                              camera.name, images[v].cols, images[v].rows,
                                              camera.width, camera.height));
    }
  }
  return Status::Ok();
}

void MultiViewTracker::LearnColors(const std::vector<cv::Mat3b>& images,
                                   const Eigen::Isometry3d& rig_from_objcentre, bool fresh,
                                   ColorSampleSource samples) {
  const Eigen::Isometry3d objcentre_from_template = caster_.mesh().objcentre_from_template();
  // Each view updates only its own models: the views are learned concurrently.
  tbb::parallel_for(size_t{0}, views_.size(), [&](size_t v) {
    if (fresh) color_models_[v] = ViewColorModels(options_.color, caster_.mesh().diameter());
    const Eigen::Isometry3d cam_from_template =
        views_[v].cam_from_rig * rig_from_objcentre * objcentre_from_template;
    if (samples == ColorSampleSource::kViewpointModel) {
      color_models_[v].UpdateAlongContour(
          images[v], viewpoint_model_->Project(viewpoint_model_->Nearest(cam_from_template),
                                               views_[v].camera, cam_from_template));
      return;
    }
    const Silhouette silhouette =
        color_models_[v].UsesContour()
            ? RenderSilhouetteContour(caster_, views_[v].camera, cam_from_template,
                                      options_.frame.region.contour)
            : RenderSilhouetteMask(caster_, views_[v].camera, cam_from_template);
    color_models_[v].Update(images[v], silhouette);
  });
}

bool MultiViewTracker::SeenByTwoViews(const Eigen::Isometry3d& rig_from_objcentre) const {
  int seen = 0;
  for (const TrackedView& view : views_) {
    if (view.weight == 0.0) continue;
    const Eigen::Vector3d centre_in_cam = view.cam_from_rig * rig_from_objcentre.translation();
    if (centre_in_cam.z() > 0.0 && view.camera.InImage(view.camera.Project(centre_in_cam))) ++seen;
  }
  return seen >= 2;
}

std::vector<FrameView> MultiViewTracker::FrameViews(const std::vector<cv::Mat3b>& images,
                                                    bool refine) const {
  std::vector<FrameView> frame_views;
  for (size_t v = 0; v < views_.size(); ++v) {
    frame_views.push_back({&views_[v].camera, views_[v].cam_from_rig, &images[v],
                           &color_models_[v].coarse(), views_[v].weight,
                           refine ? color_models_[v].refine() : nullptr, views_[v].chroma});
  }
  return frame_views;
}

FrameSummary MultiViewTracker::Solve(const FrameProblem& problem,
                                     const std::vector<cv::Mat3b>& images,
                                     Eigen::Isometry3d* rig_from_objcentre,
                                     std::vector<ViewLinearisation>* linearisations, bool refine) {
  return problem.Solve(FrameViews(images, refine), rig_from_objcentre, linearisations);
}

void MultiViewTracker::HoldSymmetryAngle(const Eigen::Isometry3d& reference,
                                         Eigen::Isometry3d* rig_from_objcentre) const {
  const std::optional<RotationalSymmetry>& symmetry = problem_->symmetry_in_objcentre();
  if (symmetry.has_value())
    *rig_from_objcentre = symmetry->HoldAngle(*rig_from_objcentre, reference);
}

bool MultiViewTracker::ResolveImageResponse(const std::vector<cv::Mat3b>& images,
                                            const Eigen::Isometry3d& rig_from_objcentre) {
  if (options_.frame.edge.lines.response.IsResolved() || !options_.frame.edge.enabled ||
      response_estimate_.has_value()) {
    return false;
  }
  response_estimate_ =
      EstimateImageResponse(*problem_, FrameViews(images, false), rig_from_objcentre);
  if (!response_estimate_->ok() || (*response_estimate_)->response == image_response_) {
    return false;
  }
  UseImageResponse((*response_estimate_)->response);
  return true;
}

Status MultiViewTracker::Reset(const std::vector<cv::Mat3b>& images,
                               const Eigen::Isometry3d& rig_from_objcentre) {
  BCOT_RETURN_IF_ERROR(CheckImages(images));
  ResolveImageResponse(images, rig_from_objcentre);
  LearnColors(images, rig_from_objcentre, /*fresh=*/true, options_.color_samples);
  previous_rig_from_objcentre_.reset();
  return Status::Ok();
}

StatusOr<FrameSummary> MultiViewTracker::Initialize(
    const std::vector<cv::Mat3b>& images, Eigen::Isometry3d* rig_from_objcentre,
    std::vector<ViewLinearisation>* linearisations) {
  BCOT_CHECK(rig_from_objcentre != nullptr);
  BCOT_RETURN_IF_ERROR(CheckImages(images));
  const Eigen::Isometry3d start = *rig_from_objcentre;
  FrameSummary summary;
  const bool has_refinement_models = color_models_.front().refine() != nullptr;
  for (int pass = 0; pass < options_.bootstrap_passes; ++pass) {
    const Eigen::Isometry3d before = *rig_from_objcentre;
    LearnColors(images, *rig_from_objcentre, /*fresh=*/true, options_.color_samples);
    summary =
        Solve(*bootstrap_problem_, images, rig_from_objcentre, linearisations, /*refine=*/false);
    if (!summary.usable()) break;
    // rig_from_objcentre's translation is the object centre in the rig frame.
    const double moved_deg = RotationDistanceDeg(rig_from_objcentre->linear(), before.linear());
    const double moved_mm = (rig_from_objcentre->translation() - before.translation()).norm();
    if (moved_deg < options_.bootstrap_converged_deg &&
        moved_mm < options_.bootstrap_converged_mm) {
      break;
    }
  }
  if (has_refinement_models && summary.usable()) {
    LearnColors(images, *rig_from_objcentre, /*fresh=*/true, options_.color_samples);
    summary =
        Solve(*bootstrap_problem_, images, rig_from_objcentre, linearisations, /*refine=*/true);
  }
  if (summary.usable() && ResolveImageResponse(images, *rig_from_objcentre)) {
    // The frame once more with its edges decoded by the estimate (the colour models are those
    // of the last solve, learned at a pose within the edge stage's reach).
    summary = Solve(*bootstrap_problem_, images, rig_from_objcentre, linearisations,
                    /*refine=*/has_refinement_models);
  }
  if (summary.usable()) HoldSymmetryAngle(start, rig_from_objcentre);
  previous_rig_from_objcentre_.reset();
  return summary;
}

StatusOr<FrameSummary> MultiViewTracker::Track(const std::vector<cv::Mat3b>& images,
                                               Eigen::Isometry3d* rig_from_objcentre,
                                               std::vector<ViewLinearisation>* linearisations) {
  BCOT_CHECK(rig_from_objcentre != nullptr);
  BCOT_RETURN_IF_ERROR(CheckImages(images));
  const Eigen::Isometry3d last = *rig_from_objcentre;
  if (previous_rig_from_objcentre_.has_value()) {
    *rig_from_objcentre =
        PredictPose(*previous_rig_from_objcentre_, last, options_.velocity_prediction);
  }
  const bool two_views = two_view_problem_ != nullptr && SeenByTwoViews(*rig_from_objcentre);
  FrameSummary summary = Solve(two_views ? *two_view_problem_ : *problem_, images,
                               rig_from_objcentre, linearisations, /*refine=*/true);
  if (summary.usable()) {
    HoldSymmetryAngle(last, rig_from_objcentre);
    LearnColors(images, *rig_from_objcentre, /*fresh=*/false,
                two_views ? ColorSampleSource::kViewpointModel : options_.color_samples);
    previous_rig_from_objcentre_ = last;
  } else {
    // No estimate on this frame: stay at the last one and forget the velocity.
    *rig_from_objcentre = last;
    previous_rig_from_objcentre_.reset();
  }
  return summary;
}

Eigen::Isometry3d PredictPose(const Eigen::Isometry3d& rig_from_objcentre_before,
                              const Eigen::Isometry3d& rig_from_objcentre_last, double fraction) {
  // Angular velocity in the rig frame, R_last·R_beforeᵀ, applied again (scaled); the object
  // centre continues along its last displacement.
  const Eigen::Matrix3d rotation_step =
      rig_from_objcentre_last.linear() * rig_from_objcentre_before.linear().transpose();
  Eigen::Isometry3d predicted = rig_from_objcentre_last;
  predicted.linear() = ExpSO3(fraction * LogSO3(rotation_step)) * rig_from_objcentre_last.linear();
  predicted.translation() +=
      fraction * (rig_from_objcentre_last.translation() - rig_from_objcentre_before.translation());
  return predicted;
}

}  // namespace bcot
