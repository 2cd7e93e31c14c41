#include "bcot/annotate/annotate_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bcot/core/yaml_util.h"

namespace bcot {

Status AnnotateOptions::Validate() const {
  std::vector<std::string> violations;
  const Status tracker_status = tracker.Validate();
  if (!tracker_status.ok()) violations.push_back(tracker_status.message());
  const Status window_status = window.Validate();
  if (!window_status.ok()) violations.push_back(window_status.message());
  if (!views.weights.empty() && !views.cameras.empty() &&
      views.weights.size() != views.cameras.size()) {
    violations.push_back(fmt::format("views: weights has {} entries for {} cameras",
                                     views.weights.size(), views.cameras.size()));
  }
  for (size_t i = 0; i < views.weights.size(); ++i) {
    if (!(views.weights[i] >= 0.0) || !std::isfinite(views.weights[i])) {
      violations.push_back(
          fmt::format("views: weights[{}] = {}, must be finite and >= 0", i, views.weights[i]));
    }
  }
  for (size_t i = 0; i < views.cameras.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (views.cameras[i] == views.cameras[j]) {
        violations.push_back(fmt::format("views: camera '{}' is listed twice", views.cameras[i]));
      }
    }
  }
  const Status quality_status = quality.Validate();
  if (!quality_status.ok()) violations.push_back(quality_status.message());
  if (violations.empty()) return Status::Ok();
  std::string message = violations[0];
  for (size_t i = 1; i < violations.size(); ++i) message += "; " + violations[i];
  return Status::InvalidConfig(message);
}

