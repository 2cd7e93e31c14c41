// Correspondence lines of the sparse region energy (DESIGN.md "Sparse variant", SRT3D/ICG
// style): per view and round, lines through evenly spaced points of the projected contour at
// T0 = rig_from_objcentre, along the contour's outward 2D normal, each turned into a
// distribution of where the image's object boundary lies on the line.
//
// For a line with centre c (contour point at T0, px), outward unit normal n and model point X
// (O_o, projecting to ≈ c at T0):
//   samples   s_k = k·h for integer k whose segment [s_k − h/2, s_k + h/2] lies in
//             [−inside_px, +outside_px] (h = scale_px, along n, px). Each sample's P_f is the mean
//             of the bilinearly interpolated posteriors at h points spread over its segment [s_k −
//             h/2, s_k + h/2), so coarse scales average the image instead of aliasing it.
//   hypothesis the contour sits at offset d: sample k is foreground with probability
//             h_f(s_k − d) = ½ − α·tanh((s_k − d) / (2·slope_px)) (the smoothed step, α < ½)
//             and background with h_b = 1 − h_f.
//   p(d)      ∝ Π_k [h_f(s_k − d)·P_f(s_k) + h_b(s_k − d)·P_b(s_k)], on a grid of d every
//             h/hypothesis_subdivisions over the sample range shrunk by one sample per end.
//   μ, σ²    mean and variance of p(d); σ² is floored at min_sigma_px².
// The residual of the sparse energy (correspondence_line_cost.h) is (n·(x_X(T) − c) − μ)/σ,
// written with the model point's own projection at T0, x0 = x_X(T0) (within the contour
// precision of c), as (n·(x_X(T) − x0) − μ)/σ so that the contour model is exact at T0.
//
// Line range. The line covers at most half_length_px on each side of c, and only as far as
// the rendered mask at T0 stays inside (inward) / outside (outward) of the silhouette: a line
// never crosses a second contour, where a one-step model of the image would be wrong (thin
// parts, nearby holes, self-occlusion boundaries).
//
// Rejection (documented rule; the counts are in CorrespondenceLines::rejected_*):
//   too short   inside_px or outside_px < min_side_px (thin part, tight concavity);
//   off image   the contour point is outside the image or its model point is behind the
//               camera (the line itself is clipped to the
//               image, with room for the bilinear 2×2 neighbours, and then may be too short);
//   ambiguous   σ > max_sigma_px (flat: no colour contrast along the line; multimodal: two
//               edges compete, the variance of two separated modes is large), or the mode of
//               p(d) lies on the first or last hypothesis (the boundary is probably beyond the
//               line, so μ would be biased towards the line's end).
//
// Frames: cam_from_rig (view extrinsics), rig_from_objcentre (T0, O_o), the silhouette in the
// mesh's template frame O_t; px and mm. Thread safety: pure functions.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/ray_caster.h"
#include "bcot/render/sparse_viewpoint_model.h"

