// Quality of an annotation (DESIGN.md "Quality"): the reprojection error of the annotated poses
// against the object boundary visible in the images, the accept / reject verdict, and the
// report files of the output contract.
//
// Measurement, per frame and view, at capture resolution:
//   1. Project the silhouette contour at the annotated pose (RayCaster contour, sub-pixel,
//      one sample every sample_spacing_px) with cam_from_object = cam_from_rig · rig_from_object.
//   2. Learn a colour model (color_kind; local by default: RBOT's histograms along the contour;
//      fresh per frame and view, so no frame's error leaks into another's) from the image with
//      the object at the annotated pose, skipping pixels within color_margin_px of the contour,
//      and compute the posterior P_f at every pixel near the contour; P_b = 1 − P_f.
//   3. Along each contour normal n through contour point c, sample P_f (bilinear) at
//      c + t·n for t in [−R, R] (R = search_radius_px) every 1/4 px. The image boundary is the
//      strongest foreground→background transition: the t maximising the step response
//      D(t) = mean P_f on [t − w, t] − mean P_f on [t, t + w] (w = step_window_px), refined to
//      sub-pixel by a parabola through the maximum and its neighbours. A normal whose best D is
//      below min_contrast (no visible boundary: occlusion, camouflage) gives no sample.
//      With edge_weight > 0 the score adds the image's RGB step over the same windows, which
//      helps where object and background colours overlap (P_f ambiguous).
//   4. (refine_on_edges, default) Each boundary t is moved to the centre of the image's own
//      blurred step within ±edge_search_px of it (RefineOffsetsOnEdges in boundary_search.h),
//      which gives it a standard deviation; a point whose profile shows no clean step is
//      dropped (not usable). The posterior finds *which* transition is the object's boundary
//      (robust to clutter of other colours), the edge fit *where* it is: a posterior puts it
//      where the two sides' colour likelihoods cross, which a shaded rim, a highlight or similar
//      colours move by a pixel or more; the centre of a blurred step does not move. The signed
//      offset t* is the point's raw boundary offset (px).
//   4b. (interior_edges, default) The model's own interior edges at the pose (its creases and
//      occlusion contours, projected) are steps in the image too, and near the silhouette they
//      can be the stronger step: the rim of a flange 3 px inside the silhouette of a spool
//      seen almost end-on, whose side has no contrast against the background. A boundary found
//      within interior_edge_px of such an edge and nearer to it than to its contour point is
//      more likely that edge, so the point is dropped as ambiguous (DropInteriorEdgeMatches in
//      boundary_search.h). A true pose error still moves the found boundaries of the other
//      points, so it is still measured.
//   5. (fit_rigid_motion, default) A pose error moves the whole contour coherently, while a
//      boundary found on a clutter edge, a highlight or a blurred edge is wrong at that point
//      only. So fit the small rigid motion of the object that best explains the raw offsets
//      (RigidMotionFitter: robust least squares weighted by the offsets' variances, linearised
//      projection) and take the offset that motion produces at every contour point as its
//      reprojection error. To first order this is exactly the true projected contour error of
//      the pose when the image boundary is the true contour. The frame-view reports the median
//      and the 90th percentile of |offset| (the raw statistics are kept beside them in
//      quality.json / .csv), and σ, the standard deviation of the judged statistic: the
//      spread over bootstrap resamples of the usable points (bootstrap_resamples) and, in
//      quadrature, the fit's prediction σ over the whole contour (what the usable points leave
//      unconstrained: a side of the object without a usable boundary whose motion nothing
//      else observes; RigidMotionFitter::PredictionSigmaPercentile).
// Why p90 by default: shifting the object 3 px in the image moves its contour by 3·|cos θ| along
// the normals, a median of only ~2 px, so the median cannot separate a 3 px error from the 2 px
// threshold; the p90 (~2.9 px) can.
// Measured by scripts/bench_quality.sh (measured vs true p90 over ground truth, ground truth
// shifted 3 px and randomly perturbed poses): see the numbers in the README's quality section.
//
// A frame-view is *unverifiable* ("cannot tell") when the object is not in the view or fewer
// than min_found_fraction (default 0: no floor) of its contour points have a usable boundary.
// Otherwise, with s its `statistic` (p90 by default), σ its standard deviation (step 5) and
// z = confidence_z: *bad* when s − z·σ > threshold_px, good when
// s + z·σ <= threshold_px, and unverifiable in between (the boundary offsets cannot decide: a
// few points far from the centre, an unstable fit). A sequence is rejected when, for any view, the
// fraction of bad frames exceeds allowed_bad_fraction or the fraction of unverifiable frames
// exceeds allowed_unverified_fraction; the reasons say which.
//
// Files (bcot/quality/quality_files.h; each written atomically):
//   quality.json   options, verdict, reasons, per view summary, per frame and view numbers
//   quality.csv    frame,view,median_px,p90_px,raw_median_px,raw_p90_px,points,found,bad,
//                  statistic_sigma_px,ambiguous,verifiable,clipped
//   report.html    self-contained (inline SVG and CSS, base64 PNG thumbnails, no scripts
//                  beyond a marker): error over time per view, the worst frames with the
//                  contour drawn, the verdict and why
// Thread safety: free functions; MeasureQuality uses the calling TBB arena for views.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/image_cache.h"
#include "bcot/core/linear_rgb.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/core/version.h"
#include "bcot/quality/quality_options.h"
#include "bcot/render/crease_contour.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct ViewFrameQuality {
  // The judged statistics (of the fitted offsets when fit_rigid_motion, else of the raw ones).
  double median_px = 0.0;  // NaN when no point found a boundary
  double p90_px = 0.0;     // NaN likewise
  // The same statistics of the raw boundary offsets.
  double raw_median_px = 0.0;
  double raw_p90_px = 0.0;
  // Standard deviation of the judged statistic (step 5: bootstrap over the usable points, when
  // bootstrap_resamples > 0, and the fit's prediction σ); NaN without the rigid-motion fit or
  // with fewer than 6 usable points.
  double statistic_sigma_px = 0.0;
  int points = 0;          // contour samples
  int found = 0;           // samples with a usable boundary
  int ambiguous = 0;       // samples whose posterior boundary had no clean image edge (step 4)
                           // or lay on an interior edge of the model (step 4b)
  int clipped = 0;         // samples whose boundary shows only in saturated colour channels
                           // (CountClippedPoints in boundary_search.h)
  bool verifiable = true;  // false: "cannot tell" (see above); then bad is false too
  bool bad = false;
  double Statistic(QualityStatistic statistic) const {
    return statistic == QualityStatistic::kMedian ? median_px : p90_px;
  }
};

