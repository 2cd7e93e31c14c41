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
//   4. The signed offset t* is the point's raw boundary offset (px).
//   5. (fit_rigid_motion, default) A pose error moves the whole contour coherently, while a
//      boundary found on a clutter edge, a highlight or a blurred edge is wrong at that point
//      only. So fit the small rigid motion of the object that best explains the raw offsets
//      (FitRigidMotionOffsets: robust least squares, linearised projection) and take the offset
//      that motion produces at every contour point as its reprojection error. To first order
//      this is exactly the true projected contour error of the pose when the image boundary is
//      the true contour. The frame-view reports the median and the 90th percentile of |offset|
//      (the raw statistics are kept beside them in quality.json / .csv).
// Why p90 by default: shifting the object 3 px in the image moves its contour by 3·|cos θ| along
// the normals, a median of only ~2 px, so the median cannot separate a 3 px error from the 2 px
// threshold; the p90 (~2.9 px) can.
// Measured by scripts/bench_quality.sh (measured vs true p90 over ground truth, ground truth
// shifted 3 px and randomly perturbed poses): see the numbers in the README's quality section.
//
// A frame-view is *bad* when its `statistic` (p90 by default) exceeds threshold_px, or when
// fewer than min_found_fraction of its contour points found a boundary (the annotation cannot
// be verified there), or when the object is not in the view. A sequence is rejected when, for
// any view, the fraction of bad frames exceeds allowed_bad_fraction.
//
// Files (each written atomically):
//   quality.json   options, verdict, reasons, per view summary, per frame and view numbers
//   quality.csv    frame,view,median_px,p90_px,raw_median_px,raw_p90_px,points,found,bad
//   report.html    self-contained (inline SVG and CSS, base64 PNG thumbnails, no scripts
//                  beyond a marker): error over time per view, the worst frames with the
//                  contour drawn, the verdict and why
// Thread safety: free functions; MeasureQuality uses the calling TBB arena for views.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/optim/color_model.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

enum class QualityStatistic { kMedian, kP90 };

