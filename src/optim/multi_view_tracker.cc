#include "bcot/optim/multi_view_tracker.h"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>

#include "bcot/optim/silhouette.h"
#include "violations.h"

namespace bcot {

Status MultiViewTrackerOptions::Validate() const {
  std::vector<std::string> violations;
  const Status frame_status = frame.Validate();
  if (!frame_status.ok()) violations.push_back(frame_status.message());
  const Status color_status = color.Validate();
  if (!color_status.ok()) violations.push_back("color: " + color_status.message());
  if (bootstrap_passes < 1) {
    violations.push_back(fmt::format("bootstrap_passes = {}, must be >= 1", bootstrap_passes));
  }
  return internal::JoinViolations("tracker", violations);
}

StatusOr<std::unique_ptr<MultiViewTracker>> MultiViewTracker::Create(
    const RayCaster& caster, std::vector<TrackedView> views,
    const MultiViewTrackerOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  if (views.empty()) return Status::InvalidConfig("tracker: no view to track in");
  for (const TrackedView& view : views) {
    BCOT_RETURN_IF_ERROR(view.camera.Validate());
    if (!(view.weight >= 0.0) || !std::isfinite(view.weight)) {
      return Status::InvalidConfig(fmt::format("camera '{}': weight = {}, must be finite and >= 0",
                                               view.camera.name, view.weight));
    }
  }
  return std::unique_ptr<MultiViewTracker>(
      new MultiViewTracker(caster, std::move(views), options));
}

MultiViewTracker::MultiViewTracker(const RayCaster& caster, std::vector<TrackedView> views,
                                   const MultiViewTrackerOptions& options)
    : caster_(caster), views_(std::move(views)), options_(options), problem_(caster, options.frame) {
  for (size_t v = 0; v < views_.size(); ++v) {
    color_models_.push_back(MakeColorModel(options_.color, caster_.mesh().diameter()));
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
                                   const Eigen::Isometry3d& rig_from_objcentre, bool fresh) {
  const Eigen::Isometry3d objcentre_from_template = caster_.mesh().objcentre_from_template();
  for (size_t v = 0; v < views_.size(); ++v) {
    if (fresh) color_models_[v] = MakeColorModel(options_.color, caster_.mesh().diameter());
    const Silhouette silhouette = RenderSilhouette(
        caster_, views_[v].camera,
        views_[v].cam_from_rig * rig_from_objcentre * objcentre_from_template,
        options_.frame.region.contour);
    color_models_[v]->Update(images[v], silhouette);
  }
}

FrameSummary MultiViewTracker::Solve(const std::vector<cv::Mat3b>& images,
                                     Eigen::Isometry3d* rig_from_objcentre,
                                     std::vector<ViewLinearisation>* linearisations) {
  std::vector<FrameView> frame_views;
  for (size_t v = 0; v < views_.size(); ++v) {
    frame_views.push_back({&views_[v].camera, views_[v].cam_from_rig, &images[v],
                           color_models_[v].get(), views_[v].weight});
  }
  return problem_.Solve(frame_views, rig_from_objcentre, linearisations);
}

Status MultiViewTracker::Reset(const std::vector<cv::Mat3b>& images,
                               const Eigen::Isometry3d& rig_from_objcentre) {
  BCOT_RETURN_IF_ERROR(CheckImages(images));
  LearnColors(images, rig_from_objcentre, /*fresh=*/true);
  return Status::Ok();
}

StatusOr<FrameSummary> MultiViewTracker::Initialize(
    const std::vector<cv::Mat3b>& images, Eigen::Isometry3d* rig_from_objcentre,
    std::vector<ViewLinearisation>* linearisations) {
  BCOT_CHECK(rig_from_objcentre != nullptr);
  BCOT_RETURN_IF_ERROR(CheckImages(images));
  FrameSummary summary;
  for (int pass = 0; pass < options_.bootstrap_passes; ++pass) {
    LearnColors(images, *rig_from_objcentre, /*fresh=*/true);
    summary = Solve(images, rig_from_objcentre, linearisations);
    if (!summary.usable()) break;
  }
  return summary;
}

StatusOr<FrameSummary> MultiViewTracker::Track(const std::vector<cv::Mat3b>& images,
                                               Eigen::Isometry3d* rig_from_objcentre,
                                               std::vector<ViewLinearisation>* linearisations) {
  BCOT_CHECK(rig_from_objcentre != nullptr);
  BCOT_RETURN_IF_ERROR(CheckImages(images));
  FrameSummary summary = Solve(images, rig_from_objcentre, linearisations);
  if (summary.usable()) LearnColors(images, *rig_from_objcentre, /*fresh=*/false);
  return summary;
}

}  // namespace bcot