namespace {

const char* FormName(RegionResidualForm form) {
  return form == RegionResidualForm::kIrls ? "irls" : "sqrt_energy";
}
const char* KindName(ColorModelKind kind) {
  return kind == ColorModelKind::kLocal ? "local" : "global";
}

// Re-reports the violations of a section's Validate() ("context: field = value, rule; ...") at
// the line of the key each one is about, as "file:line: section.key = value, rule".
Status LocateViolations(const Status& status, const YamlMap& map) {
  if (status.ok()) return status;
  std::vector<std::string> located;
  std::string rest = status.message();
  while (!rest.empty()) {
    const size_t end = rest.find("; ");
    std::string piece = rest.substr(0, end);
    rest = end == std::string::npos ? "" : rest.substr(end + 2);
    // Drop "context: " prefixes up to the "field = ..." part.
    const size_t equals = piece.find(" = ");
    if (equals != std::string::npos) {
      const size_t colon = piece.rfind(": ", equals);
      if (colon != std::string::npos) piece = piece.substr(colon + 2);
    }
    const std::string field = piece.substr(0, piece.find(" = "));
    std::string key = field;
    for (const auto& entry : map.node()) {
      const std::string candidate = entry.first.as<std::string>();
      if (candidate == field || (candidate.size() > field.size() &&
                                 candidate.compare(candidate.size() - field.size() - 1,
                                                   std::string::npos, "_" + field) == 0)) {
        key = candidate;
        break;
      }
    }
    const std::string value_and_rule = piece.substr(field.size());
    located.push_back(
        fmt::format("{}: {}.{}{}", map.Location(key), map.path(), key, value_and_rule));
  }
  std::string message = located[0];
  for (size_t i = 1; i < located.size(); ++i) message += "; " + located[i];
  return Status::InvalidConfig(message);
}

// Runs `parse` on root[section] when present, rejects unknown keys, then re-reports the
// section's validation errors at their lines.
Status ParseSection(YamlMap& root, const std::string& section,
                    const std::function<Status(YamlMap&)>& parse,
                    const std::function<Status()>& validate) {
  if (!root.Has(section)) return Status::Ok();
  YamlMap map(root.Node(section), root.source_name(), section, StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.Check());
  BCOT_RETURN_IF_ERROR(parse(map));
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  return LocateViolations(validate(), map);
}

Status ParseInto(const YAML::Node& root_node, const std::string& source_name, AnnotateOptions* o) {
  if (!root_node.IsDefined() || root_node.IsNull()) return Status::Ok();
  YamlMap root(root_node, source_name, "", StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(root.Check());
  FrameProblemOptions& frame = o->tracker.frame;

  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "frame",
      [&](YamlMap& m) -> Status {
        BCOT_RETURN_IF_ERROR(m.GetOptional("rounds", &frame.rounds));
        BCOT_RETURN_IF_ERROR(m.GetOptional("iterations", &frame.iterations));
        BCOT_RETURN_IF_ERROR(m.GetOptional("pyramid_levels", &frame.pyramid_levels));
        BCOT_RETURN_IF_ERROR(m.GetOptional("coarse_rounds", &frame.coarse_rounds));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("damping_translation_mm", &frame.damping_translation_mm));
        BCOT_RETURN_IF_ERROR(m.GetOptional("damping_rotation_deg", &frame.damping_rotation_deg));
        BCOT_RETURN_IF_ERROR(m.GetOptional("round_tolerance_deg", &frame.round_tolerance_deg));
        BCOT_RETURN_IF_ERROR(m.GetOptional("round_tolerance_mm", &frame.round_tolerance_mm));
        return m.GetOptional("num_threads", &frame.num_threads);
      },
      [&] {
        FrameProblemOptions own = frame;  // this section's fields only
        own.region = RegionTemplateOptions();
        own.cost = RegionCostOptions();
        own.energy = RegionEnergy::kDense;
        own.lines = CorrespondenceLineOptions();
        own.edge = EdgeRefineOptions();
        return own.Validate();
      }));

  RegionTemplateOptions& region = frame.region;
  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "region",
      [&](YamlMap& m) -> Status {
        BCOT_RETURN_IF_ERROR(m.GetOptional("band_px", &region.band_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("stride_px", &region.stride_px));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("contour_sample_spacing_px", &region.contour.sample_spacing_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("contour_precision_px", &region.contour.precision_px));
        return m.GetOptional("contour_coarse_step_px", &region.contour.coarse_step_px);
      },
      [&] { return region.Validate(); }));

  RegionCostOptions& cost = frame.cost;
  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "cost",
      [&](YamlMap& m) -> Status {
        int form = static_cast<int>(cost.form);
        BCOT_RETURN_IF_ERROR(m.GetOptionalChoice("form", {"sqrt_energy", "irls"}, &form));
        cost.form = static_cast<RegionResidualForm>(form);
        BCOT_RETURN_IF_ERROR(m.GetOptional("heaviside_slope", &cost.heaviside_slope));
        int energy = static_cast<int>(frame.energy);
        BCOT_RETURN_IF_ERROR(
            m.GetOptionalChoice("energy", {"dense", "sparse", "combined"}, &energy));
        frame.energy = static_cast<RegionEnergy>(energy);
        return m.GetOptional("probability_floor", &cost.probability_floor);
      },
      [&] { return cost.Validate(); }));

  CorrespondenceLineOptions& lines = frame.lines;
  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "lines",
      [&](YamlMap& m) -> Status {
        BCOT_RETURN_IF_ERROR(m.GetOptional("num_lines", &lines.num_lines));
        BCOT_RETURN_IF_ERROR(m.GetOptional("scale_px", &lines.scale_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("half_length_px", &lines.half_length_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("min_side_px", &lines.min_side_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("slope_px", &lines.slope_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("amplitude", &lines.amplitude));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("hypothesis_subdivisions", &lines.hypothesis_subdivisions));
        BCOT_RETURN_IF_ERROR(m.GetOptional("min_sigma_px", &lines.min_sigma_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("max_sigma_px", &lines.max_sigma_px));
        return m.GetOptional("weight", &lines.weight);
      },
      [&] { return lines.Validate(); }));

  EdgeRefineOptions& edge = frame.edge;
  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "edge",
      [&](YamlMap& m) -> Status {
        BCOT_RETURN_IF_ERROR(m.GetOptional("enabled", &edge.enabled));
        BCOT_RETURN_IF_ERROR(m.GetOptional("rounds", &edge.rounds));
        BCOT_RETURN_IF_ERROR(m.GetOptional("iterations", &edge.iterations));
        BCOT_RETURN_IF_ERROR(m.GetOptional("robust_scale", &edge.robust_scale));
        BCOT_RETURN_IF_ERROR(m.GetOptional("num_lines", &edge.lines.num_lines));
        BCOT_RETURN_IF_ERROR(m.GetOptional("search_px", &edge.lines.search_px));
        return m.GetOptional("min_sigma_px", &edge.lines.min_sigma_px);
      },
      [&] { return edge.Validate(); }));

  ColorModelOptions& color = o->tracker.color;
  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "color",
      [&](YamlMap& m) -> Status {
        int kind = static_cast<int>(color.kind);
        BCOT_RETURN_IF_ERROR(m.GetOptionalChoice("kind", {"global", "local"}, &kind));
        color.kind = static_cast<ColorModelKind>(kind);
        int refine_kind =
            color.refine_kind.has_value() ? 1 + static_cast<int>(*color.refine_kind) : 0;
        BCOT_RETURN_IF_ERROR(
            m.GetOptionalChoice("refine_kind", {"same", "global", "local"}, &refine_kind));
        if (refine_kind == 0) {
          color.refine_kind.reset();
        } else {
          color.refine_kind = static_cast<ColorModelKind>(refine_kind - 1);
        }
        BCOT_RETURN_IF_ERROR(m.GetOptional("bins_per_channel", &color.bins_per_channel));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("learning_rate_foreground", &color.learning_rate_foreground));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("learning_rate_background", &color.learning_rate_background));
        BCOT_RETURN_IF_ERROR(m.GetOptional("background_band_px", &color.background_band_px));
        BCOT_RETURN_IF_ERROR(m.GetOptional("sample_margin_px", &color.sample_margin_px));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("local_region_radius_px", &color.local_region_radius_px));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("local_region_spacing_px", &color.local_region_spacing_px));
        return m.GetOptional("local_anchor_fraction", &color.local_anchor_fraction);
      },
      [&] { return color.Validate(); }));

  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "tracker",
      [&](YamlMap& m) -> Status {
        BCOT_RETURN_IF_ERROR(m.GetOptional("velocity_prediction", &o->tracker.velocity_prediction));
        BCOT_RETURN_IF_ERROR(m.GetOptional("bootstrap_passes", &o->tracker.bootstrap_passes));
        BCOT_RETURN_IF_ERROR(
            m.GetOptional("bootstrap_converged_deg", &o->tracker.bootstrap_converged_deg));
        return m.GetOptional("bootstrap_converged_mm", &o->tracker.bootstrap_converged_mm);
      },
      [&]() -> Status {
        MultiViewTrackerOptions own;  // this section's fields only
        own.velocity_prediction = o->tracker.velocity_prediction;
        own.bootstrap_passes = o->tracker.bootstrap_passes;
        own.bootstrap_converged_deg = o->tracker.bootstrap_converged_deg;
        own.bootstrap_converged_mm = o->tracker.bootstrap_converged_mm;
        return own.Validate();
      }));

  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "views",
      [&](YamlMap& m) -> Status {
        BCOT_RETURN_IF_ERROR(m.GetOptional("cameras", &o->views.cameras));
        return m.GetOptional("weights", &o->views.weights);
      },
      [&] {
        AnnotateOptions own;
        own.views = o->views;
        return own.Validate();
      }));

  WindowProblemOptions& window = o->window;
  BCOT_RETURN_IF_ERROR(ParseSection(
      root, "window",
      [&](YamlMap& m) -> Status {
        BCOT_RETURN_IF_ERROR(m.GetOptional("enabled", &window.enabled));
        BCOT_RETURN_IF_ERROR(m.GetOptional("size", &window.size));
        BCOT_RETURN_IF_ERROR(m.GetOptional("overlap", &window.overlap));
        BCOT_RETURN_IF_ERROR(m.GetOptional("iterations", &window.iterations));
        int prior = static_cast<int>(window.prior);
        BCOT_RETURN_IF_ERROR(m.GetOptionalChoice("prior", {"se3", "decoupled"}, &prior));
        window.prior = static_cast<MotionPriorForm>(prior);
        for (auto [key, model] : {std::pair{"translation_model", &window.translation_model},
                                  std::pair{"rotation_model", &window.rotation_model}}) {
          int value = static_cast<int>(*model);
          BCOT_RETURN_IF_ERROR(m.GetOptionalChoice(key, {"velocity", "acceleration"}, &value));
          *model = static_cast<MotionModel>(value);
        }
        for (auto [key, axes] : {std::pair{"rotation_sigma_deg", &window.rotation_sigma_deg},
                                 std::pair{"translation_sigma_mm", &window.translation_sigma_mm}}) {
          if (!m.Has(key)) continue;
          std::vector<double> values;
          BCOT_RETURN_IF_ERROR(m.Get(key, &values));
          if (values.size() != 3) {
            return m.Error(key, fmt::format("has {} values, expected 3 (x, y, z)", values.size()));
          }
          std::copy(values.begin(), values.end(), axes->begin());
        }
        BCOT_RETURN_IF_ERROR(m.GetOptional("robust_translation_mm", &window.robust_translation_mm));
        BCOT_RETURN_IF_ERROR(m.GetOptional("robust_rotation_deg", &window.robust_rotation_deg));
        return m.GetOptional("num_threads", &window.num_threads);
      },
      [&] { return window.Validate(); }));
  if (root.Has("quality")) {
    BCOT_RETURN_IF_ERROR(ParseQualityOptions(root.Node("quality"), source_name, &o->quality));
  }
  return root.CheckNoUnknownKeys();
}

