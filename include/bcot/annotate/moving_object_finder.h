// Finding the object without clicks, from its motion (`bcot init` without --click).
//
// The cameras of a capture rig stand still while the object is carried through the scene, so
// at frame f the object is where the image differs from the scene without it. Per view:
//   1. K frames spread evenly over the sequence (frame f among them) are read and resized to
//      `work_width_px`; the background B is their per-pixel, per-channel median — the scene
//      without the object wherever the object covers a pixel in fewer than half of them;
//   2. the change D(x) = max over channels |I_f(x) − B(x)|; its noise level is robust,
//      σ = 1.4826·median_x D(x) (most pixels are background), and a pixel changed when
//      D > max(threshold_sigmas·σ, min_change);
//   3. the changed mask is opened (3×3) and closed (7×7); its largest connected region is the
//      object, its centroid the click (at capture resolution).
// Views whose largest region is smaller than min_area_fraction of the image give no click.
//
// Where it works: the object moves by more than its own size over the sampled frames, in front
// of a static scene. Where it does not: an object that stays in place (its interior keeps its
// colour in most frames), other moving things larger than the object (the region found is the
// largest), a hand holding the object (the region and its centroid include the hand), moving
// shadows, or camera motion. The clicks found are printed, so a wrong one can be replaced by a
// --click.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bcot/core/sequence.h"
#include "bcot/core/status.h"

namespace bcot {

struct MovingObjectOptions {
  // Frames sampled for the background, spread evenly over the sequence; >= 3 (the sequence
  // must have at least 3 frames).
  int frames = 15;
  // Width (px) the views are resized to (never enlarged); >= 32.
  int work_width_px = 320;
  // A pixel changed when its change exceeds this many robust σ of the change ...; > 0.
  double threshold_sigmas = 5.0;
  // ... and at least this (grey levels, 0..255); >= 0.
  double min_change = 12.0;
  // Smallest region taken for the object, as a fraction of the image area; in (0, 1).
  double min_area_fraction = 2e-4;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

struct MovingObjectView {
  std::string camera;
  bool found = false;
  Eigen::Vector2d centroid_px = Eigen::Vector2d::Zero();  // capture resolution
  double area_fraction = 0.0;     // of the largest changed region, of the image area
  double changed_fraction = 0.0;  // of all changed pixels, of the image area
};

// The moving object at `frame` in every view of the sequence (rig order). kInvalidInput when
// the sequence has fewer than 3 frames or an image does not read; `frame` must be in range
// (CHECKed); `options` must be valid.
StatusOr<std::vector<MovingObjectView>> FindMovingObject(const Sequence& sequence, int frame,
                                                         const MovingObjectOptions& options);

}  // namespace bcot
