#include "bcot/quality/quality_options.h"

#include <fmt/format.h>

#include "bcot/core/yaml_util.h"

namespace bcot {
const char* QualityStatisticName(QualityStatistic statistic) {
  return statistic == QualityStatistic::kMedian ? "median" : "p90";
}

ContourOptions QualityContourOptions(const QualityOptions& options) {
  ContourOptions contour;
  contour.sample_spacing_px = options.sample_spacing_px;
  return contour;
}

namespace {

OptionSchema<QualityOptions>* BuildQualityOptionSchema() {
  using O = QualityOptions;
  auto* s = new OptionSchema<O>();
  s->Add(
       "quality.threshold_px", [](auto& o) -> auto& { return o.threshold_px; }, "px",
       "a frame-view is bad when its statistic exceeds this (capture resolution)")
      .Range(Positive());
  s->AddChoice(
      "quality.statistic", [](auto& o) -> auto& { return o.statistic; },
      std::vector<std::pair<std::string, QualityStatistic>>{{"median", QualityStatistic::kMedian},
                                                            {"p90", QualityStatistic::kP90}},
      "per frame-view statistic of the offsets compared with threshold_px");
  s->Add(
       "quality.allowed_bad_fraction", [](auto& o) -> auto& { return o.allowed_bad_fraction; }, "",
       "a view may be bad on at most this fraction of frames")
      .Range(Closed(0, 1));
  s->Add(
       "quality.search_radius_px", [](auto& o) -> auto& { return o.search_radius_px; }, "px",
       "boundary search along each contour normal, within ± this")
      .Range(Positive());
  s->Add(
       "quality.step_window_px", [](auto& o) -> auto& { return o.step_window_px; }, "px",
       "half-width of the step detector on the P_f profile")
      .Range(Positive());
  s->Add(
       "quality.edge_weight", [](auto& o) -> auto& { return o.edge_weight; }, "",
       "weight of the image RGB edge in the boundary score (0 = colour posteriors only)")
      .Range(Closed(0, 10));
  s->Add(
       "quality.min_contrast", [](auto& o) -> auto& { return o.min_contrast; }, "",
       "minimum score for a boundary to count as found")
      .Check([](const O& o) {
        return o.min_contrast > 0 && o.min_contrast < 1 + o.edge_weight
                   ? ""
                   : "must be in (0, 1 + edge_weight)";
      });
  s->Add(
       "quality.min_found_fraction", [](auto& o) -> auto& { return o.min_found_fraction; }, "",
       "below this fraction of contour points with a usable boundary the frame-view cannot be "
       "verified (0: no floor; the statistic's σ covers what the usable points leave unseen)")
      .Range(Closed(0, 1));
  s->Add(
       "quality.allowed_unverified_fraction",
       [](auto& o) -> auto& { return o.allowed_unverified_fraction; }, "",
       "a view may be unverifiable on at most this fraction of frames")
      .Range(Closed(0, 1));
  s->Add(
      "quality.refine_on_edges", [](auto& o) -> auto& { return o.refine_on_edges; }, "",
      "move each boundary to the centre of the image's blurred step near it");
  s->Add(
       "quality.edge_search_px", [](auto& o) -> auto& { return o.edge_search_px; }, "px",
       "the image edge is looked for within this of the posterior's boundary")
      .Range(Positive());
  s->Add(
       "quality.edge_min_snr", [](auto& o) -> auto& { return o.edge_min_snr; }, "",
       "smallest edge step in units of the profile fit's noise")
      .Range(NonNegative());
  s->Add(
      "quality.interior_edges", [](auto& o) -> auto& { return o.interior_edges; }, "",
      "drop boundaries found on the model's own creases or occlusion contours instead of near "
      "its silhouette");
  s->Add(
       "quality.interior_edge_px", [](auto& o) -> auto& { return o.interior_edge_px; }, "px",
       "... a boundary within this of such an edge and nearer to it than to the silhouette")
      .Range(Positive());
  s->Add(
       "quality.crease_min_angle_deg", [](auto& o) -> auto& { return o.crease_min_angle_deg; },
       "deg", "an interior crease: an edge whose two faces' normals differ by more than this")
      .Range(Open(0.0, 180.0));
  s->Add(
       "quality.bootstrap_resamples", [](auto& o) -> auto& { return o.bootstrap_resamples; }, "",
       "bootstrap resamples for the uncertainty of the statistic (0 = none)")
      .Check([](const O& o) {
        return o.bootstrap_resamples == 0 || o.bootstrap_resamples >= 2 ? "" : "must be 0 or >= 2";
      });
  s->Add(
       "quality.confidence_z", [](auto& o) -> auto& { return o.confidence_z; }, "",
       "bad when statistic − z·σ > threshold, good when statistic + z·σ <= threshold, else "
       "cannot tell")
      .Range(NonNegative());
  s->Add(
       "quality.sample_spacing_px", [](auto& o) -> auto& { return o.sample_spacing_px; }, "px",
       "spacing of the contour samples")
      .Range(Closed(0.05, 1000));
  s->Add(
       "quality.bins_per_channel", [](auto& o) -> auto& { return o.bins_per_channel; }, "",
       "colour histogram bins per channel of the boundary model")
      .Check([](const O& o) {
        const int bins = o.bins_per_channel;
        return bins >= 1 && bins <= 256 && 256 % bins == 0 ? "" : "must divide 256";
      });
  s->AddChoice(
      "quality.color_kind", [](auto& o) -> auto& { return o.color_kind; },
      std::vector<std::pair<std::string, ColorModelKind>>{{"global", ColorModelKind::kGlobal},
                                                          {"local", ColorModelKind::kLocal}},
      "colour model of the boundary search (local: histograms along the contour)");
  s->Add(
       "quality.color_margin_px", [](auto& o) -> auto& { return o.color_margin_px; }, "px",
       "the colour model learns from no pixel this close to the contour")
      .Check([](const O& o) {
        return o.color_margin_px >= 0 && o.color_margin_px < o.search_radius_px
                   ? ""
                   : "must be in [0, search_radius_px)";
      });
  s->Add(
      "quality.fit_rigid_motion", [](auto& o) -> auto& { return o.fit_rigid_motion; }, "",
      "judge the offsets of one rigid motion robustly fitted to the boundary offsets");
  s->Add(
       "quality.fit_scale_px", [](auto& o) -> auto& { return o.fit_scale_px; }, "px",
       "scale of the robust fit (Huber threshold, Tukey's at 3x)")
      .Range(Positive());
  s->Add(
       "quality.worst_frames", [](auto& o) -> auto& { return o.worst_frames; }, "",
       "worst frames per view shown as thumbnails in report.html")
      .Range(NonNegative());
  s->Add(
       "quality.thumbnail_px", [](auto& o) -> auto& { return o.thumbnail_px; }, "px",
       "longest side of a thumbnail")
      .Range(AtLeast(32));
  return s;
}

}  // namespace

const OptionSchema<QualityOptions>& QualityOptionSchema() {
  static const OptionSchema<QualityOptions>* const schema = BuildQualityOptionSchema();
  return *schema;
}

Status QualityOptions::Validate() const { return QualityOptionSchema().Validate(*this, nullptr); }

Status ParseQualityOptions(const YAML::Node& node, const std::string& source_name,
                           QualityOptions* options) {
  if (!node.IsDefined() || node.IsNull()) return Status::Ok();
  YAML::Node root(YAML::NodeType::Map);
  root["quality"] = node;  // shares the node: its line marks stay
  OptionSources sources;
  const OptionSchema<QualityOptions>& schema = QualityOptionSchema();
  BCOT_RETURN_IF_ERROR(schema.Parse(root, source_name, "", options, &sources));
  return schema.Validate(*options, &sources);
}

std::string FormatQualityOptions(const QualityOptions& options) {
  return QualityOptionSchema().Emit(options);
}

}  // namespace bcot
