// Options of the quality measurement and verdict (the `quality:` section of the annotate
// config); what each step does is described in bcot/quality/quality_report.h.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "bcot/core/option_schema.h"
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
  // Below this fraction of contour points with a usable boundary, the frame-view cannot be
  // verified ("cannot tell"); in [0, 1]. 0 = no such floor: the statistic's σ already grows
  // where the usable points leave part of the contour unconstrained (the prediction σ of the
  // rigid-motion fit), so a small object with a usable boundary on 40 % of its contour all
  // around can be told, and one seen on two sides only cannot.
  double min_found_fraction = 0.0;
  // A view may be unverifiable on at most this fraction of frames (the sequence is rejected
  // otherwise: its annotation cannot be checked); in [0, 1].
  double allowed_unverified_fraction = 0.25;
  // Step 3b: move each boundary to the centre of the image's blurred step near it (see
  // RefineOffsetsOnEdges), discarding points without a visible edge. false = the colour
  // posterior's step alone.
  bool refine_on_edges = true;
  // The image edge is looked for within ± this of the step-3 boundary (px); > 0.
  double edge_search_px = 2.0;
  // Smallest edge step in units of its profile fit's residual standard deviation; >= 0.
  double edge_min_snr = 4.0;
  // Step 4b: the model's interior edges at the pose under test (its creases sharper than
  // crease_min_angle_deg and its occlusion contours) are steps in the image of their own. A
  // boundary found nearer to such an edge than to its contour point is more likely that edge
  // than the silhouette (the rim of a flange a few px inside a spool's silhouette whose side
  // has no contrast against the background), so it is dropped as ambiguous
  // (DropInteriorEdgeMatches).
  bool interior_edges = true;
  // A found boundary is taken for an interior edge within this distance of it (px), when it
  // lies nearer to that edge than to its own contour point; > 0.
  double interior_edge_px = 1.0;
  // In (0, 180); the edge stage's edge.crease_min_angle_deg.
  double crease_min_angle_deg = 60.0;
  // Bootstrap resamples of the contour points for the uncertainty σ of the judged statistic
  // (statistic_sigma_px; the fit's prediction σ is added to it); 0 = none, else >= 2.
  int bootstrap_resamples = 32;
  // A frame-view is bad when its statistic − confidence_z·σ exceeds threshold_px, good when its
  // statistic + confidence_z·σ does not, and cannot be told in between (the measurement cannot
  // decide); 0 = compare the statistic alone; >= 0.
  double confidence_z = 2.0;
  // Spacing of the contour samples (px); in [0.05, 1000].
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
  double fit_scale_px = 0.5;
  // Worst frames per view shown as thumbnails in report.html; >= 0.
  int worst_frames = 4;
  // Longest side of a thumbnail (px); >= 32.
  int thumbnail_px = 320;

  // Lists every violation ("quality.key = value, rule") in one kInvalidConfig status: the
  // rules of QualityOptionSchema().
  Status Validate() const;
};

// The declaration of every option above: the `quality:` section of the annotate config (keys
// spelled as the fields, "quality.threshold_px"). Built once.
const OptionSchema<QualityOptions>& QualityOptionSchema();

const char* QualityStatisticName(QualityStatistic statistic);

// The contour sampling of the quality measurement (one point every sample_spacing_px).
ContourOptions QualityContourOptions(const QualityOptions& options);

// The `quality:` YAML section `node` (may be undefined: defaults kept), by QualityOptionSchema:
// unknown keys, wrong types and out-of-range values are kInvalidConfig errors naming
// file:line: quality.key.
Status ParseQualityOptions(const YAML::Node& node, const std::string& source_name,
                           QualityOptions* options);
// The section as YAML lines ("quality:\n  threshold_px: 2\n..."), readable by the parser.
std::string FormatQualityOptions(const QualityOptions& options);

}  // namespace bcot
