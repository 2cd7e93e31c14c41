// A score of a pose that compares across solves: the region energy of all views with colour
// models learned at that pose (`bcot init` ranks its candidates with it; the annotator uses it
// to choose between the forward and the backward solve of a frame between two anchors).
//
// Per view, the image is resized to `width_px` wide (never enlarged), the silhouette at the
// pose is ray-cast, a global foreground/background colour histogram pair is learned from it,
// and RBOT's energy F = −log(He·P_f + (1 − He)·P_b) is averaged over the band of `band_px`
// around the contour. A silhouette on the object splits the colours cleanly, a wrong one mixes
// object and background on both sides. Unlike the energy a tracker reports (its colour models
// carry over from earlier frames and were learned at its own poses), this one depends on the
// pose and the images only.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "bcot/core/rig.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/region_cost.h"
#include "bcot/optim/region_template.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct PoseScorerOptions {
  int width_px = 320;           // views resized to this width; >= 16
  double band_px = 5.0;         // half-width of the band (px at that width); > 0
  int bins_per_channel = 16;    // colour histogram bins per channel; divides 256
  int background_band_px = 12;  // background samples within this distance (px); >= 1
};

// Score is const and thread-safe: every call owns its colour models.
class PoseScorer {
 public:
  // `caster` must outlive the scorer; `images` in rig order at capture size.
  PoseScorer(const RayCaster& caster, const Rig& rig, const std::vector<cv::Mat3b>& images,
             const PoseScorerOptions& options);

  // The mean over the views of each view's mean F per band pixel; a view without band pixels
  // (the object outside it, or behind its camera) counts as uninformative, F = log 2 (P_f = P_b
  // = ½), so that poses hiding the object from some views do not escape their evidence. +∞ when
  // no view has a band pixel. Lower is better.
  double Score(const Eigen::Isometry3d& rig_from_objcentre) const;

  // The object's silhouette masks at the pose, one per view (at the scoring size).
  std::vector<cv::Mat1b> Masks(const Eigen::Isometry3d& rig_from_objcentre) const;

 private:
  struct ScaledView {
    Camera camera;
    Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
    cv::Mat3b image;
  };
  // Mean F per band pixel of one view; none when the view has no band pixel.
  std::optional<double> ViewMeanEnergy(const ScaledView& view,
                                       const Eigen::Isometry3d& rig_from_objcentre) const;

  const RayCaster& caster_;
  Eigen::Isometry3d objcentre_from_template_;
  std::vector<ScaledView> views_;
  ColorModelOptions color_;
  RegionTemplateOptions region_;
  RegionCostOptions cost_;
};

}  // namespace bcot