struct ViewQualitySummary {
  std::string name;
  int bad_frames = 0;
  double bad_fraction = 0.0;
  int unverified_frames = 0;
  double unverified_fraction = 0.0;
  double median_of_medians_px = 0.0;
  double worst_px = 0.0;          // largest statistic over frames (NaN frames skipped)
  std::vector<int> worst_frames;  // frame indices, worst first
  // Share of the contour samples, over all frames, whose boundary shows only in saturated
  // colour channels (ViewFrameQuality::clipped); 0 without samples.
  double clipped_fraction = 0.0;
};

struct QualityReport {
  std::string sequence_dir;
  std::vector<std::string> view_names;
  QualityOptions options;
  // frames[f][v]
  std::vector<std::vector<ViewFrameQuality>> frames;
  std::vector<ViewQualitySummary> views;
  bool accepted = true;
  std::vector<std::string> reasons;  // why rejected (empty when accepted)
  // Stamped into quality.json and report.html; set by the caller (MeasureQuality leaves it
  // empty: the quality layer does not know the options that produced the poses).
  Provenance provenance;
};

// Saturation. Where the image is saturated in every colour channel that shows the boundary (a
// white object's lit side, a bright table mirrored in a glossy rim), no edge can be measured,
// and the poses rest on the other rims, whose own small biases are then no longer balanced by
// the saturated side's. On the Cycles renders of docs/benchmarks.md (2026-11-29): 1–9 % of a
// view's contour in the scenes without a vertical bias, 28–55 % in the three whose object sits
// 0.04–0.21 mm too high (the white bunny in both cameras, the two small bunnies in cam1). A view
// whose ViewQualitySummary::clipped_fraction reaches this share gets a warning.
constexpr double kSaturatedContourWarningFraction = 0.15;

// One sentence per view of `report` whose clipped_fraction reaches
// kSaturatedContourWarningFraction: how much of its contour is saturated, what that does, and
// what to change in the capture. Empty when no view does.
std::vector<std::string> SaturationWarnings(const QualityReport& report);

// Measures one frame-view (steps 1–5 above): `image` (BGR, camera's size, CHECKed) with the
// object at `cam_from_object` (O_t, mm); `linear` decodes its codes; `creases` are
// FindCreases(caster.mesh(), options.crease_min_angle_deg) (unused without
// options.interior_edges); `seed` seeds the bootstrap. The verdict fields are set.
ViewFrameQuality MeasureFrameView(const RayCaster& caster, const Camera& camera,
                                  const Eigen::Isometry3d& cam_from_object, const cv::Mat3b& image,
                                  const QualityOptions& options, const LinearTable& linear,
                                  const std::vector<Crease>& creases, uint32_t seed);

// Measures every frame and view. `rig_from_object` (O_t, mm) has one pose per frame of the
// sequence; `view_names` are rig cameras (empty = all); `response` is the cameras' (the edge
// refinement decodes the images with it, as the edge stage does). Errors: options or response
// invalid, pose count mismatch, a camera not in the rig, the mesh or an image does not read.
StatusOr<QualityReport> MeasureQuality(const Sequence& sequence,
                                       const std::vector<Eigen::Isometry3d>& rig_from_object,
                                       const std::vector<std::string>& view_names,
                                       const QualityOptions& options,
                                       const ImageResponse& response);
// The same with the ray caster of the sequence's mesh (O_t, mm) that the caller already built,
// e.g. the annotator's, so the mesh is neither loaded nor its BVH built again, and the images
// read through `images` when given (those the solve kept are not decoded again).
StatusOr<QualityReport> MeasureQuality(const Sequence& sequence, const RayCaster& caster,
                                       const std::vector<Eigen::Isometry3d>& rig_from_object,
                                       const std::vector<std::string>& view_names,
                                       const QualityOptions& options, const ImageResponse& response,
                                       DecodedImageCache* images = nullptr);

}  // namespace bcot
