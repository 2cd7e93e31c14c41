#include "bcot/capture/calibration_options.h"

#include <fmt/format.h>

#include "bcot/core/yaml_util.h"
#include "config_util.h"

namespace bcot {

using capture_internal::ParseSection;

Status CalibrationOptions::Validate() const {
  capture_internal::Violations v;
  v.InRange("board.inner_corners_x", board.inner_corners_x, 2, 100);
  v.InRange("board.inner_corners_y", board.inner_corners_y, 2, 100);
  v.Positive("board.square_size_mm", board.square_size_mm);
  if (input.images_dir.empty()) v.Add("input.images_dir", "\"\"", "must name a folder of images");
  if (input.cameras.empty()) v.Add("input.cameras", "[]", "must list at least one camera");
  v.CameraNames("input.cameras", input.cameras);
  v.InRange("detection.subpixel_half_window_px", detection.subpixel_half_window_px, 1, 50);
  v.Positive("outliers.max_rms_px", outliers.max_rms_px);
  return v.ToStatus("calibration options");
}

StatusOr<CalibrationOptions> ParseCalibrationOptions(const YAML::Node& root_node,
                                                     const std::string& source_name,
                                                     const std::string& base_dir) {
  CalibrationOptions o;
  if (root_node.IsDefined() && !root_node.IsNull()) {
    YamlMap root(root_node, source_name, "", StatusCode::kInvalidConfig);
    BCOT_RETURN_IF_ERROR(root.Check());
    BCOT_RETURN_IF_ERROR(ParseSection(root, "board", [&](YamlMap& m) -> Status {
      BCOT_RETURN_IF_ERROR(m.GetOptional("inner_corners_x", &o.board.inner_corners_x));
      BCOT_RETURN_IF_ERROR(m.GetOptional("inner_corners_y", &o.board.inner_corners_y));
      return m.GetOptional("square_size_mm", &o.board.square_size_mm);
    }));
    BCOT_RETURN_IF_ERROR(ParseSection(root, "input", [&](YamlMap& m) -> Status {
      BCOT_RETURN_IF_ERROR(m.GetOptional("images_dir", &o.input.images_dir));
      o.input.images_dir = capture_internal::ResolveConfigPath(base_dir, o.input.images_dir);
      return m.GetOptional("cameras", &o.input.cameras);
    }));
    BCOT_RETURN_IF_ERROR(ParseSection(root, "detection", [&](YamlMap& m) -> Status {
      auto& d = o.detection;
      BCOT_RETURN_IF_ERROR(m.GetOptional("subpixel_half_window_px", &d.subpixel_half_window_px));
      BCOT_RETURN_IF_ERROR(m.GetOptional("adaptive_threshold", &d.adaptive_threshold));
      return m.GetOptional("fast_check", &d.fast_check);
    }));
    BCOT_RETURN_IF_ERROR(ParseSection(root, "model", [&](YamlMap& m) -> Status {
      BCOT_RETURN_IF_ERROR(m.GetOptional("fix_k3", &o.model.fix_k3));
      BCOT_RETURN_IF_ERROR(m.GetOptional("zero_tangential", &o.model.zero_tangential));
      return m.GetOptional("fix_aspect_ratio", &o.model.fix_aspect_ratio);
    }));
    BCOT_RETURN_IF_ERROR(ParseSection(root, "outliers", [&](YamlMap& m) -> Status {
      BCOT_RETURN_IF_ERROR(m.GetOptional("max_rms_px", &o.outliers.max_rms_px));
      return m.GetOptional("drop", &o.outliers.drop);
    }));
    BCOT_RETURN_IF_ERROR(root.CheckNoUnknownKeys());
  }
  return capture_internal::Validated(std::move(o), source_name);
}

StatusOr<CalibrationOptions> ReadCalibrationOptions(const std::string& path,
                                                    const std::vector<std::string>& overrides) {
  return capture_internal::ReadOptions<CalibrationOptions>(path, overrides,
                                                           ParseCalibrationOptions);
}

std::string FormatCalibrationOptions(const CalibrationOptions& o) {
  const auto b = [](bool value) { return value ? "true" : "false"; };
  std::vector<std::string> cameras;
  for (const std::string& name : o.input.cameras) cameras.push_back(FormatYamlString(name));
  std::string y = "# bcot calibrate: fully resolved options (bcot " BCOT_VERSION ")\n";
  y += fmt::format("board:\n  inner_corners_x: {}\n  inner_corners_y: {}\n  square_size_mm: {}\n",
                   o.board.inner_corners_x, o.board.inner_corners_y, o.board.square_size_mm);
  y += fmt::format("input:\n  images_dir: {}\n  cameras: [{}]\n",
                   FormatYamlString(o.input.images_dir), fmt::join(cameras, ", "));
  y += fmt::format(
      "detection:\n  subpixel_half_window_px: {}\n  adaptive_threshold: {}\n  fast_check: {}\n",
      o.detection.subpixel_half_window_px, b(o.detection.adaptive_threshold),
      b(o.detection.fast_check));
  y += fmt::format("model:\n  fix_k3: {}\n  zero_tangential: {}\n  fix_aspect_ratio: {}\n",
                   b(o.model.fix_k3), b(o.model.zero_tangential), b(o.model.fix_aspect_ratio));
  y += fmt::format("outliers:\n  max_rms_px: {}\n  drop: {}\n", o.outliers.max_rms_px,
                   b(o.outliers.drop));
  return y;
}

}  // namespace bcot
