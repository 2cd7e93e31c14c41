// Quality of an annotation (DESIGN.md "Quality"): the reprojection error of the annotated poses
// against the object boundary visible in the images, the accept / reject verdict, and the
// report files of the output contract.
//
// Measurement, per frame and view, at capture resolution:
//   1. Project the silhouette contour at the annotated pose (RayCaster contour, sub-pixel,
//      one sample every sample_spacing_px) with cam_from_object = cam_from_rig · rig_from_object.
//   2. Learn a global colour model (ColorModel, fresh per frame and view, so no frame's error
//      leaks into another's) from the image with the object at the annotated pose, and compute
//      the posterior P_f at every pixel near the contour; P_b = 1 − P_f.
//   3. Along each contour normal n through contour point c, sample P_f (bilinear) at
//      c + t·n for t in [−R, R] (R = search_radius_px) every 1/4 px. The image boundary is the
//      strongest foreground→background transition: the t maximising the step response
//      D(t) = mean P_f on [t − w, t] − mean P_f on [t, t + w] (w = step_window_px), refined to
//      sub-pixel by a parabola through the maximum and its neighbours. A normal whose best D is
//      below min_contrast (no visible boundary: occlusion, camouflage) gives no sample.
//      With edge_weight > 0 the score adds the image's RGB step over the same windows, which
//      helps where object and background colours overlap (P_f ambiguous).
//   4. The offset |t*| is the point's reprojection error in px. The frame-view reports the
//      median and the 90th percentile over its points.
// Why p90 by default: shifting the object 3 px in the image moves its contour by 3·|cos θ| along
// the normals, a median of only ~2 px, so the median cannot separate a 3 px error from the 2 px
// threshold; the p90 (~2.9 px) can. Measured noise floor of the p90 on ground-truth poses
// (scripts/bench_quality.sh): ~0.4 px on the demo data, ~2 px on glossy_fast (glossy object,
// motion blur, clutter in the object's colours), where correct poses are then rejected.
//
// A frame-view is *bad* when its `statistic` (p90 by default) exceeds threshold_px, or when
// fewer than min_found_fraction of its contour points found a boundary (the annotation cannot
// be verified there), or when the object is not in the view. A sequence is rejected when, for
// any view, the fraction of bad frames exceeds allowed_bad_fraction.
//
// Files (each written atomically):
//   quality.json   options, verdict, reasons, per view summary, per frame and view numbers
//   quality.csv    frame,view,median_px,p90_px,points,found,bad
//   report.html    self-contained (inline SVG and CSS, base64 PNG thumbnails, no scripts
//                  beyond a marker): error over time per view, the worst frames with the
//                  contour drawn, the verdict and why
// Thread safety: free functions; MeasureQuality uses the calling TBB arena for views.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
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

// Median and 90th percentile of |values| ignoring NaN; NaN when none is finite.
double AbsPercentile(const std::vector<double>& values, double fraction);

struct ViewFrameQuality {
  double median_px = 0.0;   // NaN when no point found a boundary
  double p90_px = 0.0;      // NaN likewise
  int points = 0;           // contour samples
  int found = 0;            // samples with a boundary
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
  double worst_px = 0.0;           // largest statistic over frames (NaN frames skipped)
  std::vector<int> worst_frames;   // frame indices, worst first
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

// `text` with & < > " ' escaped for HTML.
std::string HtmlEscape(const std::string& text);

}  // namespace bcot
