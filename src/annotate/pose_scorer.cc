#include "bcot/annotate/pose_scorer.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <utility>

#include "bcot/optim/se3_manifold.h"
#include "bcot/optim/silhouette.h"

namespace bcot {

PoseScorer::PoseScorer(const RayCaster& caster, const Rig& rig,
                       const std::vector<cv::Mat3b>& images, const PoseScorerOptions& options)
    : caster_(caster), objcentre_from_template_(caster.mesh().objcentre_from_template()) {
  BCOT_CHECK(static_cast<int>(images.size()) == rig.size());
  for (int v = 0; v < rig.size(); ++v) {
    const Camera& camera = rig[v].camera;
    const double scale = std::min(1.0, double(options.width_px) / camera.width);
    ScaledView view;
    view.camera = scale < 1.0 ? camera.Scaled(scale) : camera;
    view.cam_from_rig = rig[v].cam_from_rig;
    if (scale < 1.0) {
      cv::resize(images[v], view.image, cv::Size(view.camera.width, view.camera.height), 0, 0,
                 cv::INTER_AREA);
    } else {
      view.image = images[v];
    }
    views_.push_back(std::move(view));
  }
  color_.kind = ColorModelKind::kGlobal;
  color_.refine_kind.reset();
  color_.bins_per_channel = options.bins_per_channel;
  color_.background_band_px = options.background_band_px;
  color_.sample_margin_px = 1.0;
  region_.band_px = options.band_px;
  region_.stride_px = 1;
  region_.contour.sample_spacing_px = 1.0;
  region_.contour.precision_px = 1.0 / 16.0;
}

double PoseScorer::Score(const Eigen::Isometry3d& rig_from_objcentre) const {
  double sum = 0.0;
  bool any_visible = false;
  for (const ScaledView& view : views_) {
    const std::optional<double> mean = ViewMeanEnergy(view, rig_from_objcentre);
    any_visible = any_visible || mean.has_value();
    sum += mean.value_or(std::log(2.0));
  }
  if (!any_visible || !std::isfinite(sum)) return std::numeric_limits<double>::infinity();
  return sum / views_.size();
}

std::vector<cv::Mat1b> PoseScorer::Masks(const Eigen::Isometry3d& rig_from_objcentre) const {
  std::vector<cv::Mat1b> masks;
  for (const ScaledView& view : views_) {
    masks.push_back(
        RenderSilhouetteMask(caster_, view.camera,
                             view.cam_from_rig * rig_from_objcentre * objcentre_from_template_)
            .mask);
  }
  return masks;
}

std::optional<double> PoseScorer::ViewMeanEnergy(
    const ScaledView& view, const Eigen::Isometry3d& rig_from_objcentre) const {
  const Silhouette silhouette = RenderSilhouette(
      caster_, view.camera, view.cam_from_rig * rig_from_objcentre * objcentre_from_template_,
      region_.contour);
  if (silhouette.contour.empty()) return std::nullopt;
  GlobalColorModel model(color_);
  model.Update(view.image, silhouette);
  if (!model.initialized()) return std::nullopt;
  StatusOr<RegionTemplate> region_template =
      BuildRegionTemplate(caster_, view.camera, view.cam_from_rig, rig_from_objcentre, view.image,
                          model, silhouette, region_);
  if (!region_template.ok() || region_template->pixels.empty()) return std::nullopt;
  const double pixels = static_cast<double>(region_template->pixels.size());
  const RegionCostFunction cost(view.camera, view.cam_from_rig, std::move(*region_template), cost_);
  return cost.Energy(ToPoseParameters(rig_from_objcentre).data()) / pixels;
}

}  // namespace bcot