struct QualityOptions {
  // A frame-view is bad when its statistic exceeds this (px, capture resolution); > 0.
  double threshold_px = 2.0;
  // Which per frame-view statistic is compared with threshold_px.
  QualityStatistic statistic = QualityStatistic::kP90;
  // A view may be bad on at most this fraction of frames; in [0, 1]. 0 = none.
  double allowed_bad_fraction = 0.0;
  // Boundary search along each normal within ±search_radius_px of the contour (px); > 0.
  double search_radius_px = 6.0;
  // Half-width of the step detector on the P_f profile (px); > 0.
  double step_window_px = 2.0;
  // Weight of the image edge in the boundary score: score(t) = D(t) + edge_weight · E(t), E the
  // RGB step (|mean colour inside − outside| / √3, colours in [0, 1]) over the same windows.
  // 0 = colour posteriors only (default: on bench_quality.sh data, clutter and distractor
  // edges near the contour made ground-truth poses fail at 1); in [0, 10].
  double edge_weight = 0.0;
  // Minimum score for a boundary to count as found; in (0, 1 + edge_weight).
  double min_contrast = 0.3;
  // Below this fraction of contour points with a boundary, the frame-view is bad; in [0, 1].
  double min_found_fraction = 0.5;
  // Spacing of the contour samples (px); > 0.
  double sample_spacing_px = 2.0;
  // Histogram bins per channel of the colour model (must divide 256).
  int bins_per_channel = 16;
  // Colour model the posteriors come from: global (one histogram pair) or local (RBOT's
  // histograms along the contour, which tell the object from clutter of similar colour
  // elsewhere in the image).
  ColorModelKind color_kind = ColorModelKind::kLocal;
  // The colour model learns from no pixel within this distance (px) of the contour, so a pose
  // a few px off does not teach each side the other's colours near the boundary it is judged
  // against (which would pull the found boundary towards the pose); in [0, search_radius_px).
  double color_margin_px = 4.0;
  // Judge the offsets of one rigid motion robustly fitted to the raw boundary offsets instead
  // of the raw offsets themselves (step 5 above).
  bool fit_rigid_motion = true;
  // Scale of the robust fit (px): Huber threshold, Tukey's at 3×; > 0.
  double fit_scale_px = 1.0;
  // Worst frames per view shown as thumbnails in report.html; >= 0.
  int worst_frames = 4;
  // Longest side of a thumbnail (px); >= 32.
  int thumbnail_px = 320;

  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

const char* QualityStatisticName(QualityStatistic statistic);

// The `quality:` YAML section (keys spelled as the fields; statistic: median | p90).
// Unknown keys, wrong types and out-of-range values are kInvalidConfig errors naming
// file:line: quality.key. `node` may be undefined (defaults kept).
Status ParseQualityOptions(const YAML::Node& node, const std::string& source_name,
                           QualityOptions* options);
// The section as YAML lines ("quality:\n  threshold_px: 2\n..."), readable by the parser.
std::string FormatQualityOptions(const QualityOptions& options);

// Boundary offsets of one contour against a P_f image. `posterior` is P_f on `roi` (image
// coordinates of its top-left pixel centre = roi.tl()); `colour` (optional, used when
// options.edge_weight > 0) the image channels on the same roi, in [0, 1]. Returns one entry
// per contour point: the signed offset t* along the outward normal (px), or NaN when no
// boundary was found.
std::vector<double> BoundaryOffsets(const std::vector<ContourPoint>& contour,
                                    const cv::Mat1f& posterior, const cv::Rect& roi,
                                    const QualityOptions& options,
                                    const std::vector<cv::Mat1f>& colour = {});

// The offsets along the normals that the best rigid motion of the object explains (step 5):
// robust (Huber, then Tukey) least squares fit of a small motion δ = (ω, v) about
// `object_centre` (object frame) to the finite `offsets` (one per contour point, NaN = none),
// with the first-order model offset_i = n_iᵀ · ∂x_i/∂δ · δ; returns that model's offset at every
// contour point (all NaN when fewer than 6 offsets carry weight). `scale_px` > 0.
std::vector<double> FitRigidMotionOffsets(const std::vector<ContourPoint>& contour,
                                          const std::vector<double>& offsets, const Camera& camera,
                                          const Eigen::Isometry3d& cam_from_object,
                                          const Eigen::Vector3d& object_centre, double scale_px);

// Median and 90th percentile of |values| ignoring NaN; NaN when none is finite.
double AbsPercentile(const std::vector<double>& values, double fraction);

struct ViewFrameQuality {
  // The judged statistics (of the fitted offsets when fit_rigid_motion, else of the raw ones).
  double median_px = 0.0;  // NaN when no point found a boundary
  double p90_px = 0.0;     // NaN likewise
  // The same statistics of the raw boundary offsets.
  double raw_median_px = 0.0;
  double raw_p90_px = 0.0;
  int points = 0;  // contour samples
  int found = 0;   // samples with a boundary
  bool bad = false;
  double Statistic(QualityStatistic statistic) const {
    return statistic == QualityStatistic::kMedian ? median_px : p90_px;
  }
};

struct ViewQualitySummary {
  std::string name;
  int bad_frames = 0;
  double bad_fraction = 0.0;
  double median_of_medians_px = 0.0;
  double worst_px = 0.0;          // largest statistic over frames (NaN frames skipped)
  std::vector<int> worst_frames;  // frame indices, worst first
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
};

// Measures every frame and view. `rig_from_object` (O_t, mm) has one pose per frame of the
// sequence; `view_names` are rig cameras (empty = all). Errors: options invalid, pose count
// mismatch, a camera not in the rig, the mesh or an image does not read.
StatusOr<QualityReport> MeasureQuality(const Sequence& sequence,
                                       const std::vector<Eigen::Isometry3d>& rig_from_object,
                                       const std::vector<std::string>& view_names,
                                       const QualityOptions& options);

std::string QualityJson(const QualityReport& report);
std::string QualityCsv(const QualityReport& report);
// report.html; reads the worst frames' images and draws the contour of the annotated pose.
StatusOr<std::string> QualityHtml(const QualityReport& report, const Sequence& sequence,
                                  const std::vector<Eigen::Isometry3d>& rig_from_object);

// Measures and writes quality.json, quality.csv and report.html into `out_dir`.
StatusOr<QualityReport> WriteQualityReport(const std::string& out_dir, const Sequence& sequence,
                                           const std::vector<Eigen::Isometry3d>& rig_from_object,
                                           const std::vector<std::string>& view_names,
                                           const QualityOptions& options);

// `bcot report`: regenerates quality.json, quality.csv and report.html of one annotation
// directory from its rig_from_object.txt without re-solving. The sequence is `sequence_dir`,
// or (when empty) the one recorded in config.resolved.yaml ("# sequence: <path>"); the options
// are those of config.resolved.yaml with `overrides` (`quality.threshold_px=1`, ...) applied.
// DONE is left as it is.
StatusOr<QualityReport> RegenerateQualityReport(const std::string& annotation_dir,
                                                const std::string& sequence_dir,
                                                const std::vector<std::string>& overrides);

// The verdict stored in `<annotation dir>/quality.json`: "accepted" / "rejected", the reasons
// and the worst statistic; for summaries over a batch.
struct QualityVerdict {
  bool accepted = false;
  std::vector<std::string> reasons;
  double worst_px = 0.0;
  int frames = 0;
};
StatusOr<QualityVerdict> ReadQualityVerdict(const std::string& annotation_dir);

}  // namespace bcot
