#include "bcot/eval/online/region_monocular_tracker.h"

#include <string>
#include <utility>

#include "bcot/render/ray_caster.h"

namespace bcot {
namespace {

class RegionMonocularTracker final : public MonocularTracker {
 public:
  RegionMonocularTracker(const Mesh& mesh, std::unique_ptr<RayCaster> caster,
                         std::unique_ptr<MultiViewTracker> tracker)
      : objcentre_from_template_(mesh.objcentre_from_template()),
        caster_(std::move(caster)),
        tracker_(std::move(tracker)) {}

  Status Reset(const cv::Mat3b& image, const Eigen::Isometry3d& cam_from_object) override {
    cam_from_objcentre_ = cam_from_object * objcentre_from_template_.inverse();
    return tracker_->Reset({image}, cam_from_objcentre_);
  }

  StatusOr<Eigen::Isometry3d> Track(const cv::Mat3b& image) override {
    StatusOr<FrameSummary> summary = tracker_->Track({image}, &cam_from_objcentre_);
    if (!summary.ok()) return summary.status();
    if (!summary->usable()) {
      return Status::Internal(std::string("tracking failed (") +
                              FrameTerminationName(summary->termination) +
                              "): " + summary->message);
    }
    return cam_from_objcentre_ * objcentre_from_template_;
  }

 private:
  Eigen::Isometry3d objcentre_from_template_;
  Eigen::Isometry3d cam_from_objcentre_ = Eigen::Isometry3d::Identity();
  // The tracker keeps a reference to the caster: declared first, destroyed last.
  std::unique_ptr<RayCaster> caster_;
  std::unique_ptr<MultiViewTracker> tracker_;
};

}  // namespace

MonocularTrackerFactory MakeRegionTrackerFactory(const MultiViewTrackerOptions& options) {
  return [options](const Camera& camera,
                   const Mesh& mesh) -> StatusOr<std::unique_ptr<MonocularTracker>> {
    auto caster = std::make_unique<RayCaster>(mesh);
    StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
        MultiViewTracker::Create(*caster, {{camera, Eigen::Isometry3d::Identity(), 1.0}}, options);
    if (!tracker.ok()) return tracker.status();
    return std::unique_ptr<MonocularTracker>(std::make_unique<RegionMonocularTracker>(
        mesh, std::move(caster), std::move(tracker).value()));
  };
}

}  // namespace bcot