namespace bcot {

struct CorrespondenceLineOptions {
  // Lines per view (evenly spaced by arc length over all contours); >= 1. ICG: 200.
  int num_lines = 200;
  // Sample spacing h along the line (px) at full resolution; > 0. Coarse levels of the
  // pyramid multiply it (and half_length_px, min_side_px, slope_px, min/max_sigma_px) by 2^l.
  double scale_px = 1.0;
  // Maximum extent of the line on each side of the contour point (px); > scale_px.
  double half_length_px = 12.0;
  // A line is rejected when it covers less than this on either side (px); >= 0.
  double min_side_px = 3.0;
  // Smoothed step: slope (px) and amplitude α of h_f = ½ − α·tanh(s / (2·slope));
  // slope > 0, α in (0, 0.5). ICG: slope 0.5, α 0.42 (α < ½ bounds the influence of a
  // single mislabelled sample).
  double slope_px = 0.5;
  double amplitude = 0.42;
  // Hypotheses d per sample spacing; >= 1. 4 gives a 0.25 px grid at scale 1.
  int hypothesis_subdivisions = 4;
  // σ is floored at min_sigma_px (a perfectly sharp distribution must not get unbounded
  // weight) and the line rejected as ambiguous above max_sigma_px; 0 < min < max.
  double min_sigma_px = 0.5;
  double max_sigma_px = 4.0;
  // Weight of the sparse energy in a frame problem (multiplies each view's weight); >= 0.
  // Only matters relative to the dense energy when both are combined.
  double weight = 1.0;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

struct CorrespondenceLine {
  Eigen::Vector2d centre;              // c, px (contour point at T0)
  Eigen::Vector2d normal;              // n, unit, outward
  Eigen::Vector3d point_in_objcentre;  // X in O_o, mm
  Eigen::Vector2d projection0;         // x0 = x_X(T0), px
  double mean_px = 0.0;                // μ along n from c
  double sigma_px = 1.0;               // σ (floored)
};

struct CorrespondenceLines {
  Eigen::Isometry3d rig_from_objcentre = Eigen::Isometry3d::Identity();  // T0
  std::vector<CorrespondenceLine> lines;
  int candidates = 0;  // contour points tried
  // Length of traced contour (px) per candidate line (edge lines; 0 when not set).
  double line_spacing_px = 0.0;
  int rejected_short = 0;
  int rejected_off_image = 0;
  int rejected_ambiguous = 0;
};

// Shared by the builders of lines (this file's and edge_lines.h's): the candidate lines of one
// view, min(num_lines, contour samples) of them spread evenly over the silhouette's contour
// (evenly spaced indices are evenly spaced in arc length), and each line anchored at T0:
// centre, normal, model point in the object-centred frame and its projection. Holds references
// to `camera` and `silhouette`, which must outlive it.
class LineAnchors {
 public:
  LineAnchors(const RayCaster& caster, const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
              const Eigen::Isometry3d& rig_from_objcentre, const Silhouette& silhouette,
              int num_lines)
      : LineAnchors(caster, camera, cam_from_rig, rig_from_objcentre, silhouette.contour,
                    num_lines) {}
  // The same along any samples with model points (`contour` must outlive the anchors).
  LineAnchors(const RayCaster& caster, const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
              const Eigen::Isometry3d& rig_from_objcentre, const std::vector<ContourPoint>& contour,
              int num_lines);
  int size() const { return size_; }
  // The contour sample of candidate j, 0 <= j < size(), and its index in the contour.
  const ContourPoint& point(int j) const;
  size_t index(int j) const;
  // The line of candidate j anchored at T0; false when its model point is not in front of the
  // camera.
  bool Anchor(int j, CorrespondenceLine* line) const;

 private:
  const Camera& camera_;
  const std::vector<ContourPoint>& contour_;
  Eigen::Isometry3d objcentre_from_template_;
  Eigen::Isometry3d cam_from_objcentre_;
  int size_;
};

// Builds the lines of one view at T0. `silhouette` must be RenderSilhouette at
// cam_from_rig · T0 · objcentre_from_template. Errors (kInvalidConfig / kInvalidInput):
// invalid options, image size different from the camera's, silhouette mask of another size.
// An object outside the view gives no lines (not an error).
StatusOr<CorrespondenceLines> BuildCorrespondenceLines(
    const RayCaster& caster, const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
    const Eigen::Isometry3d& rig_from_objcentre, const cv::Mat3b& image,
    const ColorModel& color_model, const Silhouette& silhouette,
    const CorrespondenceLineOptions& options = {});

// The same lines along the points of a sparse viewpoint model (sparse_viewpoint_model.h)
// projected at cam_from_rig · T0 · objcentre_from_template, without a render: a line extends as
// far as the model's extents of its point (less the margin the rendered mask's walk keeps) and
// the image allow. Errors: invalid options, image size different from the camera's.
StatusOr<CorrespondenceLines> BuildCorrespondenceLines(
    const RayCaster& caster, const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
    const Eigen::Isometry3d& rig_from_objcentre, const cv::Mat3b& image,
    const ColorModel& color_model, const std::vector<ProjectedContourPoint>& points,
    const CorrespondenceLineOptions& options = {});

// The contour-position distribution of one line from its samples (exposed for tests):
// `p_foreground[k]` at offset first_offset_px + k·scale_px. Writes μ and σ (unfloored) and
// returns false when the mode lies on the first or last hypothesis or there are < 3 samples.
bool ContourDistribution(const std::vector<double>& p_foreground, double first_offset_px,
                         const CorrespondenceLineOptions& options, double* mean_px,
                         double* sigma_px);

}  // namespace bcot