std::string Quote(const std::string& text) { return FormatYamlString(text); }

template <typename T, typename Format>
std::string List(const std::vector<T>& values, Format format) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) text += (i > 0 ? ", " : "") + format(values[i]);
  return text + "]";
}

}  // namespace

StatusOr<AnnotateOptions> ParseAnnotateOptions(const YAML::Node& root,
                                               const std::string& source_name) {
  AnnotateOptions options;
  const Status status = ParseInto(root, source_name, &options);
  if (!status.ok()) return Status::InvalidConfig(status.message());
  // Sections were validated one by one; this catches what spans sections.
  const Status whole = options.Validate();
  if (!whole.ok()) return Status::InvalidConfig(source_name + ": " + whole.message());
  return options;
}

StatusOr<AnnotateOptions> ReadAnnotateOptions(const std::string& path,
                                              const std::vector<std::string>& overrides) {
  YAML::Node node(YAML::NodeType::Map);
  if (!path.empty()) {
    if (!std::filesystem::exists(path)) {
      return Status::InvalidConfig(fmt::format("{}: config file not found", path));
    }
    StatusOr<YAML::Node> root = LoadYamlFile(path, StatusCode::kInvalidConfig);
    if (!root.ok()) return Status::InvalidConfig(root.status().message());
    node = *root;
  }
  if (!overrides.empty()) {
    if (!node.IsDefined() || node.IsNull()) node = YAML::Node(YAML::NodeType::Map);
    const Status status = ApplyYamlOverrides(overrides, &node);
    if (!status.ok()) return Status::InvalidConfig(status.message());
  }
  return ParseAnnotateOptions(node, path.empty() ? "--set" : path);
}

