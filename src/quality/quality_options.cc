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

Status QualityOptions::Validate() const {
  std::vector<std::string> violations;
  auto require = [&](bool ok, const std::string& field, double value, const char* rule) {
    if (!ok) violations.push_back(fmt::format("{} = {}, {}", field, value, rule));
  };
  require(threshold_px > 0, "threshold_px", threshold_px, "must be > 0");
  require(allowed_bad_fraction >= 0 && allowed_bad_fraction <= 1, "allowed_bad_fraction",
          allowed_bad_fraction, "must be in [0, 1]");
  require(search_radius_px > 0, "search_radius_px", search_radius_px, "must be > 0");
  require(step_window_px > 0, "step_window_px", step_window_px, "must be > 0");
  require(edge_weight >= 0 && edge_weight <= 10, "edge_weight", edge_weight, "must be in [0, 10]");
  require(min_contrast > 0 && min_contrast < 1 + edge_weight, "min_contrast", min_contrast,
          "must be in (0, 1 + edge_weight)");
  require(min_found_fraction >= 0 && min_found_fraction <= 1, "min_found_fraction",
          min_found_fraction, "must be in [0, 1]");
  require(sample_spacing_px > 0, "sample_spacing_px", sample_spacing_px, "must be > 0");
  require(bins_per_channel >= 1 && bins_per_channel <= 256 && 256 % bins_per_channel == 0,
          "bins_per_channel", bins_per_channel, "must divide 256");
  require(color_margin_px >= 0 && color_margin_px < search_radius_px, "color_margin_px",
          color_margin_px, "must be in [0, search_radius_px)");
  require(fit_scale_px > 0, "fit_scale_px", fit_scale_px, "must be > 0");
  require(worst_frames >= 0, "worst_frames", worst_frames, "must be >= 0");
  require(thumbnail_px >= 32, "thumbnail_px", thumbnail_px, "must be >= 32");
  if (violations.empty()) return Status::Ok();
  std::string message = "quality: " + violations[0];
  for (size_t i = 1; i < violations.size(); ++i) message += "; " + violations[i];
  return Status::InvalidConfig(message);
}

Status ParseQualityOptions(const YAML::Node& node, const std::string& source_name,
                           QualityOptions* options) {
  if (!node.IsDefined() || node.IsNull()) return Status::Ok();
  YamlMap map(node, source_name, "quality", StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.Check());
  QualityOptions& o = *options;
  BCOT_RETURN_IF_ERROR(map.GetOptional("threshold_px", &o.threshold_px));
  int statistic = o.statistic == QualityStatistic::kMedian ? 0 : 1;
  BCOT_RETURN_IF_ERROR(map.GetOptionalChoice("statistic", {"median", "p90"}, &statistic));
  o.statistic = statistic == 0 ? QualityStatistic::kMedian : QualityStatistic::kP90;
  BCOT_RETURN_IF_ERROR(map.GetOptional("allowed_bad_fraction", &o.allowed_bad_fraction));
  BCOT_RETURN_IF_ERROR(map.GetOptional("search_radius_px", &o.search_radius_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("step_window_px", &o.step_window_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("edge_weight", &o.edge_weight));
  BCOT_RETURN_IF_ERROR(map.GetOptional("min_contrast", &o.min_contrast));
  BCOT_RETURN_IF_ERROR(map.GetOptional("min_found_fraction", &o.min_found_fraction));
  BCOT_RETURN_IF_ERROR(map.GetOptional("sample_spacing_px", &o.sample_spacing_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("bins_per_channel", &o.bins_per_channel));
  int color_kind = o.color_kind == ColorModelKind::kGlobal ? 0 : 1;
  BCOT_RETURN_IF_ERROR(map.GetOptionalChoice("color_kind", {"global", "local"}, &color_kind));
  o.color_kind = color_kind == 0 ? ColorModelKind::kGlobal : ColorModelKind::kLocal;
  BCOT_RETURN_IF_ERROR(map.GetOptional("color_margin_px", &o.color_margin_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("fit_rigid_motion", &o.fit_rigid_motion));
  BCOT_RETURN_IF_ERROR(map.GetOptional("fit_scale_px", &o.fit_scale_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("worst_frames", &o.worst_frames));
  BCOT_RETURN_IF_ERROR(map.GetOptional("thumbnail_px", &o.thumbnail_px));
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  const Status status = o.Validate();
  if (status.ok()) return status;
  // Name the line of the first offending key: "file:line: quality.key = value, rule; ...".
  std::string message;
  std::string rest = status.message().substr(std::string("quality: ").size());
  while (!rest.empty()) {
    const size_t end = rest.find("; ");
    const std::string piece = rest.substr(0, end);
    rest = end == std::string::npos ? "" : rest.substr(end + 2);
    const std::string key = piece.substr(0, piece.find(" = "));
    message +=
        (message.empty() ? "" : "; ") + fmt::format("{}: quality.{}", map.Location(key), piece);
  }
  return Status::InvalidConfig(message);
}

std::string FormatQualityOptions(const QualityOptions& o) {
  std::string y = "quality:\n";
  auto line = [&y](const char* key, const std::string& value) {
    y += fmt::format("  {}: {}\n", key, value);
  };
  line("threshold_px", fmt::format("{}", o.threshold_px));
  line("statistic", QualityStatisticName(o.statistic));
  line("allowed_bad_fraction", fmt::format("{}", o.allowed_bad_fraction));
  line("search_radius_px", fmt::format("{}", o.search_radius_px));
  line("step_window_px", fmt::format("{}", o.step_window_px));
  line("edge_weight", fmt::format("{}", o.edge_weight));
  line("min_contrast", fmt::format("{}", o.min_contrast));
  line("min_found_fraction", fmt::format("{}", o.min_found_fraction));
  line("sample_spacing_px", fmt::format("{}", o.sample_spacing_px));
  line("bins_per_channel", fmt::format("{}", o.bins_per_channel));
  line("color_kind", o.color_kind == ColorModelKind::kLocal ? "local" : "global");
  line("color_margin_px", fmt::format("{}", o.color_margin_px));
  line("fit_rigid_motion", o.fit_rigid_motion ? "true" : "false");
  line("fit_scale_px", fmt::format("{}", o.fit_scale_px));
  line("worst_frames", fmt::format("{}", o.worst_frames));
  line("thumbnail_px", fmt::format("{}", o.thumbnail_px));
  return y;
}

}  // namespace bcot