std::string FormatAnnotateOptions(const AnnotateOptions& o) {
  const FrameProblemOptions& f = o.tracker.frame;
  const ColorModelOptions& c = o.tracker.color;
  std::string y;
  auto section = [&y](const std::string& name) { y += name + ":\n"; };
  auto line = [&y](const std::string& key, const std::string& value) {
    y += "  " + key + ": " + value + "\n";
  };
  auto number = [](double value) { return fmt::format("{}", value); };
  section("frame");
  line("rounds", number(f.rounds));
  line("iterations", number(f.iterations));
  line("pyramid_levels", number(f.pyramid_levels));
  line("coarse_rounds", number(f.coarse_rounds));
  line("damping_translation_mm", number(f.damping_translation_mm));
  line("damping_rotation_deg", number(f.damping_rotation_deg));
  line("round_tolerance_deg", number(f.round_tolerance_deg));
  line("round_tolerance_mm", number(f.round_tolerance_mm));
  line("num_threads", number(f.num_threads));
  section("region");
  line("band_px", number(f.region.band_px));
  line("stride_px", number(f.region.stride_px));
  line("contour_sample_spacing_px", number(f.region.contour.sample_spacing_px));
  line("contour_precision_px", number(f.region.contour.precision_px));
  line("contour_coarse_step_px", number(f.region.contour.coarse_step_px));
  section("cost");
  line("form", FormName(f.cost.form));
  line("heaviside_slope", number(f.cost.heaviside_slope));
  line("probability_floor", number(f.cost.probability_floor));
  line("energy", RegionEnergyName(f.energy));
  section("lines");
  line("num_lines", number(f.lines.num_lines));
  line("scale_px", number(f.lines.scale_px));
  line("half_length_px", number(f.lines.half_length_px));
  line("min_side_px", number(f.lines.min_side_px));
  line("slope_px", number(f.lines.slope_px));
  line("amplitude", number(f.lines.amplitude));
  line("hypothesis_subdivisions", number(f.lines.hypothesis_subdivisions));
  line("min_sigma_px", number(f.lines.min_sigma_px));
  line("max_sigma_px", number(f.lines.max_sigma_px));
  line("weight", number(f.lines.weight));
  section("edge");
  line("enabled", f.edge.enabled ? "true" : "false");
  line("rounds", number(f.edge.rounds));
  line("iterations", number(f.edge.iterations));
  line("robust_scale", number(f.edge.robust_scale));
  line("num_lines", number(f.edge.lines.num_lines));
  line("search_px", number(f.edge.lines.search_px));
  line("min_sigma_px", number(f.edge.lines.min_sigma_px));
  section("color");
  line("kind", KindName(c.kind));
  line("refine_kind", c.refine_kind.has_value() ? KindName(*c.refine_kind) : "same");
  line("bins_per_channel", number(c.bins_per_channel));
  line("learning_rate_foreground", number(c.learning_rate_foreground));
  line("learning_rate_background", number(c.learning_rate_background));
  line("background_band_px", number(c.background_band_px));
  line("sample_margin_px", number(c.sample_margin_px));
  line("local_region_radius_px", number(c.local_region_radius_px));
  line("local_region_spacing_px", number(c.local_region_spacing_px));
  line("local_anchor_fraction", number(c.local_anchor_fraction));
  section("tracker");
  line("velocity_prediction", number(o.tracker.velocity_prediction));
  line("bootstrap_passes", number(o.tracker.bootstrap_passes));
  line("bootstrap_converged_deg", number(o.tracker.bootstrap_converged_deg));
  line("bootstrap_converged_mm", number(o.tracker.bootstrap_converged_mm));
  section("views");
  line("cameras", List(o.views.cameras, Quote));
  line("weights", List(o.views.weights, number));
  const WindowProblemOptions& w = o.window;
  section("window");
  line("enabled", w.enabled ? "true" : "false");
  line("size", number(w.size));
  line("overlap", number(w.overlap));
  line("iterations", number(w.iterations));
  line("prior", w.prior == MotionPriorForm::kSe3 ? "se3" : "decoupled");
  for (auto [key, model] : {std::pair{"translation_model", w.translation_model},
                            std::pair{"rotation_model", w.rotation_model}}) {
    line(key, model == MotionModel::kConstantVelocity ? "velocity" : "acceleration");
  }
  line("rotation_sigma_deg",
       List(std::vector<double>(w.rotation_sigma_deg.begin(), w.rotation_sigma_deg.end()), number));
  line("translation_sigma_mm",
       List(std::vector<double>(w.translation_sigma_mm.begin(), w.translation_sigma_mm.end()),
            number));
  line("robust_translation_mm", number(w.robust_translation_mm));
  line("robust_rotation_deg", number(w.robust_rotation_deg));
  line("num_threads", number(w.num_threads));
  return y + FormatQualityOptions(o.quality);
}

}  // namespace bcot
